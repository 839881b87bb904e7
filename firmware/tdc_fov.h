/*
 * tdc_fov.h - foveated streams, display side (docs/design.md §4.5; thesis
 * "Image Upscaling for Ray Traced Foveated Rendering" §2.2.2, §4.2, §4.4).
 *
 * The renderer traces a kernel log-polar buffer of lp_w x lp_h samples
 * (column u = radius, row v = angle) around the gaze point C, plus a foveal
 * disk of radius r_d = disk * R uniformly (one sample per display pixel);
 * R is the distance from C to the farthest screen corner, L = ln R.
 * This stage rebuilds the Cartesian frame:
 *
 *   eq. 2.2   u = K^-1(ln|x'| / L) * lp_w,  v = atan2(y', x') mod 2pi * lp_h / 2pi,
 *             K(x) = x^alpha, so K^-1(x) = 2^(log2(x) / alpha).
 *   eq. 4.4   radial Gaussian along u, diameter eta(x) = max(3 + 0.8 (x - 0.1) / 0.05, 0)
 *             output pixels, x = |x'| / R; sigma_u = eta/4 * du/dr columns, clamped
 *             to [1/2, 2] (1/2: the kernel then interpolates like a tent; 2: at most
 *             9 taps).  Kernel (e^(-t^2/2) - e^-2)/(1 - e^-2) for t = d/sigma < 2:
 *             cut continuously at t = 2, so no tap switches on with a jump.
 *             Bilinear (periodic) along v.
 *   eq. 4.5   the disk is the rectangle u < l(r_d) = ceil(K^-1(ln r_d / L) * lp_w):
 *             tdc_fov_geom_t.l.  The link carries columns [u0, lp_w), u0 <= l, so
 *             that the blend band and the kernel's reach have samples.
 *   blend     log-polar weight b = clamp((r - (r_d - 4 px)) / 4 px, 0, 1): the disk
 *             inside, the log-polar buffer outside, a 4-pixel ramp inside the border.
 *   TAA       eqs. 2.5, 4.7-4.10 in the periphery: f = a s + (1 - a) f_{n-1}(p + mv),
 *             a = a_min + min((1 - a_min) H, 1 - a_min), a_min = clamp(box3x3 |s - f_{n-1}|,
 *             0.1, 1), H = (|m| / |(W, H)|)^(1/4) * 60 / R_n, R_n = 0.1/dt_n + 0.9/dt_{n-1}.
 *             Phased out *after* the disk border (§5.3): the TAA weight is b, so it
 *             runs at full strength up to the border and ramps to 0 inside it.
 *             A gaze jump of more than 1/8 of the screen diagonal (a saccade)
 *             rejects the whole history for that frame.
 *
 * Note on eq. 2.3 as printed (x = e^(A K(u)) cos(Bv) + x^, A = L/w): it is the
 * inverse of eq. 2.2 only for K(x) = x.  The exact inverse, used by the
 * renderer (render) and the reference (ref/ref_fov.c), is
 * r = e^(L K(u / w)), which equals the printed form at alpha = 1.
 *
 * Coordinates: the screen is [0, W] x [0, H]; pixel (i, j) has its centre at
 * (i + 1/2, j + 1/2); the gaze is in Q8 pixels and may lie outside the screen
 * by up to one screen size.  Log-polar sample (i, j) sits at u = i, v = j.
 * Colours: 8-bit RGB interleaved codes; the stage interpolates gamma-coded
 * values in Q8 (like TRM's D and U), the history is Q8 codes (uint16).
 *
 * Memory: caller-owned arena of tdc_fov_get_size() bytes (TDC_FOV_MEM_BYTES
 * on a board; layout TDC_FOV_ARENA, carved by tdc_arena.h): the radial
 * table (8 bytes per node, TDC_FOV_RAD_NODES: 2561 nodes, 20 KB for a
 * 1080 x 1200 eye) and 34 bytes per display column (reciprocals, one row of
 * tap descriptors and colours); with TAA two Q8 history
 * frames (12 bytes per display pixel: the previous frame is read by
 * reprojection while the new one is written) and 38 bytes per display
 * column of row scratch.
 * No heap, no float, no recursion; same bytes on every compiler and CPU.
 */
#ifndef TDC_FOV_H
#define TDC_FOV_H

#include "tdc_arena.h"
#include "tdc_fixed.h"
#include "tdc_fov_kernels.h"
#include "tdc_fov_params.h"


/* Checks the parameters against a display of width x height and fills g.
 * TDC_ERR_ARG: alpha, disk, lp size out of range or the gaze farther than
 * one screen size outside the screen; TDC_ERR_SIZE: lp larger than the display. */
TDC_MUST_CHECK tdc_status_t tdc_fov_geom(tdc_fov_geom_t *g, uint16_t width, uint16_t height, const tdc_fov_params_t *p);

/* eq. 2.2 at a display point (Q8): u, v in Q16 log-polar samples,
 * u in [0, lp_w], v in [0, lp_h). */
void tdc_fov_to_lp(const tdc_fov_geom_t *g, int32_t x_q8, int32_t y_q8, uint32_t *u_q16, uint32_t *v_q16);

/* Is display pixel (i, j) in the foveal disk (the link carries it)? */
int tdc_fov_in_disk(const tdc_fov_geom_t *g, int32_t i, int32_t j);
/* Pixels of display row j in the disk: [*x0, *x0 + return value). */
uint32_t tdc_fov_disk_span(const tdc_fov_geom_t *g, int32_t j, int32_t *x0);
/* Number of disk pixels on the screen (the link's disk payload / 3 bytes). */
uint32_t tdc_fov_disk_pixels(const tdc_fov_geom_t *g);

/* Stage configuration: the largest frame it must handle. */
typedef struct {
    uint16_t width, height; /* display size */
    uint8_t taa;            /* 1: peripheral TAA (history in the arena) */
} tdc_fov_config_t;

/* The per-frame radial table (eq. 2.2's u and eq. 4.4's sigma as functions
 * of |x'|^2): node n = 128 (e - 20) + m sits at |x'|^2 = 2^e (1 + m/128)
 * (Q16, e >= 20, i.e. |x'| >= 4 px; closer pixels take the exact path),
 * linear interpolation between nodes (u error <= 3.3e-4 columns: the
 * interpolation of w (log2 r^2 / log2 R^2)^(1/alpha) over a node, alpha 1..8).
 * Rebuilt only when R, alpha or lp_w change (the gaze moves R).  Nodes up to
 * the octave of R^2 <= 4 (W^2 + H^2) px^2 (the gaze is at most one screen
 * outside): floor(log2(W^2 + H^2)) - 1 octaves of 128 nodes, + 1. */
typedef struct {
    uint32_t u_q16;    /* eq. 2.2 u, Q16 columns, not clipped at lp_w (extrapolated past R) */
    uint16_t sig_q14;  /* sigma_u in [1/2, 2], Q14 */
    uint16_t inv2_q12; /* 1 / sigma_u^2 in [1/4, 4], Q12 */
} tdc_fov_node_t;
#define TDC_FOV_NODE_BITS 7u /* 128 nodes per octave of |x'|^2 */
#define TDC_FOV_NODE_E0 20u  /* first octave: |x'|^2 = 2^20 (Q16) = 16 px^2 */
#define TDC_FOV_LOG2_S_(S, k) +(((uint64_t)(S)) >= ((uint64_t)1 << (k)) ? 1u : 0u)
#define TDC_FOV_FLOOR_LOG2_(S)                                                                                     \
    (0u TDC_FOV_LOG2_S_(S, 1) TDC_FOV_LOG2_S_(S, 2) TDC_FOV_LOG2_S_(S, 3) TDC_FOV_LOG2_S_(S, 4)                   \
         TDC_FOV_LOG2_S_(S, 5) TDC_FOV_LOG2_S_(S, 6) TDC_FOV_LOG2_S_(S, 7) TDC_FOV_LOG2_S_(S, 8)                  \
             TDC_FOV_LOG2_S_(S, 9) TDC_FOV_LOG2_S_(S, 10) TDC_FOV_LOG2_S_(S, 11) TDC_FOV_LOG2_S_(S, 12)           \
                 TDC_FOV_LOG2_S_(S, 13) TDC_FOV_LOG2_S_(S, 14) TDC_FOV_LOG2_S_(S, 15) TDC_FOV_LOG2_S_(S, 16)      \
                     TDC_FOV_LOG2_S_(S, 17) TDC_FOV_LOG2_S_(S, 18) TDC_FOV_LOG2_S_(S, 19) TDC_FOV_LOG2_S_(S, 20)  \
                         TDC_FOV_LOG2_S_(S, 21) TDC_FOV_LOG2_S_(S, 22) TDC_FOV_LOG2_S_(S, 23)                     \
                             TDC_FOV_LOG2_S_(S, 24) TDC_FOV_LOG2_S_(S, 25) TDC_FOV_LOG2_S_(S, 26)                 \
                                 TDC_FOV_LOG2_S_(S, 27))
/* Nodes for a W x H display (W, H >= 4, so W^2 + H^2 >= 32: >= 4 octaves). */
#define TDC_FOV_RAD_NODES(W, H) \
    ((size_t)(TDC_FOV_FLOOR_LOG2_((uint64_t)(W) * (W) + (uint64_t)(H) * (H)) - 1u) * 128u + 1u)

/* The arena layout (firmware/tdc_arena.h), one list: the radial table, one
 * reciprocal per display column (the angle's atan without a divide), and
 * with TAA two Q8 RGB history frames (ping-pong) and the row scratch, 19
 * uint16 per display column (2 rows x 8 values + 3 rows of |s - h|). */
#define TDC_FOV_ROW_VALS 19u
#define TDC_FOV_ARENA(X, W, H, TAA)                                 \
    X(rad, tdc_fov_node_t, TDC_FOV_RAD_NODES(W, H))                 \
    X(colinv, uint32_t, (size_t)(W))                                \
    X(t_off0, uint32_t, (size_t)(W))                                \
    X(t_off1, uint32_t, (size_t)(W))                                \
    X(t_wf, uint32_t, (size_t)(W))                                  \
    X(t_ij, uint32_t, (size_t)(W))                                  \
    X(t_out, uint16_t, (size_t)(W)*3u)                              \
    X(t_gen, uint16_t, (size_t)(W)*3u)                              \
    X(t_b, uint16_t, (size_t)(W))                                   \
    X(hist[0], uint16_t, (TAA) ? (size_t)(W) * (size_t)(H)*3u : 0u) \
    X(hist[1], uint16_t, (TAA) ? (size_t)(W) * (size_t)(H)*3u : 0u) \
    X(rows, uint16_t, (TAA) ? (size_t)(W)*TDC_FOV_ROW_VALS : 0u)
/* Compile-time bound for static arenas. */
#define TDC_FOV_MEM_BYTES(W, H, TAA) ((size_t)0 TDC_FOV_ARENA(TDC_ARENA_BLOCK_BYTES, W, H, TAA))

struct tdc_fov_lr_s; /* tdc_fov_lr.h */

/* The geometry pass over one display row (internal to the stage; public for
 * the SIMD kernels and tests/checkasm): eq. 2.2 from the radial table and
 * the reciprocals, eq. 4.4's sigma, the blend weight; per pixel a two-tap
 * descriptor (tdc_fov_kernels.h) or, where sigma > 1/2 or the pixel is
 * log-rectilinear, its colour in gen.  Built per frame and row by
 * tdc_fov_geom_args() from the stage; the kernels fill pixels [x0, x1). */
typedef struct {
    const tdc_fov_geom_t *g;
    const uint8_t *lp;
    size_t lp_stride;
    const tdc_fov_node_t *rad;
    uint32_t rad_nodes;
    uint32_t half_lo, half_hi;            /* nodes [half_lo, half_hi] have sigma = 1/2 (none: lo > hi) */
    const uint32_t *colinv;               /* per column: recip_norm(|dx|) */
    const uint32_t *atan_tab, *tent_tab;  /* tdc_fov_tables.h (257 entries each) */
    uint64_t rb2_q16;                     /* (r_d - 4 px)^2, or 0 */
    int32_t rb_q8;                        /* r_d - 4 px (may be negative) */
    int32_t leta_max;                     /* log2 of the largest eta (x = 1), Q24 */
    uint32_t off_dummy;                   /* sample (u0, 0) */
    int taa;                              /* 1: the nearest samples (ij) are needed */
    const struct tdc_fov_lr_s *lr;        /* log-rectilinear frame: the periphery from tdc_fov_lr.c */
    int32_t dy;                           /* this row: y' (Q8), y'^2 (Q16), |y'| and recip_norm(|y'|) */
    uint64_t dy2;
    uint32_t ay, inv_y;
    uint32_t *off0, *off1, *wf, *ij;      /* out: descriptors, iu | jv << 16 */
    uint16_t *gen, *b;                    /* out: colours (Q8 x 3) where b & 512, blend weight | 512 */
} tdc_fov_geom_args_t;

/* u, sigma and 1/sigma^2 of the radial table at |x'|^2 (Q16): a node of the
 * frame's table, or a pixel closer than 4 px to the gaze (the row kernel).
 * clip: u = lp_w from R on; leta_max: log2 of eq. 4.4's largest eta. */
void tdc_fov_node_fill(const tdc_fov_geom_t *g, uint64_t r2_q16, int clip, int32_t leta_max, tdc_fov_node_t *nd);

typedef void tdc_fov_geom_row_fn(const tdc_fov_geom_args_t *a, int32_t x0, int32_t x1);
tdc_fov_geom_row_fn tdc_fov_geom_row_c;    /* the reference: every pixel in C (what the boards run), tdc_fov_rows.c */
tdc_fov_geom_row_fn tdc_fov_geom_row_avx2; /* 8 pixels a step where all 8 take the two-tap path; the C row elsewhere */

typedef struct {
    tdc_fov_config_t cfg;
    struct tdc_fov_lr_s *lr; /* log-rectilinear scratch (tdc_fov_lr_attach), NULL: refused */
    tdc_fov_node_t *rad; /* radial table (TDC_FOV_RAD_NODES), valid for rad_key */
    uint32_t *colinv;    /* per display column: 2^63 / (|dx| << clz(|dx|)), for colinv_cx */
    /* one display row of the geometry pass (tdc_fov_kernels.h): tap descriptors, the
     * kernel's output planes, the other pixels' colours, blend weight | general flag, iu | jv << 16 */
    uint32_t *t_off0, *t_off1, *t_wf, *t_ij;
    uint16_t *t_out, *t_gen, *t_b;
    tdc_fov_tap2_row_fn *tap2; /* the row kernels (tdc_fov_set_simd) */
    tdc_fov_geom_row_fn *geom;
    uint16_t *hist[2];   /* Q8 RGB history frames, ping-pong */
    uint16_t *rows;      /* scratch: 2 rows x 8 values + 3 rows of |s - h| */
    uint8_t cur;         /* hist[cur] holds the last output */
    uint8_t have_hist;
    uint8_t rad_valid, colinv_valid;
    int32_t rad_key_r2, rad_key_lpw, rad_key_alpha; /* the table's log2(R^2) (Q24), lp_w, alpha */
    uint32_t rad_nodes;                             /* nodes built */
    uint32_t rad_half_lo, rad_half_hi;              /* their longest run with sigma = 1/2 */
    int32_t colinv_cx;                              /* gaze x (Q8) of colinv */
    uint32_t dt_prev_us;
    int32_t gaze_prev_x_q8, gaze_prev_y_q8;
    uint32_t frames, rejected_frames; /* counters: frames composed, histories rejected */
    uint32_t rad_builds;              /* counter: radial tables built */
} tdc_fov_t;

size_t tdc_fov_get_size(const tdc_fov_config_t *cfg);
/* mem: caller-owned arena of tdc_fov_get_size() bytes, aligned to
 * TDC_ARENA_ALIGN (8); TDC_ERR_ARG if not, TDC_ERR_SIZE if too small. */
TDC_MUST_CHECK tdc_status_t tdc_fov_init(tdc_fov_t *st, const tdc_fov_config_t *cfg, void *mem, size_t mem_bytes);
/* 1: the SIMD row kernels (geometry, taps) where the CPU has them (the
 * default), 0: the C kernels (same bytes; for the benchmarks and checkasm). */
void tdc_fov_set_simd(tdc_fov_t *st, int enable);
/* The geometry pass's arguments for display row y of a kernel log-polar
 * frame with parameters p (its geometry into g, which must outlive a),
 * building the stage's tables as tdc_fov_frame does and pointing at its row
 * buffers (tests/checkasm).  TDC_ERR_ARG for a log-rectilinear frame or a
 * row off the display; tdc_fov_geom's refusals. */
TDC_MUST_CHECK tdc_status_t tdc_fov_geom_args(tdc_fov_t *st, const tdc_fov_params_t *p, const uint8_t *lp,
                                              size_t lp_stride, int32_t y, tdc_fov_geom_t *g, tdc_fov_geom_args_t *a);
/* Forget the history (stream restart, loss): the next frame is taken as is. */
void tdc_fov_reset(tdc_fov_t *st);

/* One foveated frame.
 *   lp:   lp_h rows of lp_w RGB8 samples (row = angle), stride lp_stride bytes;
 *         only columns [g.u0, lp_w) are read.
 *   mv:   motion vectors of the log-polar samples, int16 (x, y) pairs in Q4
 *         display pixels, BACKWARD as everywhere on the link (docs/design.md §4.4):
 *         the point now at p was at p + mv (the thesis's eq. 4.6 vector is
 *         -mv); stride mv_stride int16 per row; NULL = no motion.  TAA only.
 *   disk: W x H RGB8 image of which only disk pixels are read (stride
 *         disk_stride); may be the same buffer as out (each pixel is read
 *         before it is written).
 *   dt_us: this frame's time, for eq. 4.7 (TAA only; 0 = as the last one).
 * A log-rectilinear frame (p->transform, tdc_fov_lr.h) reads lp as its whole
 * texel buffer and needs scratch attached (tdc_fov_lr_attach), else TDC_ERR_ARG.
 * TDC_ERR_ARG / TDC_ERR_SIZE as tdc_fov_geom, or a geometry larger than the config;
 * TDC_ERR_ARG for a stride too small or a log-polar buffer spanning 2^31 bytes or
 * more ((lp_h - 1) lp_stride + 3 lp_w: the tap descriptors hold byte offsets). */
TDC_MUST_CHECK tdc_status_t tdc_fov_frame(tdc_fov_t *st, const tdc_fov_params_t *p, const uint8_t *lp, size_t lp_stride,
                                          const int16_t *mv, size_t mv_stride, const uint8_t *disk, size_t disk_stride,
                                          uint32_t dt_us, uint8_t *out, size_t out_stride);

/* Building blocks, exported for the tests (each states its error). */
/* The stage accepts log-rectilinear frames only with the warp's scratch
 * attached (tdc_fov_lr.h; NULL detaches); TDC_ERR_SIZE if lr serves a
 * narrower display. */
TDC_MUST_CHECK tdc_status_t tdc_fov_lr_attach(tdc_fov_t *st, struct tdc_fov_lr_s *lr);

int32_t tdc_fov_exp2_q16(int32_t s_q24);            /* 2^s in Q16, s in Q24, saturating */
uint32_t tdc_fov_turns_q32(int32_t dx, int32_t dy); /* atan2(dy, dx) mod 2pi, Q32 turns */

#endif /* TDC_FOV_H */
