/*
 * ref_fov_lr.c - double-precision reference of the log-rectilinear kind;
 * see ref_fov_lr.h.  Written from the equations, not from the fixed-point
 * code (natural logarithms here, log2 tables there: the base cancels in u).
 */
#include "ref_fov_lr.h"

#include <math.h>
#include <stdlib.h>

#include "tdc_sim_codes.h" /* tdc_sim_encode_code: the sources' encoder */

#define K_MAX (65535.0 / 16.0)

static double warp(const ref_fov_lr_axis_t *a, double d)
{
    const double s = log1p(fabs(d) / a->k);
    return d < 0 ? -s : s;
}

void ref_fov_lr_axis(ref_fov_lr_axis_t *a, double c, double k, int N, int n)
{
    a->c = c;
    a->k = k;
    a->N = N;
    a->n = n;
    a->s0 = warp(a, -c);
    a->S = warp(a, N - c) - a->s0;
}

double ref_fov_lr_fwd(const ref_fov_lr_axis_t *a, double x)
{
    x = fmin(fmax(x, 0), a->N);
    return a->n * (warp(a, x - a->c) - a->s0) / a->S;
}

double ref_fov_lr_inv(const ref_fov_lr_axis_t *a, double u)
{
    const double t = a->s0 + a->S * u / a->n;
    const double d = a->k * expm1(fabs(t));
    return a->c + (t < 0 ? -d : d);
}

double ref_fov_lr_density(const ref_fov_lr_axis_t *a, double x)
{
    return a->n / (a->S * (a->k + fabs(x - a->c)));
}

double ref_fov_lr_k(int N, int n, double c)
{
    /* f(k) = k S(k) is strictly increasing (d/dk k ln(1 + a/k) = ln(1 + a/k) - a/(k + a) > 0,
     * and the difference of two such terms when the gaze is off the screen also grows) */
    double lo = 1, hi = K_MAX;
    ref_fov_lr_axis_t a;
    ref_fov_lr_axis(&a, c, hi, N, n);
    if (hi * a.S <= n) {
        return hi;
    }
    ref_fov_lr_axis(&a, c, lo, N, n);
    if (lo * a.S >= n) {
        return lo;
    }
    for (int it = 0; it < 100; it++) {
        const double mid = sqrt(lo * hi);
        ref_fov_lr_axis(&a, c, mid, N, n);
        if (mid * a.S < n) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return sqrt(lo * hi);
}

void ref_fov_lin_lut(const double gamma[3], double lut[3 * 256])
{
    for (int ch = 0; ch < 3; ch++) {
        for (int k = 0; k < 256; k++) {
            lut[256 * ch + k] = pow(k / 255.0, gamma[ch]);
        }
    }
}

double *ref_fov_lr_sat(const uint8_t *img, size_t stride, int W, int H, const double *lut)
{
    const size_t w1 = (size_t)W + 1;
    double *sat = calloc(w1 * ((size_t)H + 1) * 3, sizeof(double));
    if (!sat) {
        return NULL;
    }
    for (int y = 0; y < H; y++) {
        double row[3] = {0, 0, 0};
        for (int x = 0; x < W; x++) {
            for (int ch = 0; ch < 3; ch++) {
                const uint8_t code = img[(size_t)y * stride + (size_t)x * 3 + ch];
                row[ch] += lut ? lut[256 * ch + code] : code;
                sat[(((size_t)y + 1) * w1 + x + 1) * 3 + ch] = sat[((size_t)y * w1 + x + 1) * 3 + ch] + row[ch];
            }
        }
    }
    return sat;
}

/* SAT at a fractional point: bilinear in the cell (exact for a piecewise-constant picture) */
static void sat_at(const double *sat, int W, int H, double x, double y, double out[3])
{
    x = fmin(fmax(x, 0), W);
    y = fmin(fmax(y, 0), H);
    int i = (int)floor(x), j = (int)floor(y);
    i = i >= W ? W - 1 : i;
    j = j >= H ? H - 1 : j;
    const double fx = x - i, fy = y - j;
    const size_t w1 = (size_t)W + 1;
    for (int ch = 0; ch < 3; ch++) {
        const double a = sat[((size_t)j * w1 + i) * 3 + ch], b = sat[((size_t)j * w1 + i + 1) * 3 + ch];
        const double c = sat[(((size_t)j + 1) * w1 + i) * 3 + ch], d = sat[(((size_t)j + 1) * w1 + i + 1) * 3 + ch];
        out[ch] = (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
    }
}

void ref_fov_lr_box(const double *sat, int W, int H, double x0, double y0, double x1, double y1, double out[3])
{
    double a[3], b[3], c[3], d[3];
    sat_at(sat, W, H, x0, y0, a);
    sat_at(sat, W, H, x1, y0, b);
    sat_at(sat, W, H, x0, y1, c);
    sat_at(sat, W, H, x1, y1, d);
    for (int ch = 0; ch < 3; ch++) {
        out[ch] = d[ch] - b[ch] - c[ch] + a[ch];
    }
}

void ref_fov_lr_box_mean(const double *sat, int W, int H, double x, double y, double side, double out[3])
{
    x = fmin(fmax(x, 0), W);
    y = fmin(fmax(y, 0), H);
    const double x0 = fmax(x - side / 2, 0), x1 = fmin(x + side / 2, W);
    const double y0 = fmax(y - side / 2, 0), y1 = fmin(y + side / 2, H);
    ref_fov_lr_box(sat, W, H, x0, y0, x1, y1, out);
    const double area = (x1 - x0) * (y1 - y0);
    for (int ch = 0; ch < 3; ch++) {
        out[ch] /= area;
    }
}

void ref_fov_lr_buffer(const double *sat, int W, int H, const ref_fov_lr_axis_t *ax, const ref_fov_lr_axis_t *ay,
                       uint8_t *lp, size_t lp_stride, double *avg, const double *gamma)
{
    for (int j = 0; j < ay->n; j++) {
        const double y0 = ref_fov_lr_inv(ay, j), y1 = ref_fov_lr_inv(ay, j + 1);
        for (int m = 0; m < ax->n; m++) {
            const double x0 = ref_fov_lr_inv(ax, m), x1 = ref_fov_lr_inv(ax, m + 1);
            double s[3];
            ref_fov_lr_box(sat, W, H, x0, y0, x1, y1, s);
            const double area = (x1 - x0) * (y1 - y0);
            for (int ch = 0; ch < 3; ch++) {
                const double v = fmin(fmax(s[ch] / area, 0), gamma ? 1 : 255);
                lp[(size_t)j * lp_stride + (size_t)m * 3 + ch] =
                    gamma ? tdc_sim_encode_code(v, gamma[ch]) : (uint8_t)lround(v);
                if (avg) {
                    avg[((size_t)j * ax->n + m) * 3 + ch] = v;
                }
            }
        }
    }
}

static double texel_pos(const ref_fov_lr_axis_t *a, double x, int *near)
{
    const double u = ref_fov_lr_fwd(a, x);
    const int f = (int)floor(u);
    *near = f < 0 ? 0 : (f > a->n - 1 ? a->n - 1 : f);
    return fmin(fmax(u - 0.5, 0), a->n - 1);
}

void ref_fov_lr_sample(const ref_fov_lr_axis_t *ax, const ref_fov_lr_axis_t *ay, const uint8_t *lp, size_t lp_stride,
                       double x, double y, double c[3], int *iu, int *jv)
{
    const double tu = texel_pos(ax, x, iu), tv = texel_pos(ay, y, jv);
    const int m0 = (int)floor(tu), j0 = (int)floor(tv);
    const int m1 = m0 + 1 < ax->n ? m0 + 1 : m0, j1 = j0 + 1 < ay->n ? j0 + 1 : j0;
    const double fu = tu - m0, fv = tv - j0;
    for (int ch = 0; ch < 3; ch++) {
        const double a = lp[(size_t)j0 * lp_stride + (size_t)m0 * 3 + ch] * (1 - fu) +
                         lp[(size_t)j0 * lp_stride + (size_t)m1 * 3 + ch] * fu;
        const double b = lp[(size_t)j1 * lp_stride + (size_t)m0 * 3 + ch] * (1 - fu) +
                         lp[(size_t)j1 * lp_stride + (size_t)m1 * 3 + ch] * fu;
        c[ch] = a * (1 - fv) + b * fv;
    }
}
