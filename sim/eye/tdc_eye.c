/* tdc_eye.c - Talbot-Plateau integration along smooth pursuit (see tdc_eye.h). */
#include "eye/tdc_eye.h"

#include <math.h>
#include <string.h>

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

/* out += wgt * img shifted by (sx, sy): out(x) += wgt * img(x + s). */
static void accumulate_shifted(double *out, const double *img, int w, int h, double sx, double sy, double wgt)
{
    double fsx = floor(sx), fsy = floor(sy);
    if (sx == fsx && sy == fsy) {
        /* integer shift: plain copy with clamping */
        int ix = (int)fsx, iy = (int)fsy;
        for (int y = 0; y < h; y++) {
            int yy = y + iy < 0 ? 0 : (y + iy >= h ? h - 1 : y + iy);
            for (int x = 0; x < w; x++) {
                int xx = x + ix < 0 ? 0 : (x + ix >= w ? w - 1 : x + ix);
                const double *p = img + 3 * ((size_t)yy * w + xx);
                double *o = out + 3 * ((size_t)y * w + x);
                o[0] += wgt * p[0];
                o[1] += wgt * p[1];
                o[2] += wgt * p[2];
            }
        }
        return;
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double *o = out + 3 * ((size_t)y * w + x);
            for (int c = 0; c < 3; c++) {
                o[c] += wgt * tdc_eye_bilinear(img, w, h, x + sx, y + sy, c);
            }
        }
    }
}

void tdc_eye_perceive(const tdc_eye_cfg_t *cfg, const tdc_eye_slice_t *slices, int n, double t_end, const double v[2],
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
        if (b <= a || !slices[i].lin) {
            continue;
        }
        int nsub = (int)ceil(speed * (b - a) / step);
        nsub = nsub < 1 ? 1 : (nsub > 64 ? 64 : nsub);
        double dt = (b - a) / nsub;
        for (int k = 0; k < nsub; k++) {
            double tm = a + (k + 0.5) * dt;
            accumulate_shifted(out, slices[i].lin, w, h, vx * (tm - t_end), vy * (tm - t_end), dt / T * cfg->norm);
        }
    }
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
        for (size_t j = 0; j < n; j++) {
            out[j] += scratch[j] / nsteps;
        }
    }
    return nsteps;
}
