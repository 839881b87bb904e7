/*
 * tdc_fov_lr.h - the log-rectilinear foveation kind (after
 * Li, Du, Babu, Brumar, Varshney, "A log-rectilinear transformation for
 * foveated 360-degree video streaming", IEEE TVCG 27(5), 2021, which the
 * thesis recommends as future work, §6.3).  Second transform behind the
 * same link header (tdc_fov_link.h, transform byte) and the same stage
 * entry (tdc_fov_frame dispatches on tdc_fov_params_t.transform).
 *
 * The screen is warped separably, each axis on its own, around the gaze C.
 * For the x axis (display width N = W, buffer width n = lp_w, gaze c = C.x,
 * foveal scale k = lr_k_q4[0] / 16 display pixels; the y axis likewise with
 * H, lp_h, C.y, lr_k_q4[1]):
 *
 *   s(d)  = sign(d) * log2(1 + |d| / k)                     (warp of an offset d = x - c)
 *   S     = s(N - c) - s(-c)                                 (> 0: s is strictly increasing)
 *   u(x)  = n * (s(x - c) - s(-c)) / S                       (forward: screen x in [0, N] -> u in [0, n])
 *   x(u)  = c + k * sign(t) * (2^|t| - 1),  t = s(-c) + S u / n      (inverse)
 *   du/dx = n / (S ln2 (k + |x - c|))                        (density: largest at the gaze, falling as k/(k + |d|))
 *
 * The base of the logarithm cancels in u; log2 is the table the kernel
 * log-polar kind already has (tdc_log2_q24, tdc-tablegen --fov).
 * Buffer texel m covers [x(m), x(m + 1)) on screen; the sender fills it
 * with the AREA AVERAGE of the picture over its footprint rectangle
 * [x(m), x(m+1)) x [y(j), y(j+1)) (summed-area tables, Li et al.), so the
 * periphery is prefiltered, not point sampled: no aliasing, no blur needed
 * on the display side (the kernel log-polar kind's eq. 4.4 blur is not
 * applied).  The display side reconstructs bilinearly between texel
 * centres: display pixel (i, j) (centre (i + 1/2, j + 1/2)) reads the buffer
 * at (u - 1/2, v - 1/2), clamped to [0, n - 1] on each axis.
 *
 * The foveal scale k is the sender's choice (header field, 1 <= k < 4096 px).
 * The sender's default (ref/ref_fov_lr.c ref_fov_lr_k) solves
 * k * S(k) * ln2 = n, which makes du/dx = 1 at the gaze: one texel per
 * display pixel there, the density falling to k / (k + |d|) away from it.
 * The foveal disk (radius disk * R, R = distance to the farthest corner),
 * its 4-pixel blend band and the peripheral TAA are the kernel log-polar
 * kind's, unchanged (tdc_fov.c: the same code runs; only the periphery's
 * sample comes from here).  The whole buffer is carried (u0 = 0).
 *
 * Scaling and overflow:
 *   offsets d Q8, |d| <= 3 * 8192 * 256 < 2^23; k Q8 = k_q4 * 16 < 2^20;
 *   k + |d| < 2^24 -> log2 Q24 in [0, 24 * 2^24) < 2^29; s(d) Q24, |s| < 2^29;
 *   S = s(N - c) - s(-c) in (0, 2^30); (s - s(-c)) in [0, S];
 *   u Q16 = ((s - s(-c)) * n * 2^16 + S/2) / S: numerator < 2^30 * 2^13 * 2^16
 *   = 2^59 (uint64), quotient <= n * 2^16 < 2^29 (tdc_udiv64_32's condition
 *   (num >> 32) < S holds since num < S * 2^29).
 *   Row scratch: vertically interpolated texels, Q8 codes <= 255 * 256 < 2^16
 *   (uint16); the horizontal lerp a (2^16 - f) + b f <= 65280 * 2^16 < 2^32
 *   (uint32), + 2^15 still < 2^32.
 *   Error against the double reference: log2 table error <= 2.84e-6 per
 *   value, so u is off by <= n * 4 * 2.84e-6 / S texels (0.0026 texels at
 *   1080 p, k ~ 280 px); the two lerps round once each (<= 1/256 code).
 *
 * Memory (caller-owned, TDC_FOV_LR_MEM_BYTES(W), the arena list
 * TDC_FOV_LR_ARENA): a column table of W uint32 (u - 1/2, Q16, clamped) and
 * one row of W RGB uint16 (the vertically interpolated texels of the
 * current display row): 10 bytes per display column.  The separable remap
 * is one pass over display rows: per row one vertical interpolation of the
 * lp_w texels, per pixel one horizontal interpolation.
 * No heap, no float, no recursion; same bytes on every compiler and CPU.
 */
#ifndef TDC_FOV_LR_H
#define TDC_FOV_LR_H

#include "tdc_arena.h"
#include "tdc_fixed.h"
#include "tdc_fov_params.h"

#define TDC_FOV_LR_K_MIN_Q4 16u /* k >= 1 display pixel */

/* One axis of the warp (tdc_fov_lr_axis). */
typedef struct {
    int32_t c_q8;   /* gaze coordinate, Q8 */
    uint32_t k_q8;  /* foveal scale k, Q8 */
    int32_t lk_q24; /* log2(k_q8), Q24 */
    int32_t s0_q24; /* s(-c), Q24 */
    uint32_t S_q24; /* s(N - c) - s(-c), Q24, > 0 */
    uint16_t N, n;  /* display and buffer sides */
} tdc_fov_lr_axis_t;

/* 1 if p's log-rectilinear fields are valid (k in range, alpha = 1). */
int tdc_fov_lr_params_ok(const tdc_fov_params_t *p);
/* The axis of display side N, buffer side n, gaze c (Q8), scale k (Q4). */
void tdc_fov_lr_axis(tdc_fov_lr_axis_t *a, int32_t c_q8, uint16_t k_q4, uint16_t N, uint16_t n);
/* s(d) of an offset d (Q8), Q24. */
int32_t tdc_fov_lr_warp_q24(const tdc_fov_lr_axis_t *a, int32_t d_q8);
/* Forward map u(x) of a display coordinate x (Q8), Q16 in [0, n * 2^16]
 * (x outside [0, N] clamps to the ends). */
uint32_t tdc_fov_lr_fwd_q16(const tdc_fov_lr_axis_t *a, int32_t x_q8);

/* The stage's log-rectilinear scratch (attached to a tdc_fov_t, st->lr). */
#define TDC_FOV_LR_ARENA(X, W)        \
    X(col, uint32_t, (size_t)(W))     \
    X(row, uint16_t, (size_t)(W) * 3u)
#define TDC_FOV_LR_MEM_BYTES(W) ((size_t)0 TDC_FOV_LR_ARENA(TDC_ARENA_BLOCK_BYTES, W))

typedef struct tdc_fov_lr_s {
    uint16_t width;   /* the largest display width it serves */
    uint32_t *col;    /* per display column: u - 1/2 clamped to [0, lp_w - 1], Q16 */
    uint16_t *row;    /* the current display row's texels, vertically interpolated, Q8 RGB */
    tdc_fov_lr_axis_t ax, ay;
    uint32_t jv;      /* the current row's nearest texel row */
    const uint8_t *lp;
    size_t lp_stride;
    uint32_t frames;  /* log-rectilinear frames composed */
} tdc_fov_lr_t;

size_t tdc_fov_lr_get_size(uint16_t width);
/* mem: aligned to TDC_ARENA_ALIGN; TDC_ERR_ARG (null, width out of range,
 * misaligned), TDC_ERR_SIZE (too small).  Attach with tdc_fov_lr_attach. */
TDC_MUST_CHECK tdc_status_t tdc_fov_lr_init(tdc_fov_lr_t *lr, uint16_t width, void *mem, size_t mem_bytes);
/* (attached to the stage with tdc_fov_lr_attach, tdc_fov.h) */

/* Called by tdc_fov_frame (the dispatch on the transform): set-up of a
 * frame (the axes and the column table), one display row (the vertical
 * interpolation), one pixel's periphery sample (Q8 RGB) and its nearest
 * texel (iu, jv) for the motion vectors. */
TDC_MUST_CHECK tdc_status_t tdc_fov_lr_begin(tdc_fov_lr_t *lr, const tdc_fov_geom_t *g, const tdc_fov_params_t *p,
                                             const uint8_t *lp, size_t lp_stride);
void tdc_fov_lr_row(tdc_fov_lr_t *lr, int32_t y);
void tdc_fov_lr_sample(const tdc_fov_lr_t *lr, int32_t x, uint32_t c[3], uint32_t *iu, uint32_t *jv);

#endif /* TDC_FOV_LR_H */
