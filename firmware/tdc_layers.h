/*
 * tdc_layers.h - layered tile assembly (Zeng et al., temporally
 * reliable motion vectors, §4-§5; TDRT §3.2): the tile-ordered assembly of
 * tdc_assemble.h run per component, each reprojected with its own motion
 * vector, and the components recombined into the displayed frame.
 *
 * Input per refresh: a layered subframe from the link (tdc_layer_link.h,
 * tdc_layer_frame_t: per layer type the sample values and vectors of every
 * tile, the eq. 4 falloff weights) and the stream's tile orderings.
 *
 * Per layer L (SHADING, VISIBILITY, GLOSSY, INDIRECT; 3 or 1 channels) and
 * pixel p, with m = L's vector at p:
 *   - SURFACE vectors: m = the longest vector of p's 3x3 neighbourhood in
 *     L's motion buffer (TDRT); every other kind (SHADOW, MIRROR, GLOSSY,
 *     DUAL): m = p's own vector -- a shadow or dual vector is not overridden
 *     by a longer surface vector next to it;
 *   - VISIBILITY with SHADOW vectors, splatting (§4.1): a pixel whose own
 *     vector is zero takes the mean vector of the in-shadow pixels (non-zero
 *     shadow vector) of its (2R+1)^2 neighbourhood, R = cfg.splat_radius;
 *   - m = 0 (static): the moving window mean of the last up to 4 samples,
 *     as tdc_assemble (slot = cycle mod 4);
 *   - m != 0: a new sample is stored; an old pixel is the bilinear sample of
 *     L's previous frame at p + m (Q8), clamped per channel to mean +- k
 *     sigma of its 8 neighbours that are new this frame (k = 1: TDRT, k = 3:
 *     Zeng §5), then, for VISIBILITY with falloff weights G (eq. 4), the
 *     history weight is G: v = G h* + (1 - G) mean;
 *   - clean-up (§5, eqs. 7-8, cfg.cleanup): where the history was clamped
 *     or down-weighted, sigma = min(w_A + w_C, 5) px, w_A = (alpha_V -
 *     alpha)^2 = ((1 - alpha)(1 - G))^2, w_C = |h* - h| / (h + eps) (max
 *     over channels, values in [0, 1], eps = 0.001); the pixel is replaced by
 *     the Gaussian of that sigma over its 9x9 neighbourhood (separable
 *     weights g(dx) g(dy), clipped at the frame edge) of the layer before
 *     clean-up.  sigma is quantised down to 1/16 px; below 1/16 nothing runs.
 * Recombination in linear light (panel gamma tables): L = lin(S) V / 255 +
 * lin(G) + lin(I), clamped to 1, encoded.
 *
 * Scaling and overflow (per kernel):
 *   bilinear: v (<= 255) x Q4 x Q4 weights, 4 taps: <= 255 * 256 (Q8 code);
 *   clamp box: S1 <= 8 * 255, S2 <= 8 * 255^2; n S2 - S1^2 <= 2^22, times
 *     2^16 for Q8 < 2^38 (tdc_isqrt64), k sigma <= 3 * 2^16;
 *   falloff blend: G (<= 2^15) x Q8 value (< 2^16) < 2^31;
 *   w_C: |d| (Q8) << 8 < 2^24 over (h + eps) in Q8, capped at 5 px;
 *   clean-up: Q12 weights, row sums <= 9 * 4096 * 255 < 2^24, total weight
 *     <= (9 * 4096)^2 < 2^31, total <= 2^39 (uint64), one 64/32 division;
 *   recombination: lin(S) (<= 2^24) x V (<= 255) < 2^32, / 255.
 *
 * History per layer (cfg.history = 1; Zeng et al. eq. 2, tdc_layer_hist.h):
 * without it a moving pixel is one reprojected sample and a 1-sample layer
 * stays as noisy as it arrives.  With it, each layer's assembled frame above
 * (after clean-up) is the current frame x of that layer's tdc_lhist stage,
 * with, per pixel, the vector m the assembly used (surface: the 3x3
 * longest; visibility: splatted) and, for VISIBILITY, the falloff G (eq. 4);
 * the history is clamped to mu +- k sigma of x's 3x3 neighbourhood (k =
 * clamp_k) and blended with alpha = alpha_q15.  The recombination (and
 * tdc_lasm_layer) then reads the history outputs; the assembly's own frames
 * still feed its reprojection, so with history 0 every byte is as before.
 *
 * Memory (caller-owned arena, TDC_LASM_ARENA): per pixel, per configured
 * layer of c channels 6c + 5 bytes (2 frames 2c, 4 window slots 4c, window
 * mask 1, vectors 4), + 4 (splatted shadow vectors) with VISIBILITY, + 10
 * shared (new-sample mask 1, falloff 2, clean-up sigma 1, scratch 3, output
 * 3); SHADING + VISIBILITY 48 B/px, all four layers 94 B/px
 * (TDC_LASM_BYTES_PER_PIXEL_MAX, the compile-time bound at W x H).  With
 * history, + 5c per layer (two Q8 frames and the output, tdc_layer_hist.h)
 * and 4 shared (the vectors used): all four layers + 54 = 148 B/px
 * (TDC_LASM_HIST_BYTES_PER_PIXEL_MAX, bound TDC_LASM_MEM_BYTES_HIST).
 */
#ifndef TDC_LAYERS_H
#define TDC_LAYERS_H

#include "tdc_arena.h"
#include "tdc_fixed.h"
#include "tdc_layer_hist.h"
#include "tdc_layer_link.h"
#include "tdc_ordering.h"
#include "tdc_panel.h"
#include "tdc_status.h"

#define TDC_LASM_MAX_DIM 4096
#define TDC_LASM_SPLAT_MAX 4           /* splatting radius bound: a 9 x 9 neighbourhood */
#define TDC_LASM_SIGMA_STEPS 80        /* clean-up sigma in 1/16 px, 1 .. 80 = 5 px */
#define TDC_LASM_BYTES_PER_PIXEL_MAX 94u /* all four layers */
#define TDC_LASM_HIST_BYTES_PER_PIXEL_MAX 148u /* all four layers with history */

enum { TDC_LASM_CLAMP_TDRT = 1, TDC_LASM_CLAMP_ZENG = 3 }; /* k of mean +- k sigma */

typedef struct {
    uint16_t width, height;     /* 1 .. TDC_LASM_MAX_DIM */
    uint16_t layers;            /* TDC_LAYER_PKT_TYPE set kept (must include SHADING) */
    uint8_t clamp_k;            /* TDC_LASM_CLAMP_TDRT or _ZENG */
    uint8_t cleanup;            /* 1: §5 clean-up filter */
    uint8_t splat_radius;       /* 0 (off) .. TDC_LASM_SPLAT_MAX */
    uint8_t history;            /* 1: exponential history per layer (eq. 2; alpha_q15 >= 1) */
    uint16_t alpha_q15;         /* alpha of eqs. 2, 4, 7 (Zeng: 0.1 = 3277) */
    const tdc_panel_t *panel;   /* gamma tables, 8-bit codes */
} tdc_lasm_config_t;

typedef struct {
    uint64_t frames, reprojected, clamped, weighted, cleaned, splatted, static_px, no_neighbour;
} tdc_lasm_stats_t;

typedef struct {
    uint8_t *hist[2]; /* W x H x ch, the layer's assembled frames */
    uint8_t *slots;   /* 4 planes W x H x ch: window samples by slot */
    uint8_t *window;  /* W x H: bit s = slot s in the window */
    int16_t *mv;      /* W x H x 2: vector of the pixel's latest sample */
    uint64_t *lh_mem; /* the layer's tdc_lhist arena (history only) */
    tdc_lhist_t lh;   /* its exponential history (history only) */
} tdc_lasm_layer_t;

/* The arena: X(member, type, count) for W x H pixels, BM pattern bytes,
 * the channel count C0..C3 of each layer type (0 = not kept) and HI = 1
 * with history (each layer's tdc_lhist arena one block, its own layout). */
#define TDC_LASM_LHIST_WORDS(WH, C) \
    ((2u * TDC_ARENA_ROUND((WH) * (C) * 2u) + TDC_ARENA_ROUND((WH) * (C))) / 8u)
#define TDC_LASM_LAYER_ARENA(X, i, WH, C, HI)                                 \
    X(l[i].hist[0], uint8_t, (WH) * (C)) X(l[i].hist[1], uint8_t, (WH) * (C)) \
    X(l[i].slots, uint8_t, (WH) * (C) * 4u) X(l[i].window, uint8_t, (C) ? (WH) : 0u) \
    X(l[i].mv, int16_t, (C) ? (WH) * 2u : 0u)                                 \
    X(l[i].lh_mem, uint64_t, (HI) ? TDC_LASM_LHIST_WORDS(WH, C) : 0u)
#define TDC_LASM_ARENA(X, W, H, BM, C0, C1, C2, C3, HI)                      \
    TDC_LASM_LAYER_ARENA(X, 0, (size_t)(W) * (H), C0, HI)                   \
    TDC_LASM_LAYER_ARENA(X, 1, (size_t)(W) * (H), C1, HI)                   \
    TDC_LASM_LAYER_ARENA(X, 2, (size_t)(W) * (H), C2, HI)                   \
    TDC_LASM_LAYER_ARENA(X, 3, (size_t)(W) * (H), C3, HI)                   \
    X(hmv, int16_t, (HI) ? (size_t)(W) * (H) * 2u : 0u)                      \
    X(splat, int16_t, (C1) ? (size_t)(W) * (H) * 2u : 0u)                    \
    X(newmask, uint8_t, (size_t)(W) * (H))                                   \
    X(weight, uint16_t, (size_t)(W) * (H))                                   \
    X(sigma, uint8_t, (size_t)(W) * (H))                                     \
    X(scratch, uint8_t, (size_t)(W) * (H) * 3u)                              \
    X(out, uint8_t, (size_t)(W) * (H) * 3u)                                  \
    X(gauss, uint16_t, (size_t)(TDC_LASM_SIGMA_STEPS + 1u) * 5u)             \
    X(pattern, uint8_t, (size_t)(BM))

/* Compile-time bounds: all four layers, without and with history. */
#define TDC_LASM_MEM_BYTES(W, H) \
    ((size_t)0 TDC_LASM_ARENA(TDC_ARENA_BLOCK_BYTES, W, H, TDC_PATTERN_BYTES(W, H), 3u, 1u, 3u, 3u, 0u))
#define TDC_LASM_MEM_BYTES_HIST(W, H) \
    ((size_t)0 TDC_LASM_ARENA(TDC_ARENA_BLOCK_BYTES, W, H, TDC_PATTERN_BYTES(W, H), 3u, 1u, 3u, 3u, 1u))

typedef struct {
    tdc_lasm_config_t cfg;
    uint8_t ch[TDC_LAYER_MAX];      /* channels per layer type (0: not kept) */
    uint8_t kind[TDC_LAYER_MAX];    /* vector kind of the last ingested packet */
    tdc_lasm_layer_t l[TDC_LAYER_MAX];
    int16_t *splat, *hmv;           /* hmv: W x H x 2, the vector each pixel used (history) */
    uint8_t *newmask, *sigma, *scratch, *out, *pattern;
    uint16_t *weight, *gauss;
    uint32_t tiles_x, tiles_y;
    int cur;                        /* index of the last frame of every layer */
    uint32_t next_frame;
    int have_subframe;
    uint16_t present;               /* layers of the ingested subframe */
    tdc_lasm_stats_t stats;
} tdc_lasm_t;

/* Arena bytes for cfg (0 if invalid). */
size_t tdc_lasm_get_size(const tdc_lasm_config_t *cfg);
/* TDC_ERR_ARG (invalid cfg, unaligned arena), TDC_ERR_PANEL (not 8-bit),
 * TDC_ERR_SIZE (n < get_size).  Layers start black / lit, vectors zero. */
TDC_MUST_CHECK tdc_status_t tdc_lasm_init(tdc_lasm_t *st, const tdc_lasm_config_t *cfg, void *arena, size_t n);
/* The subframe of `frame` (the next to assemble): lf from the link decoder,
 * pattern_bits = the stream's orderings (read when frame % 4 == 0; NULL
 * keeps the last cycle's).  TDC_ERR_FRAME out of sequence, TDC_ERR_LAYER if
 * lf carries a layer the stage does not keep or its tiles disagree. */
TDC_MUST_CHECK tdc_status_t tdc_lasm_ingest(tdc_lasm_t *st, uint32_t frame, const tdc_layer_frame_t *lf,
                                            const uint8_t *pattern_bits);
/* Restarts assembly at `frame` (a late joiner: state as after init). */
void tdc_lasm_start_at(tdc_lasm_t *st, uint32_t frame);
/* Assembles `frame` (a missing subframe is allowed: old pixels only). */
TDC_MUST_CHECK tdc_status_t tdc_lasm_assemble(tdc_lasm_t *st, uint32_t frame);
/* The displayed frame, RGB888, stride width * 3. */
const uint8_t *tdc_lasm_output(const tdc_lasm_t *st, int *stride_bytes);
/* The last frame of layer type t as recombined (with history: the history
 * output; NULL if not kept); *ch = channels. */
const uint8_t *tdc_lasm_layer(const tdc_lasm_t *st, unsigned type, unsigned *ch);

#endif /* TDC_LAYERS_H */
