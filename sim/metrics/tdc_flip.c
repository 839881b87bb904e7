/*
 * tdc_flip.c - the FLIP difference evaluator (Andersson, Nilsson,
 * Akenine-Moller, Oskarsson, Astrom, Fairchild, HPG 2020), LDR version,
 * written from the paper's definition (see tdc_metrics.h for the outline).
 *
 * Colour pipeline: linear RGB (sRGB primaries, D65) -> XYZ -> YyCxCz
 *   Yy = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn),
 * each channel convolved with its contrast sensitivity function written as
 * a spatial sum of Gaussians (x in degrees)
 *   S(x) = a1 sqrt(pi/b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi/b2) exp(-pi^2 x^2 / b2)
 * evaluated in 2-D at the radial distance (x^2 = dx^2 + dy^2, as the paper's
 * eq. 2 and NVlabs flip v1.6's generate_spatial_filter do): each Gaussian is
 * separable, exp(-pi^2 (dx^2 + dy^2) / b) = g(dx) g(dy), and keeps its
 * amplitude a sqrt(pi / b) - not (a sqrt(pi / b))^2 = a pi / b, which an
 * earlier version used and which weighted the blue-yellow channel's two
 * Gaussians 34.1 sqrt(pi/0.04) : 13.5 sqrt(pi/0.025) wrongly (per-pixel
 * maps off by up to 0.02 from flip v1.6)
 *   achromatic a1 = 1,    b1 = 0.0047, a2 = 0,    b2 = 1e-5
 *   red-green  a1 = 1,    b1 = 0.0053, a2 = 0,    b2 = 1e-5
 *   blue-yell. a1 = 34.1, b1 = 0.04,   a2 = 13.5, b2 = 0.025
 * (kernel radius ceil(3 sqrt(b_max / (2 pi^2)) ppd), normalised to sum 1),
 * then back to linear RGB, clamped to [0, 1], to CIE L*a*b*, Hunt-adjusted
 * (a*, b* scaled by 0.01 L*), and compared with HyAB
 *   d = |dL| + sqrt(da^2 + db^2).
 * Colour error: d^0.7 remapped against cmax = HyAB(green, blue)^0.7 so that
 * [0, 0.4 cmax) maps linearly to [0, 0.95) and [0.4 cmax, cmax] to [0.95, 1].
 * Feature error on the achromatic channel normalised to [0, 1]:
 * first- and second-derivative-of-Gaussian responses (sigma = 0.5 * 0.082
 * degrees * ppd, positive and negative lobes each normalised to unit sum),
 *   Delta_f = (max(| |e_r| - |e_t| |, | |p_r| - |p_t| |) / sqrt 2)^0.5.
 * Pixel error: Delta_c^(1 - Delta_f).
 */
#include "metrics/tdc_metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/tdc_filter.h"
#include "metrics/tdc_powtab.h"
#include "tdc_par.h"

#define PI 3.14159265358979323846

static const double k_rgb2xyz[9] = {0.4124564, 0.3575761, 0.1804375, 0.2126729, 0.7151522,
                                    0.0721750, 0.0193339, 0.1191920, 0.9503041};
static const double k_xyz2rgb[9] = {3.2404542, -1.5371385, -0.4985314, -0.9692660, 1.8760108,
                                    0.0415560, 0.0556434,  -0.2040259, 1.0572252};
/* Reference white: XYZ of linear RGB (1, 1, 1). */
#define XN (0.4124564 + 0.3575761 + 0.1804375)
#define YN 1.0
#define ZN (0.0193339 + 0.1191920 + 0.9503041)

static void mat3(const double *m, const double *in, double *out)
{
    out[0] = m[0] * in[0] + m[1] * in[1] + m[2] * in[2];
    out[1] = m[3] * in[0] + m[4] * in[1] + m[5] * in[2];
    out[2] = m[6] * in[0] + m[7] * in[1] + m[8] * in[2];
}

static void rgb_to_ycxcz(const double *rgb, double *o)
{
    double xyz[3];
    mat3(k_rgb2xyz, rgb, xyz);
    double xr = xyz[0] / XN, yr = xyz[1] / YN, zr = xyz[2] / ZN;
    o[0] = 116.0 * yr - 16.0;
    o[1] = 500.0 * (xr - yr);
    o[2] = 200.0 * (yr - zr);
}

static void ycxcz_to_rgb(const double *c, double *rgb)
{
    double yr = (c[0] + 16.0) / 116.0;
    double xyz[3] = {(c[1] / 500.0 + yr) * XN, yr * YN, (yr - c[2] / 200.0) * ZN};
    mat3(k_xyz2rgb, xyz, rgb);
}

/* cbrt by table (tdc_powtab.h: 7e-9 relative, below the float L*a*b* kept) */
static double lab_f(const tdc_powtab_t *cb, double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? tdc_powtab(cb, t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

static void rgb_to_lab_hunt(const tdc_powtab_t *cb, const double *rgb, double *lab)
{
    double xyz[3];
    mat3(k_rgb2xyz, rgb, xyz);
    double fx = lab_f(cb, xyz[0] / XN), fy = lab_f(cb, xyz[1] / YN), fz = lab_f(cb, xyz[2] / ZN);
    double L = 116.0 * fy - 16.0;
    lab[0] = L;
    lab[1] = 0.01 * L * 500.0 * (fx - fy);
    lab[2] = 0.01 * L * 200.0 * (fy - fz);
}

static double hyab(const double *a, const double *b)
{
    double da = a[1] - b[1], db = a[2] - b[2];
    return fabs(a[0] - b[0]) + sqrt(da * da + db * db);
}

/* Prefiltered YyCxCz -> clamped linear RGB -> Hunt-adjusted L*a*b* (lab_out,
 * 3 floats per pixel) and the feature plane (Yy + 16) / 116 (yfeat). */
static int flip_color_prepare(const double *lin, int w, int h, double ppd, float *lab_out, float *yfeat, float *work)
{
    static const double a1[3] = {1.0, 1.0, 34.1}, b1[3] = {0.0047, 0.0053, 0.04};
    static const double a2[3] = {0.0, 0.0, 13.5}, b2[3] = {1e-5, 1e-5, 0.025};
    const double bmax = 0.04;
    int r = (int)ceil(3.0 * sqrt(bmax / (2.0 * PI * PI)) * ppd);
    if (r < 1) {
        r = 1;
    }
    if (r > TDC_FILTER_MAX_R) {
        return -1;
    }
    size_t n = (size_t)w * h;
    const tdc_powtab_t *cb = tdc_powtab_metrics(TDC_POWTAB_CBRT);
    float *plane[3] = {work, work + n, work + 2 * n};
    float *filt[3] = {work + 3 * n, work + 4 * n, work + 5 * n};
    float *f2 = work + 6 * n, *tmp = work + 7 * n;
    TDC_PAR_FOR((size_t)w * h)
    for (int y = 0; y < h; y++) {
        for (size_t i = (size_t)y * w; i < (size_t)(y + 1) * w; i++) {
            double o[3];
            rgb_to_ycxcz(lin + 3 * i, o);
            plane[0][i] = (float)o[0];
            plane[1][i] = (float)o[1];
            plane[2][i] = (float)o[2];
            yfeat[i] = (float)((o[0] + 16.0) / 116.0);
        }
    }
    for (int c = 0; c < 3; c++) {
        /* 2-D kernel (w1 g1(x) g1(y) + w2 g2(x) g2(y)) / total with
         * w = a sqrt(pi / b); each term as a separable pass whose 1-D
         * kernels carry sqrt(w / total) */
        double g1[2 * TDC_FILTER_MAX_R + 1], g2[2 * TDC_FILTER_MAX_R + 1];
        float k1[2 * TDC_FILTER_MAX_R + 1], k2[2 * TDC_FILTER_MAX_R + 1];
        double s1 = 0.0, s2 = 0.0;
        for (int j = -r; j <= r; j++) {
            double xd = (double)j / ppd; /* degrees */
            g1[j + r] = exp(-PI * PI * xd * xd / b1[c]);
            g2[j + r] = exp(-PI * PI * xd * xd / b2[c]);
            s1 += g1[j + r];
            s2 += g2[j + r];
        }
        double w1 = a1[c] * sqrt(PI / b1[c]), w2 = a2[c] * sqrt(PI / b2[c]);
        double total = w1 * s1 * s1 + w2 * s2 * s2;
        double q1 = sqrt(w1 / total), q2 = sqrt(w2 / total);
        for (int j = 0; j < 2 * r + 1; j++) {
            k1[j] = (float)(q1 * g1[j]);
            k2[j] = (float)(q2 * g2[j]);
        }
        if (tdc_sep_filter_f(plane[c], filt[c], tmp, w, h, k1, k1, r, TDC_EDGE_CLAMP)) {
            return -1;
        }
        if (w2 > 0.0) {
            if (tdc_sep_filter_f(plane[c], f2, tmp, w, h, k2, k2, r, TDC_EDGE_CLAMP)) {
                return -1;
            }
            TDC_PAR_FOR((size_t)w * h)
            for (int y = 0; y < h; y++) {
                for (size_t i = (size_t)y * w; i < (size_t)(y + 1) * w; i++) {
                    filt[c][i] += f2[i];
                }
            }
        }
    }
    TDC_PAR_FOR((size_t)w * h)
    for (int y = 0; y < h; y++) {
        for (size_t i = (size_t)y * w; i < (size_t)(y + 1) * w; i++) {
            double c[3] = {filt[0][i], filt[1][i], filt[2][i]}, rgb[3], lab[3];
            ycxcz_to_rgb(c, rgb);
            for (int k = 0; k < 3; k++) {
                rgb[k] = rgb[k] < 0.0 ? 0.0 : (rgb[k] > 1.0 ? 1.0 : rgb[k]);
            }
            rgb_to_lab_hunt(cb, rgb, lab);
            lab_out[3 * i] = (float)lab[0];
            lab_out[3 * i + 1] = (float)lab[1];
            lab_out[3 * i + 2] = (float)lab[2];
        }
    }
    return 0;
}

/* Edge and point feature magnitudes of plane y (work: 3 w*h floats). */
static int flip_features(const float *y, int w, int h, double ppd, float *edge, float *point, float *work)
{
    double sigma = 0.5 * 0.082 * ppd;
    int r = (int)ceil(3.0 * sigma);
    if (r < 1) {
        r = 1;
    }
    if (r > TDC_FILTER_MAX_R) {
        return -1;
    }
    int kn = 2 * r + 1;
    size_t n = (size_t)w * h;
    float *gx = work, *gy = work + n, *tmp = work + 2 * n;
    double g[2 * TDC_FILTER_MAX_R + 1], d1[2 * TDC_FILTER_MAX_R + 1], d2[2 * TDC_FILTER_MAX_R + 1];
    float fg[2 * TDC_FILTER_MAX_R + 1], fd1[2 * TDC_FILTER_MAX_R + 1], fd2[2 * TDC_FILTER_MAX_R + 1];
    double gs = 0.0, d1p = 0.0, d2p = 0.0, d2n = 0.0;
    for (int j = -r; j <= r; j++) {
        double e = exp(-(double)(j * j) / (2.0 * sigma * sigma));
        g[j + r] = e;
        d1[j + r] = -(double)j * e;
        d2[j + r] = ((double)(j * j) / (sigma * sigma) - 1.0) * e;
        gs += e;
        if (d1[j + r] > 0.0) {
            d1p += d1[j + r];
        }
        if (d2[j + r] > 0.0) {
            d2p += d2[j + r];
        } else {
            d2n -= d2[j + r];
        }
    }
    for (int j = 0; j < kn; j++) {
        fg[j] = (float)(g[j] / gs);
        fd1[j] = (float)(d1[j] / d1p); /* antisymmetric: negative lobe sums to -1 too */
        fd2[j] = (float)(d2[j] > 0.0 ? d2[j] / d2p : d2[j] / d2n);
    }
    for (int pass = 0; pass < 2; pass++) {
        const float *d = pass ? fd2 : fd1;
        float *o = pass ? point : edge;
        if (tdc_sep_filter_f(y, gx, tmp, w, h, d, fg, r, TDC_EDGE_CLAMP) ||
            tdc_sep_filter_f(y, gy, tmp, w, h, fg, d, r, TDC_EDGE_CLAMP)) {
            return -1;
        }
        TDC_PAR_FOR((size_t)w * h)
        for (int yr = 0; yr < h; yr++) {
            for (size_t i = (size_t)yr * w; i < (size_t)(yr + 1) * w; i++) {
                o[i] = sqrtf(gx[i] * gx[i] + gy[i] * gy[i]);
            }
        }
    }
    return 0;
}

/* The per-image half of FLIP: L*a*b* of the prefiltered image (3 floats per
 * pixel) and its edge and point feature magnitudes (1 each); work: 9 floats
 * per pixel. */
static int flip_image(const double *lin, int w, int h, double ppd, float *lab, float *edge, float *point, float *work)
{
    size_t n = (size_t)w * h;
    float *yf = work + 8 * n;
    return flip_color_prepare(lin, w, h, ppd, lab, yf, work) || flip_features(yf, w, h, ppd, edge, point, work);
}

size_t tdc_flip_work_bytes(int w, int h)
{
    return sizeof(float) * (size_t)w * h * 14 + sizeof(double) * (size_t)h;
}

int tdc_flip_prepare(tdc_flip_ref_t *ref, const double *lin, int w, int h, double ppd, void *work)
{
    size_t n = (size_t)w * h;
    if (w < 1 || h < 1 || w > TDC_FILTER_MAX_W) {
        return -1;
    }
    ref->buf = tdc_metrics_reserve(ref->buf, &ref->cap, sizeof(float) * 5 * n);
    float *own = work ? NULL : malloc(tdc_flip_work_bytes(w, h));
    if (!ref->buf || (!work && !own)) {
        free(own);
        return -1;
    }
    ref->w = w;
    ref->h = h;
    ref->ppd = ppd;
    int bad = flip_image(lin, w, h, ppd, ref->buf, ref->buf + 3 * n, ref->buf + 4 * n, work ? (float *)work : own);
    free(own);
    return bad ? -1 : 0;
}

void tdc_flip_ref_free(tdc_flip_ref_t *ref)
{
    free(ref->buf);
    memset(ref, 0, sizeof(*ref));
}

double tdc_flip_vs(const tdc_flip_ref_t *ref, const double *test, double *map, void *work)
{
    const double qc = 0.7, pc = 0.4, pt = 0.95, qf = 0.5;
    const int w = ref->w, h = ref->h;
    size_t n = (size_t)w * h;
    /* lab t 3, features t 2, work 9 floats per pixel; row sums */
    float *own = work ? NULL : malloc(tdc_flip_work_bytes(w, h));
    float *mem = work ? (float *)work : own;
    if (!mem) {
        return -1.0;
    }
    const float *lab_r = ref->buf, *e_r = ref->buf + 3 * n, *p_r = ref->buf + 4 * n;
    float *lab_t = mem, *e_t = mem + 3 * n, *p_t = mem + 4 * n, *fw = mem + 5 * n;
    double *rows = (double *)(void *)(mem + 14 * n);
    if (flip_image(test, w, h, ref->ppd, lab_t, e_t, p_t, fw)) {
        free(own);
        return -1.0;
    }
    const double green[3] = {0.0, 1.0, 0.0}, blue[3] = {0.0, 0.0, 1.0};
    const tdc_powtab_t *cb = tdc_powtab_metrics(TDC_POWTAB_CBRT), *pq = tdc_powtab_metrics(TDC_POWTAB_HYAB);
    double lg[3], lb[3];
    rgb_to_lab_hunt(cb, green, lg);
    rgb_to_lab_hunt(cb, blue, lb);
    const double cmax = tdc_powtab(pq, hyab(lg, lb)); /* ^qc, qc = 0.7 */
    TDC_PAR_FOR((size_t)w * h)
    for (int y = 0; y < h; y++) {
        double sum = 0.0;
        for (size_t i = (size_t)y * w; i < (size_t)(y + 1) * w; i++) {
            double lr[3] = {lab_r[3 * i], lab_r[3 * i + 1], lab_r[3 * i + 2]};
            double lt[3] = {lab_t[3 * i], lab_t[3 * i + 1], lab_t[3 * i + 2]};
            double dc = tdc_powtab(pq, hyab(lr, lt)); /* ^qc */
            if (dc < pc * cmax) {
                dc = pt / (pc * cmax) * dc;
            } else {
                dc = pt + (dc - pc * cmax) / (cmax - pc * cmax) * (1.0 - pt);
            }
            if (dc > 1.0) {
                dc = 1.0;
            }
            double fe = fabs((double)e_r[i] - e_t[i]), fp = fabs((double)p_r[i] - p_t[i]);
            double df = sqrt((fe > fp ? fe : fp) / sqrt(2.0)); /* ^qf, qf = 0.5 */
            if (df > 1.0) {
                df = 1.0;
            }
            double e = pow(dc, 1.0 - df);
            if (map) {
                map[i] = e;
            }
            sum += e;
        }
        rows[y] = sum;
    }
    (void)qf, (void)qc; /* qc is the HYAB table's exponent */
    double sum = tdc_par_sum_rows(rows, h);
    free(own);
    return n ? sum / (double)n : 0.0;
}

double tdc_flip(const double *ref, const double *test, int w, int h, double ppd, double *map)
{
    tdc_flip_ref_t r = {0};
    double v = tdc_flip_prepare(&r, ref, w, h, ppd, NULL) ? -1.0 : tdc_flip_vs(&r, test, map, NULL);
    tdc_flip_ref_free(&r);
    return v;
}
