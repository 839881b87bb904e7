/*
 * zeng_filter.c - spatial filters and history operations (zeng_filter.h).
 */
#include "zeng/zeng_filter.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double edge_w(const zf_guide_t *g, const zf_edges_t *e, size_t p, size_t q)
{
    double w = 1.0;
    if (e->same_id && g->id[p] != g->id[q]) {
        return 0.0;
    }
    if (e->sigma_depth > 0) {
        double dp = g->depth[p], dq = g->depth[q];
        double rel = (dp - dq) / (fmax(dp, 1e-9) * e->sigma_depth);
        w *= exp(-0.5 * rel * rel);
    }
    if (e->normal_power > 0) {
        const double *a = g->nrm + 3 * p, *b = g->nrm + 3 * q;
        double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        if (d <= 0) {
            return 0.0;
        }
        /* normal_power a power of two (32, 128): squarings, as exact as pow */
        double pw = d;
        for (double k = 1; k < e->normal_power; k *= 2) {
            pw *= pw;
        }
        w *= pw;
    }
    return w;
}

static void bilateral_pass(const double *in, int ch, const zf_guide_t *g, const zf_edges_t *e, int r, double sigma,
                           const double *sigma_px, int dx, int dy, double *out)
{
    const int w = g->w, h = g->h;
    double gk[ZF_MAX_R + 1], sg = -1;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const size_t p = (size_t)y * w + x;
            double s = sigma_px ? sigma_px[p] : sigma;
            if (!(s > 0)) {
                memcpy(out + p * ch, in + p * ch, ch * sizeof(double));
                continue;
            }
            if (s != sg) {
                sg = s;
                for (int k = 0; k <= r; k++) {
                    gk[k] = exp(-0.5 * k * k / (s * s));
                }
            }
            double acc[4] = {0, 0, 0, 0}, ws = 0;
            for (int k = -r; k <= r; k++) {
                int xx = x + k * dx, yy = y + k * dy;
                if (xx < 0 || yy < 0 || xx >= w || yy >= h) {
                    continue;
                }
                const size_t q = (size_t)yy * w + xx;
                double wk = gk[k < 0 ? -k : k] * edge_w(g, e, p, q);
                for (int c = 0; c < ch; c++) {
                    acc[c] += wk * in[q * ch + c];
                }
                ws += wk;
            }
            for (int c = 0; c < ch; c++) {
                out[p * ch + c] = ws > 0 ? acc[c] / ws : in[p * ch + c];
            }
        }
    }
}

void zf_bilateral(const double *in, int ch, const zf_guide_t *g, const zf_edges_t *e, int r, double sigma,
                  const double *sigma_px, double *out, double *tmp)
{
    bilateral_pass(in, ch, g, e, r, sigma, sigma_px, 1, 0, tmp);
    bilateral_pass(tmp, ch, g, e, r, sigma, sigma_px, 0, 1, out);
}

static const double k_b3[5] = {1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16};

/* One tap of a 5x5 a-trous kernel at offset (dx, dy) from (x, y): its
 * index in *q, 0 when it falls outside the frame (the tap is skipped and the
 * weights renormalised). */
static int atrous_tap(int w, int h, int x, int y, int dx, int dy, size_t *q)
{
    const int xx = x + dx, yy = y + dy;
    if (xx < 0 || yy < 0 || xx >= w || yy >= h) {
        return 0;
    }
    *q = (size_t)yy * w + xx;
    return 1;
}

void zf_atrous(const double *in, int ch, const zf_guide_t *g, const zf_edges_t *e, int levels, double sigma_c,
               double *out, double *tmp)
{
    const int w = g->w, h = g->h;
    const size_t n = (size_t)w * h * ch;
    /* ping-pong so that the last level lands in out */
    double *src = (levels % 2) ? tmp : out, *dst = (levels % 2) ? out : tmp;
    memcpy(src, in, n * sizeof(double));
    for (int l = 0; l < levels; l++) {
        const int step = 1 << l;
        const double sc = sigma_c / (double)(1 << l);
        for (int y = 0; y < h; y++) {
            for (int x = 0; x < w; x++) {
                const size_t p = (size_t)y * w + x;
                double acc[4] = {0, 0, 0, 0}, ws = 0;
                for (int j = -2; j <= 2; j++) {
                    for (int i = -2; i <= 2; i++) {
                        size_t q;
                        if (!atrous_tap(w, h, x, y, i * step, j * step, &q)) {
                            continue;
                        }
                        double wk = k_b3[i + 2] * k_b3[j + 2] * edge_w(g, e, p, q);
                        if (sigma_c > 0 && wk > 0) {
                            double d2 = 0;
                            for (int c = 0; c < ch; c++) {
                                double d = src[q * ch + c] - src[p * ch + c];
                                d2 += d * d;
                            }
                            wk *= exp(-d2 / (sc * sc));
                        }
                        for (int c = 0; c < ch; c++) {
                            acc[c] += wk * src[q * ch + c];
                        }
                        ws += wk;
                    }
                }
                for (int c = 0; c < ch; c++) {
                    dst[p * ch + c] = ws > 0 ? acc[c] / ws : src[p * ch + c];
                }
            }
        }
        double *t = src;
        src = dst;
        dst = t;
    }
}

static double lum(const double *c, int ch)
{
    double s = 0;
    for (int k = 0; k < ch; k++) {
        s += c[k];
    }
    return s / ch;
}

void zf_svgf_level(const double *col, const double *var, int ch, const zf_guide_t *g, const zf_edges_t *e,
                   int level, double *col_out, double *var_out)
{
    const int w = g->w, h = g->h, step = 1 << level;
    static const double g3[3] = {0.25, 0.5, 0.25};
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const size_t p = (size_t)y * w + x;
            double vs = 0, vw = 0;
            for (int j = -1; j <= 1; j++) {
                for (int i = -1; i <= 1; i++) {
                    int xx = x + i, yy = y + j;
                    if (xx < 0 || yy < 0 || xx >= w || yy >= h) {
                        continue;
                    }
                    vs += g3[i + 1] * g3[j + 1] * var[(size_t)yy * w + xx];
                    vw += g3[i + 1] * g3[j + 1];
                }
            }
            const double sl = 4.0 * sqrt(fmax(0.0, vs / vw)) + 1e-6;
            const double lp = lum(col + p * ch, ch);
            double acc[4] = {0, 0, 0, 0}, ws = 0, va = 0;
            for (int j = -2; j <= 2; j++) {
                for (int i = -2; i <= 2; i++) {
                    size_t q;
                    if (!atrous_tap(w, h, x, y, i * step, j * step, &q)) {
                        continue;
                    }
                    double wk = k_b3[i + 2] * k_b3[j + 2] * edge_w(g, e, p, q) *
                                exp(-fabs(lum(col + q * ch, ch) - lp) / sl);
                    for (int c = 0; c < ch; c++) {
                        acc[c] += wk * col[q * ch + c];
                    }
                    ws += wk;
                    va += wk * wk * var[q];
                }
            }
            for (int c = 0; c < ch; c++) {
                col_out[p * ch + c] = ws > 0 ? acc[c] / ws : col[p * ch + c];
            }
            var_out[p] = ws > 0 ? va / (ws * ws) : var[p];
        }
    }
}

int zf_fetch(const double *img, int ch, int w, int h, double x, double y, const int *ids, int want, double *out)
{
    const double fx = x - 0.5, fy = y - 0.5;
    if (!(fx > -1.0 && fy > -1.0 && fx < w && fy < h)) {
        return 0;
    }
    const int x0 = (int)floor(fx), y0 = (int)floor(fy);
    const double ax = fx - x0, ay = fy - y0;
    double acc[4] = {0, 0, 0, 0}, ws = 0;
    for (int j = 0; j < 2; j++) {
        for (int i = 0; i < 2; i++) {
            int xx = x0 + i, yy = y0 + j;
            if (xx < 0 || yy < 0 || xx >= w || yy >= h) {
                continue;
            }
            const size_t q = (size_t)yy * w + xx;
            if (ids && ids[q] != want) {
                continue;
            }
            double wk = (i ? ax : 1 - ax) * (j ? ay : 1 - ay);
            if (wk <= 0) {
                continue;
            }
            for (int c = 0; c < ch; c++) {
                acc[c] += wk * img[q * ch + c];
            }
            ws += wk;
        }
    }
    if (ws <= 1e-9) {
        return 0;
    }
    for (int c = 0; c < ch; c++) {
        out[c] = acc[c] / ws;
    }
    return 1;
}

void zf_moments(const double *img, int ch, int w, int h, int x, int y, int r, double *mu, double *sd)
{
    double s1[4] = {0, 0, 0, 0}, s2[4] = {0, 0, 0, 0};
    int n = 0;
    for (int yy = y - r; yy <= y + r; yy++) {
        for (int xx = x - r; xx <= x + r; xx++) {
            if (xx < 0 || yy < 0 || xx >= w || yy >= h) {
                continue;
            }
            const double *v = img + ((size_t)yy * w + xx) * ch;
            for (int c = 0; c < ch; c++) {
                s1[c] += v[c];
                s2[c] += v[c] * v[c];
            }
            n++;
        }
    }
    for (int c = 0; c < ch; c++) {
        mu[c] = s1[c] / n;
        sd[c] = sqrt(fmax(0.0, s2[c] / n - mu[c] * mu[c]));
    }
}
