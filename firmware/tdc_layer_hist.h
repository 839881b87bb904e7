/*
 * tdc_layer_hist.h - exponential history per layer (Zeng et al. eq. 2,
 * alpha = 0.1; eq. 4's alpha^V from the link's falloff weights), the
 * controller's side of what the double-precision reference (sim/zeng/,
 * ref/ref_layer_hist.c) shows the layered path needs: with one reprojected
 * sample and no history (tdc_layers.h), a 1-sample layer stays as noisy as
 * it arrives; eq. 2 averages ~1/alpha frames along the layer's own vectors.
 *
 * Per pixel p of a layer of c channels (1 or 3), each refresh, with the
 * layer's current full frame x (8-bit), its vector m (Q4 px, the previous
 * position is p + m) and optionally the eq. 4 falloff G (Q15):
 *   h   = bilinear sample of the history at p + m (Q8), or none when p + m
 *         leaves the frame;
 *   h*  = h clamped per channel to mu +- k sigma of x's 3x3 neighbourhood
 *         (clipped at the frame edge; k = 0: no clamp, 1: Salvi, 3: Zeng §5);
 *   a   = alpha, or with G: alpha^V = 1 - G (1 - alpha) (eq. 4);
 *   v   = a x + (1 - a) h*   (eq. 2; x alone where there is no h),
 * kept in Q8 as the next history; the output is v rounded to 8 bits.
 *
 * Scaling and overflow:
 *   bilinear: history <= 255 * 256 (Q8) x Q4 x Q4 weights (sum 256), 4 taps
 *     < 2^24, >> 8 -> Q8;
 *   moments: S1 <= 9 * 255, S2 <= 9 * 255^2; n S2 - S1^2 <= n^2 255^2 / 4
 *     < 2^21, << 4 < 2^25 (uint32), / n^2: the variance in Q4 < 2^18,
 *     tdc_sqrt_q8 (table, |error| <= 12 in Q8) >> 2: sigma in Q8 within
 *     0.012 code (an exact isqrt cost 25x the whole step without clamp);
 *   k sigma <= 3 * 2^15 (Q8), bounds clipped to [0, 255 * 256];
 *   alpha^V: (32768 - alpha) G < 2^30, >> 15;
 *   blend: a (<= 2^15) x x << 8 (< 2^16) + (2^15 - a) x h* (< 2^16) < 2^32
 *     (uint32), + 2^14 and >> 15.
 *
 * Memory (caller-owned arena, TDC_LHIST_ARENA): per pixel 5c bytes (two Q8
 * history frames 4c, output c): 15 B/px for a colour layer, 5 for
 * visibility; the four layers of tdc_layers.h together 50 B/px.
 */
#ifndef TDC_LAYER_HIST_H
#define TDC_LAYER_HIST_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_arena.h"
#include "tdc_status.h"

#define TDC_LHIST_MAX_DIM 4096

typedef struct {
    uint16_t width, height; /* 1 .. TDC_LHIST_MAX_DIM */
    uint8_t channels;       /* 1 or 3 */
    uint8_t clamp_k;        /* 0, 1 or 3 */
    uint16_t alpha_q15;     /* eq. 2's alpha (Zeng: 0.1 = 3277), 1 .. 32768 */
} tdc_lhist_config_t;

typedef struct {
    uint64_t frames, reset, clamped;
} tdc_lhist_stats_t;

typedef struct {
    tdc_lhist_config_t cfg;
    uint16_t *hist[2]; /* W x H x c, Q8 */
    uint8_t *out;      /* W x H x c */
    int cur, have;
    tdc_lhist_stats_t stats;
} tdc_lhist_t;

#define TDC_LHIST_ARENA(X, W, H, C)                                                     \
    X(hist[0], uint16_t, (size_t)(W) * (H) * (C)) X(hist[1], uint16_t, (size_t)(W) * (H) * (C)) \
    X(out, uint8_t, (size_t)(W) * (H) * (C))

/* Compile-time bound for a colour layer at W x H. */
#define TDC_LHIST_MEM_BYTES(W, H) ((size_t)0 TDC_LHIST_ARENA(TDC_ARENA_BLOCK_BYTES, W, H, 3u))

/* Arena bytes for cfg (0 if invalid). */
size_t tdc_lhist_get_size(const tdc_lhist_config_t *cfg);
/* TDC_ERR_ARG (invalid cfg, unaligned arena), TDC_ERR_SIZE (n too small). */
TDC_MUST_CHECK tdc_status_t tdc_lhist_init(tdc_lhist_t *st, const tdc_lhist_config_t *cfg, void *arena, size_t n);
/* One refresh: x (W x H x c, 8-bit), mv (W x H x 2, Q4 px; NULL: zero
 * vectors), falloff (W x H, Q15 G of eq. 4; NULL: alpha everywhere).  The
 * first frame after init has no history (v = x).  TDC_ERR_ARG on NULL x. */
TDC_MUST_CHECK tdc_status_t tdc_lhist_step(tdc_lhist_t *st, const uint8_t *x, const int16_t *mv,
                                           const uint16_t *falloff);
/* The last output (W x H x c) and the Q8 history it was rounded from. */
const uint8_t *tdc_lhist_output(const tdc_lhist_t *st);
const uint16_t *tdc_lhist_history_q8(const tdc_lhist_t *st);

#endif /* TDC_LAYER_HIST_H */
