/*
 * fov_fixture.h - foveated test inputs shared by the fov tests: a
 * procedural picture (edges, gradients, fine stripes) sampled the way the
 * renderer samples it, the log-polar buffer at eq. 2.3 positions (exact
 * inverse, sim/ref_fov.c) and the disk at pixel centres, and the
 * fixed-point parameters of a double-precision parameter set.
 */
#ifndef FOV_FIXTURE_H
#define FOV_FIXTURE_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "ref_fov.h"
#include "tdc_fov.h"

/* The picture at a display point (t shifts it: motion), codes 0..255. */
static inline void fov_picture(double x, double y, double t, uint8_t c[3])
{
    x -= t;
    const double a = 127.5 + 100 * sin(x * 0.11) * cos(y * 0.07);
    const double b = ((int)floor(x / 9) + (int)floor(y / 7)) & 1 ? 220 : 30;
    const double s = 127.5 + 120 * sin(x * 1.3 + y * 0.4);
    c[0] = (uint8_t)lround(fmin(fmax(a, 0), 255));
    c[1] = (uint8_t)lround(b);
    c[2] = (uint8_t)lround(fmin(fmax(0.5 * s + 0.5 * a, 0), 255));
}

/* Log-polar buffer (lp_w x lp_h RGB) and disk (W x H RGB, every pixel) of
 * the picture; jitter (jx, jy) in samples (Halton where TAA follows). */
static inline void fov_make_inputs(const ref_fov_geom_t *g, double t, double jx, double jy, uint8_t *lp, uint8_t *disk)
{
    for (int j = 0; j < g->lp_h; j++) {
        for (int i = 0; i < g->lp_w; i++) {
            double x, y;
            ref_fov_from_lp(g, i + jx, j + jy, &x, &y);
            fov_picture(x, y, t, lp + ((size_t)j * g->lp_w + i) * 3);
        }
    }
    for (int j = 0; j < g->height; j++) {
        for (int i = 0; i < g->width; i++) {
            fov_picture(i + 0.5, j + 0.5, t, disk + ((size_t)j * g->width + i) * 3);
        }
    }
}

static inline void fov_params(const ref_fov_params_t *rp, tdc_fov_params_t *fp)
{
    fp->gaze_x_q8 = (int32_t)lround(rp->cx * 256);
    fp->gaze_y_q8 = (int32_t)lround(rp->cy * 256);
    fp->alpha_q8 = (uint16_t)lround(rp->alpha * 256);
    fp->disk_q15 = (uint16_t)lround(rp->disk * 32768);
    fp->lp_w = (uint16_t)rp->lp_w;
    fp->lp_h = (uint16_t)rp->lp_h;
    fp->transform = (uint16_t)rp->transform;
    fp->zero = 0;
    fp->lr_k_q4[0] = rp->transform ? (uint16_t)lround(rp->kx * 16) : 0;
    fp->lr_k_q4[1] = rp->transform ? (uint16_t)lround(rp->ky * 16) : 0;
}

/* The reference's parameters as the firmware sees them (after rounding). */
static inline void fov_quantise(ref_fov_params_t *rp)
{
    rp->cx = lround(rp->cx * 256) / 256.0;
    rp->cy = lround(rp->cy * 256) / 256.0;
    rp->alpha = lround(rp->alpha * 256) / 256.0;
    rp->disk = lround(rp->disk * 32768) / 32768.0;
    rp->kx = lround(rp->kx * 16) / 16.0;
    rp->ky = lround(rp->ky * 16) / 16.0;
}

#endif
