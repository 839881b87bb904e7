/*
 * ref_fov_lr.h - double-precision reference of the log-rectilinear
 * foveation kind (firmware/tdc_fov_lr.c), from the equations stated in
 * firmware/tdc_fov_lr.h and docs/foveation.md (after Li et al. 2021):
 *
 *   s(d) = sign(d) ln(1 + |d| / k),  S = s(N - c) - s(-c),
 *   u(x) = n (s(x - c) - s(-c)) / S,  x(u) = c + k sign(t) (e^|t| - 1), t = s(-c) + S u / n,
 *
 * the sender's default foveal scale (k S(k) = n: one texel per display
 * pixel at the gaze), the area-averaged buffer by summed-area tables (the
 * sender's side) and the display side's bilinear periphery sample.
 * Host code: doubles, malloc, libm.
 */
#ifndef REF_FOV_LR_H
#define REF_FOV_LR_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    double c, k;  /* gaze coordinate, foveal scale (display pixels) */
    double s0, S; /* s(-c), s(N - c) - s(-c) */
    int N, n;     /* display side, buffer side */
} ref_fov_lr_axis_t;

void ref_fov_lr_axis(ref_fov_lr_axis_t *a, double c, double k, int N, int n);
/* forward u(x) (x clamped to [0, N]) and inverse x(u) (u in [0, n]) */
double ref_fov_lr_fwd(const ref_fov_lr_axis_t *a, double x);
double ref_fov_lr_inv(const ref_fov_lr_axis_t *a, double u);
/* du/dx at x: buffer texels per display pixel */
double ref_fov_lr_density(const ref_fov_lr_axis_t *a, double x);
/* The sender's default k for a display side N, buffer side n, gaze c:
 * k S(k) = n (du/dx = 1 at the gaze), clamped to [1, 4095.9375] px. */
double ref_fov_lr_k(int N, int n, double c);

/* Summed-area table of a W x H RGB8 picture (rows stride bytes apart):
 * (W + 1) x (H + 1) x 3 doubles, sat[(y (W + 1) + x) 3 + ch] = sum over
 * pixels [0, x) x [0, y) of lut[256 ch + code] (lut NULL: the codes
 * themselves; ref_fov_lin_lut: linear light).  NULL on allocation failure. */
double *ref_fov_lr_sat(const uint8_t *img, size_t stride, int W, int H, const double *lut);
/* lut[256 ch + k] = (k / 255)^gamma[ch]: the linear light of drive code k
 * under the panel gamma the simulator's sources encode with
 * (tdc_sim_encode_code is its inverse). */
void ref_fov_lin_lut(const double gamma[3], double lut[3 * 256]);
/* Integral of the picture (piecewise constant per pixel) over
 * [x0, x1] x [y0, y1] (fractional, inside [0, W] x [0, H]) from its SAT:
 * the SAT is bilinear inside each pixel cell, so this is exact. */
void ref_fov_lr_box(const double *sat, int W, int H, double x0, double y0, double x1, double y1, double out[3]);
/* Mean of the picture over the square of side `side` (> 0) centred at
 * (x, y) moved into [0, W] x [0, H], cut to the screen (so never empty):
 * the footprint prefilter of a log-polar sample (ref_fov_lod_cone). */
void ref_fov_lr_box_mean(const double *sat, int W, int H, double x, double y, double side, double out[3]);
/* The buffer the sender transmits: texel (m, j) = the area average over
 * [x(m), x(m+1)) x [y(j), y(j+1)); lp: ay->n rows of ax->n texels, rows
 * lp_stride bytes apart.  gamma NULL: sat holds codes, the average is
 * rounded to RGB8; else sat holds linear light (ref_fov_lr_sat with
 * ref_fov_lin_lut) and the average is encoded round(255 v^(1/gamma)).  With
 * avg (may be NULL) the unrounded averages (n_x n_y 3 doubles, in sat's
 * units). */
void ref_fov_lr_buffer(const double *sat, int W, int H, const ref_fov_lr_axis_t *ax, const ref_fov_lr_axis_t *ay,
                       uint8_t *lp, size_t lp_stride, double *avg, const double *gamma);
/* The display side's periphery sample at display point (x, y): bilinear
 * between texel centres at (u - 1/2, v - 1/2) clamped to [0, n - 1];
 * nearest texel (floor(u), floor(v)) clamped. */
void ref_fov_lr_sample(const ref_fov_lr_axis_t *ax, const ref_fov_lr_axis_t *ay, const uint8_t *lp, size_t lp_stride,
                       double x, double y, double c[3], int *iu, int *jv);

#endif
