/*
 * tdc_render_fov.c - sample positions of the FOVEATED mode (thesis §4.2.1,
 * §4.2.3): the kernel log-polar buffer through the exact inverse of eq. 2.2
 * and the uniformly sampled foveal disk.  The geometry (the columns u0..w-1
 * the link carries, which pixels are in the disk) comes from the firmware
 * (tdc_fov_geom, tdc_fov_disk_span), so renderer and controller agree on
 * every sample; the positions themselves are double precision.
 */
#include <math.h>
#include <stdlib.h>

#include "ref_fov.h" /* ref_fov_lod_cone: the footprint both sample paths use */
#include "tdc_fov.h"
#include "tdc_fov_link.h"
#include "tdc_render_internal.h"

void tdc_render_halton(uint32_t f, double *jx, double *jy)
{
    ref_fov_halton(f, jx, jy);
}

int tdc_render_set_foveation(tdc_render_t *r, const tdc_render_fov_t *f, int *lp_samples, int *disk_pixels)
{
    if (!r || !f || !(f->delta > 0 && f->delta <= 1) || !(f->alpha >= 1 && f->alpha <= 8) ||
        !(f->disk >= 0 && f->disk <= 1) || !(fabs(f->gaze_x) < 1e6 && fabs(f->gaze_y) < 1e6))
        return -1;
    /* delta quantised up to Q15 as the link header carries it (0.555 -> 18187) */
    const uint16_t dq = (uint16_t)ceil(f->delta * 32768 - 1e-9);
    tdc_fov_params_t p = {(int32_t)lround(f->gaze_x * 256),    (int32_t)lround(f->gaze_y * 256),
                          (uint16_t)lround(f->alpha * 256),    (uint16_t)lround(f->disk * 32768),
                          tdc_fov_lp_size(dq, (uint16_t)r->W), tdc_fov_lp_size(dq, (uint16_t)r->H), {0, 0}, 0, 0};
    tdc_fov_geom_t g;
    if (tdc_fov_geom(&g, (uint16_t)r->W, (uint16_t)r->H, &p) != TDC_OK) return -1;
    const int nlp = (g.lp_w - g.u0) * g.lp_h;
    const int nd = (int)tdc_fov_disk_pixels(&g);
    float *xy = realloc(r->fov_xy, (size_t)(nlp + nd > 0 ? nlp + nd : 1) * 2 * sizeof(float));
    if (!xy) return -1;
    r->fov_xy = xy;
    float *cone = realloc(r->fov_cone, (size_t)(nlp + nd > 0 ? nlp + nd : 1) * sizeof(float));
    if (!cone) return -1;
    r->fov_cone = cone;
    /* eq. 2.3 with the exact inverse: r = e^(L (u / w)^alpha), theta = 2 pi v / h */
    const double cx = p.gaze_x_q8 / 256.0, cy = p.gaze_y_q8 / 256.0, alpha = p.alpha_q8 / 256.0;
    const double ex = fmax(cx, r->W - cx), ey = fmax(cy, r->H - cy), L = log(sqrt(ex * ex + ey * ey));
    size_t k = 0;
    for (int j = 0; j < g.lp_h; j++) {
        for (int i = g.u0; i < g.lp_w; i++) {
            double u, v;
            ref_fov_lp_jitter(f->jitter, L, alpha, g.lp_w, g.lp_h, i, j, f->jx, f->jy, &u, &v);
            const double th = 2 * M_PI * v / g.lp_h;
            const double c = cos(th), s = sin(th);
            const double rad = exp(L * pow(u / g.lp_w, alpha));
            xy[2 * k] = (float)(cx + rad * c);
            xy[2 * k + 1] = (float)(cy + rad * s);
            cone[k] = (float)ref_fov_lod_cone(r->cfg.fov_lod, rad, L, alpha, u / g.lp_w, g.lp_w, g.lp_h);
            k++;
        }
    }
    for (int j = 0; j < g.height; j++) {
        int32_t x0;
        const uint32_t n = tdc_fov_disk_span(&g, j, &x0);
        for (uint32_t i = 0; i < n; i++) {
            xy[2 * k] = (float)(x0 + (int32_t)i + 0.5);
            xy[2 * k + 1] = (float)(j + 0.5);
            cone[k] = 1.0f;
            k++;
        }
    }
    r->fov_n = (int)k;
    r->fov_lp = nlp;
    if (lp_samples) *lp_samples = nlp;
    if (disk_pixels) *disk_pixels = nd;
    return 0;
}

int tdc_render_set_samples(tdc_render_t *r, const double *xy, int n)
{
    if (!r || !xy || n < 1 || n > 64 * 1024 * 1024) return -1;
    for (int i = 0; i < 2 * n; i++)
        if (!(fabs(xy[i]) < 1e6)) return -1;
    float *p = realloc(r->fov_xy, (size_t)n * 2 * sizeof(float));
    if (!p) return -1;
    r->fov_xy = p;
    free(r->fov_cone); /* arbitrary positions: one display pixel's cone each */
    r->fov_cone = NULL;
    for (int i = 0; i < 2 * n; i++) p[i] = (float)xy[i];
    r->fov_n = n;
    r->fov_lp = 0;
    return 0;
}

float tdc_render_fov_cone(const tdc_render_t *r, int k)
{
    if (!r || k < 0 || k >= r->fov_n) return 0;
    return r->fov_cone ? r->fov_cone[k] : 1.0f;
}
