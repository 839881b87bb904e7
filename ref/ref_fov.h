/*
 * ref_fov.h - double-precision reference of the foveated remap
 * (firmware/tdc_fov.c), straight from the thesis's equations: eq. 2.2 and its
 * exact inverse (eq. 2.3, see tdc_fov.h for the note on the printed form),
 * eq. 4.4 blur, eq. 4.5 disk rectangle, the disk blend, TAA eqs. 2.5 and
 * 4.7-4.10 phased out after the disk border (§5.3).  Host code: doubles,
 * malloc, libm.  Colours are codes in [0, 255] (doubles).
 */
#ifndef REF_FOV_H
#define REF_FOV_H

#include <stddef.h>
#include <stdint.h>

#include "ref_fov_lr.h"

typedef struct {
    double cx, cy;  /* gaze, display pixels (screen [0, W] x [0, H]) */
    double alpha;   /* K(x) = x^alpha */
    double disk;    /* r_d / R */
    int lp_w, lp_h; /* log-polar buffer */
    int transform;  /* 0 kernel log-polar, 1 log-rectilinear (ref_fov_lr.h; alpha unused) */
    double kx, ky;  /* log-rectilinear foveal scale per axis, display pixels */
} ref_fov_params_t;

typedef struct {
    int width, height, lp_w, lp_h;
    double cx, cy, alpha;
    double R, L;   /* farthest corner distance, L = ln R */
    double r_disk; /* r_d */
    int l;         /* eq. 4.5 */
    int u0;        /* first column carried (same rule as the firmware) */
    int transform;
    ref_fov_lr_axis_t ax, ay; /* log-rectilinear axes (transform 1) */
} ref_fov_geom_t;

void ref_fov_geom(ref_fov_geom_t *g, int width, int height, const ref_fov_params_t *p);
/* eq. 2.2: display point -> (u, v); r <= 1 gives u = 0. */
void ref_fov_to_lp(const ref_fov_geom_t *g, double x, double y, double *u, double *v);
/* exact inverse of eq. 2.2 (eq. 2.3 with r = e^(L K(u / w))). */
void ref_fov_from_lp(const ref_fov_geom_t *g, double u, double v, double *x, double *y);
/* eq. 4.5 in double: ceil(K^-1(ln r / L) w), also the unrounded value. */
int ref_fov_disk_columns(const ref_fov_geom_t *g, double r, double *exact);
/* eq. 4.4 sigma along u in columns before the [1/2, 2] clamp. */
double ref_fov_sigma_u(const ref_fov_geom_t *g, double r, double u);

typedef struct {
    int width, height, taa;
    double *hist; /* W x H x 3 */
    int have_hist;
    uint32_t dt_prev_us;
    double gaze_prev_x, gaze_prev_y;
} ref_fov_t;

int ref_fov_init(ref_fov_t *st, int width, int height, int taa);
void ref_fov_free(ref_fov_t *st);
/* Same inputs as tdc_fov_frame (mv: backward Q4 int16 pairs per log-polar
 * sample or NULL); out: W x H x 3 doubles (codes). */
void ref_fov_frame(ref_fov_t *st, const ref_fov_params_t *p, const uint8_t *lp, size_t lp_stride, const int16_t *mv,
                   size_t mv_stride, const uint8_t *disk, size_t disk_stride, uint32_t dt_us, double *out);

/* Texture LOD / footprint prefilter of the log-polar samples (thesis §4.1.2,
 * eqs. 4.1-4.3): what one log-polar sample stands for on the display, in
 * display pixels (the renderer's cone factor, tdc_render.h cfg.fov_lod; the
 * simulator's box side for photographs and procedural scenes):
 *  OFF        1 (one display pixel: the point sample);
 *  FOOTPRINT  max(1, the longer side of eq. 2.3's cell at radius r, u / w = un:
 *             radial r L alpha un^(alpha-1) / w, tangential 2 pi r / h);
 *  THESIS     2^phi, phi = 3 S1(un^alpha)^3 (eq. 4.3, S1 = smoothstep on
 *             [0, 1]; without eq. 4.2's base bias 0.3).
 * The one definition both sample paths use (do not write it twice). */
enum { TDC_FOV_LOD_OFF = 0, TDC_FOV_LOD_FOOTPRINT = 1, TDC_FOV_LOD_THESIS = 2 };
double ref_fov_lod_cone(int mode, double r, double L, double alpha, double un, int w, int h);

/* Halton(2,3) point f + 1 moved to [-1/2, 1/2)^2: the TAA jitter of frame f
 * (thesis §4.3.2; tdc_render_halton is this). */
void ref_fov_halton(uint32_t f, double *jx, double *jy);

/* The TAA jitter (jx, jy) in [-1/2, 1/2)^2 of log-polar sample (i, j) as a
 * buffer position (u, v) = (max(i + jx s_u, 0), j + jy s_v):
 *  TEXEL  s_u = s_v = 1: half a buffer texel (the thesis offsets the
 *         dispatch index of its render target, §4.3.2) - at alpha 4 up to
 *         ~12 display pixels radially at a headset's screen edge, ~18 at
 *         the corners, and the display side does not know the offset;
 *  PIXEL  s = min(1, 1 / (display pixels per texel along that axis at i)):
 *         at most half a texel and at most half a display pixel (radial
 *         r L alpha (i/w)^(alpha-1) / w, tangential 2 pi r / h, r = e^(L (i/w)^alpha)). */
enum { TDC_FOV_JITTER_TEXEL = 0, TDC_FOV_JITTER_PIXEL = 1 };
void ref_fov_lp_jitter(int mode, double L, double alpha, int w, int h, int i, int j, double jx, double jy, double *u,
                       double *v);

/* The log-polar samples of columns [u0, lp_w) x rows [0, lp_h), in payload
 * order (row by row), at buffer position ref_fov_lp_jitter(jitter, ...):
 * their display positions by the exact inverse of eq. 2.2 into xy (2
 * doubles per sample) and, with side != NULL, ref_fov_lod_cone(lod, ...) at
 * that position.  Returns the number of samples. */
size_t ref_fov_lp_samples(const ref_fov_geom_t *g, int u0, double jx, double jy, int jitter, int lod, double *xy,
                          double *side);

/* eq. 5.1 ray model: samples traced for a frame (log-polar columns [u0, w)
 * plus the disk pixels on the screen) over W*H. */
double ref_fov_ray_share(const ref_fov_geom_t *g, long disk_pixels);

#endif
