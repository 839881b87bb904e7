/*
 * tdc_fov_params.h - the foveation stage's per-frame parameters (the
 * foveated packet's header) and the frame geometry derived from them
 * (tdc_fov_geom, tdc_fov.h): what the stage, its log-rectilinear warp
 * (tdc_fov_lr.h) and the link's header parser (tdc_fov_link.h) share, below
 * all three.
 */
#ifndef TDC_FOV_PARAMS_H
#define TDC_FOV_PARAMS_H

#include <stdint.h>

#define TDC_FOV_MIN_SIZE 4u /* display and log-polar sides at least this */
#define TDC_FOV_MAX_SIZE 8192u
#define TDC_FOV_ALPHA_MIN_Q8 256u /* K(x) = x^alpha, alpha in [1, 8], Q8 */
#define TDC_FOV_ALPHA_MAX_Q8 2048u
#define TDC_FOV_BLEND_Q8 1024 /* the blend band: 4 px, Q8 */
#define TDC_FOV_REACH 4       /* the kernel reaches 2 sigma <= 4 columns */

/* The transform of the buffer (the link header's transform byte). */
#define TDC_FOV_KERNEL_LOG_POLAR 0u /* this file: eq. 2.2 */
#define TDC_FOV_LOG_RECT 1u         /* log-rectilinear, tdc_fov_lr.h */

/* Per-frame foveation parameters (the foveated packet's header).  Zero
 * lr_k_q4, transform (and zero) is the kernel log-polar kind. */
typedef struct {
    int32_t gaze_x_q8, gaze_y_q8; /* C in display pixels, Q8 */
    uint16_t alpha_q8;            /* K(x) = x^alpha, Q8 in [1, 8]; 256 for log-rectilinear */
    uint16_t disk_q15;            /* r_d / R, Q15 in [0, 1] (32768 = 1) */
    uint16_t lp_w, lp_h;          /* log-polar buffer size (delta * W, delta * H) */
    uint16_t lr_k_q4[2];          /* log-rectilinear foveal scale k (x, y), Q4 px, >= 1 px; 0 otherwise */
    uint16_t transform;           /* TDC_FOV_KERNEL_LOG_POLAR or TDC_FOV_LOG_RECT */
    uint16_t zero;                /* 0: no padding bytes (parsed headers compare bytewise) */
} tdc_fov_params_t;

/* Geometry of one frame, derived from the parameters (tdc_fov_geom). */
typedef struct {
    uint16_t width, height, lp_w, lp_h;
    int32_t cx_q8, cy_q8;
    int32_t log2_r2max_q24; /* log2(R^2), Q24, > 0 */
    int32_t lg_lr_q24;      /* log2(log2(R^2)) + 24 (the table's scale), Q24 */
    int32_t log2_w_q24;     /* log2(lp_w), Q24 */
    int32_t log2_alpha_q24; /* log2(alpha), Q24 */
    uint32_t inv_alpha_q24; /* 2^24 / alpha */
    uint32_t r_max_q8;      /* R = sqrt(R^2), Q8 (floor) */
    uint32_t r_disk_q8;     /* r_d = disk * R, Q8 */
    uint64_t r_disk2_q16;   /* r_d^2: a pixel is in the disk iff |x'|^2 <= r_d^2 */
    uint16_t l;             /* eq. 4.5: disk rectangle columns [0, l) */
    uint16_t u0;            /* first column the link carries */
    uint8_t transform;      /* the parameters' (log-rectilinear: l = u0 = 0) */
} tdc_fov_geom_t;

#endif
