/* tdc_eye.c - Talbot-Plateau integration along smooth pursuit (see tdc_eye.h). */
#include "eye/tdc_eye.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_par.h"

double tdc_eye_bilinear(const double *img, int w, int h, double x, double y, int c)
{
    if (x < 0.0) {
        x = 0.0;
    }
    if (y < 0.0) {
        y = 0.0;
    }
    if (x > w - 1) {
        x = w - 1;
    }
    if (y > h - 1) {
        y = h - 1;
    }
    int x0 = (int)x, y0 = (int)y;
    int x1 = x0 + 1 < w ? x0 + 1 : x0, y1 = y0 + 1 < h ? y0 + 1 : y0;
    double fx = x - x0, fy = y - y0;
    double a = img[3 * ((size_t)y0 * w + x0) + c], b = img[3 * ((size_t)y0 * w + x1) + c];
    double d = img[3 * ((size_t)y1 * w + x0) + c], e = img[3 * ((size_t)y1 * w + x1) + c];
    return (a + (b - a) * fx) * (1.0 - fy) + (d + (e - d) * fx) * fy;
}

/* out += wgt * img shifted by (sx, sy): out(x) += wgt * img(x + s), img the
 * slice's light (lin, or lut[] of codes).  The shift is the same for every
 * pixel, so the clamped source columns and their weights are computed once
 * per call (the same expressions as tdc_eye_bilinear, so the same values)
 * and rows run in parallel. */
#define PIX(row, i, c) (lin ? lin[(row) + (i) + (c)] : lut[256 * (c) + codes[(row) + (i) + (c)]])
static int accumulate_shifted(double *out, const tdc_eye_slice_t *sl, int w, int h, double sx, double sy, double wgt)
{
    const double *lin = sl->lin, *lut = sl->lut;
    const uint8_t *codes = sl->codes;
    double fsx = floor(sx), fsy = floor(sy);
    int *col = malloc(sizeof(int) * 2 * (size_t)w);
    double *fxs = malloc(sizeof(double) * (size_t)w);
    if (!col || !fxs) {
        free(col);
        free(fxs);
        return -1;
    }
    int integer = sx == fsx && sy == fsy;
    for (int x = 0; x < w; x++) {
        if (integer) {
            int ix = (int)fsx, xx = x + ix < 0 ? 0 : (x + ix >= w ? w - 1 : x + ix);
            col[2 * x] = col[2 * x + 1] = 3 * xx;
            fxs[x] = 0.0;
            continue;
        }
        double xs = x + sx;
        xs = xs < 0.0 ? 0.0 : (xs > w - 1 ? w - 1 : xs);
        int x0 = (int)xs;
        col[2 * x] = 3 * x0;
        col[2 * x + 1] = 3 * (x0 + 1 < w ? x0 + 1 : x0);
        fxs[x] = xs - x0;
    }
    TDC_PAR_FOR((size_t)w * h)
    for (int y = 0; y < h; y++) {
        double *o = out + 3 * (size_t)y * w;
        if (integer) {
            /* integer shift: plain copy with clamping */
            int iy = (int)fsy, yy = y + iy < 0 ? 0 : (y + iy >= h ? h - 1 : y + iy);
            size_t r0 = 3 * (size_t)yy * w;
            for (int x = 0; x < w; x++) {
                int i0 = col[2 * x];
                o[3 * x] += wgt * PIX(r0, i0, 0);
                o[3 * x + 1] += wgt * PIX(r0, i0, 1);
                o[3 * x + 2] += wgt * PIX(r0, i0, 2);
            }
            continue;
        }
        double ys = y + sy;
        ys = ys < 0.0 ? 0.0 : (ys > h - 1 ? h - 1 : ys);
        int y0 = (int)ys;
        int y1 = y0 + 1 < h ? y0 + 1 : y0;
        double fy = ys - y0;
        size_t r0 = 3 * (size_t)y0 * w, r1 = 3 * (size_t)y1 * w;
        for (int x = 0; x < w; x++) {
            int i0 = col[2 * x], i1 = col[2 * x + 1];
            double fx = fxs[x];
            for (int c = 0; c < 3; c++) {
                double a = PIX(r0, i0, c), b = PIX(r0, i1, c), d = PIX(r1, i0, c), e = PIX(r1, i1, c);
                o[3 * x + c] += wgt * ((a + (b - a) * fx) * (1.0 - fy) + (d + (e - d) * fx) * fy);
            }
        }
    }
    free(col);
    free(fxs);
    return 0;
}
#undef PIX

int tdc_eye_perceive(const tdc_eye_cfg_t *cfg, const tdc_eye_slice_t *slices, int n, double t_end, const double v[2],
                     double *out)
{
    int w = cfg->width, h = cfg->height;
    double T = cfg->window_s, t_start = t_end - T;
    double g = cfg->pursuit_gain;
    double vx = v[0] * g, vy = v[1] * g;
    double speed = sqrt(vx * vx + vy * vy);
    double step = cfg->max_step_px > 0.0 ? cfg->max_step_px : 0.5;
    memset(out, 0, sizeof(double) * 3 * (size_t)w * h);
    for (int i = 0; i < n; i++) {
        double a = slices[i].t0 > t_start ? slices[i].t0 : t_start;
        double b = slices[i].t1 < t_end ? slices[i].t1 : t_end;
        if (b <= a || (!slices[i].lin && (!slices[i].codes || !slices[i].lut))) {
            continue;
        }
        int nsub = (int)ceil(speed * (b - a) / step);
        nsub = nsub < 1 ? 1 : (nsub > 64 ? 64 : nsub);
        double dt = (b - a) / nsub;
        for (int k = 0; k < nsub; k++) {
            double tm = a + (k + 0.5) * dt;
            if (accumulate_shifted(out, &slices[i], w, h, vx * (tm - t_end), vy * (tm - t_end), dt / T * cfg->norm)) {
                return -1;
            }
        }
    }
    return 0;
}

int tdc_eye_ground_truth(const tdc_eye_cfg_t *cfg, tdc_source_t *src, double t_end, const double v[2], int nsteps,
                         double *out, double *scratch)
{
    size_t n = 3 * (size_t)cfg->width * cfg->height;
    double g = cfg->pursuit_gain;
    double T = cfg->window_s;
    if (nsteps < 1) {
        nsteps = 1;
    }
    memset(out, 0, sizeof(double) * n);
    for (int i = 0; i < nsteps; i++) {
        double tm = t_end - T + (i + 0.5) * T / nsteps;
        double ox = v[0] * g * (tm - t_end), oy = v[1] * g * (tm - t_end);
        src->ground_truth(src, tm, ox, oy, scratch);
        TDC_PAR_FOR((size_t)cfg->width * cfg->height)
        for (int y = 0; y < cfg->height; y++) {
            for (size_t j = 3 * (size_t)y * cfg->width; j < 3 * (size_t)(y + 1) * cfg->width; j++) {
                out[j] += scratch[j] / nsteps;
            }
        }
    }
    return nsteps;
}
