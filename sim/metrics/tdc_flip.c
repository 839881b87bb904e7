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

/*
 * The per-image half of FLIP, streamed in bands of rows (tdc_filter.h): a
 * source row is converted to YyCxCz and the feature plane (Yy + 16) / 116,
 * edge-padded, and filtered horizontally - the CSF kernels per channel and
 * the feature kernels d1, g, d2 - into a ring; an output row is filtered
 * vertically, taken back to clamped linear RGB and Hunt-adjusted L*a*b*,
 * and its edge and point magnitudes formed.  The reference keeps those
 * rows (5 floats per pixel); a test image's rows are compared with the
 * reference's at once, so no plane of the test image is stored.
 */
#define KMAX (2 * TDC_FILTER_MAX_R + 1)
enum { RC0 = 0, RC2 = 3, RD1 = 6, RG = 7, RD2 = 8, NRING = 9 }; /* ring rows of a source row */

typedef struct {
    int w, h, rc, rf, rmax, two[3];
    float k1[3][KMAX], k2[3][KMAX];   /* CSF: first and (if two[c]) second Gaussian of channel c */
    float fg[KMAX], fd1[KMAX], fd2[KMAX]; /* features: Gaussian, first and second derivative */
} flip_kern_t;

/* The kernels at ppd; 0, or -1 if a radius exceeds TDC_FILTER_MAX_R. */
static int flip_kernels(flip_kern_t *K, int w, int h, double ppd)
{
    static const double a1[3] = {1.0, 1.0, 34.1}, b1[3] = {0.0047, 0.0053, 0.04};
    static const double a2[3] = {0.0, 0.0, 13.5}, b2[3] = {1e-5, 1e-5, 0.025};
    const double bmax = 0.04;
    K->w = w;
    K->h = h;
    int r = (int)ceil(3.0 * sqrt(bmax / (2.0 * PI * PI)) * ppd);
    K->rc = r < 1 ? 1 : r;
    double sigma = 0.5 * 0.082 * ppd;
    r = (int)ceil(3.0 * sigma);
    K->rf = r < 1 ? 1 : r;
    if (K->rc > TDC_FILTER_MAX_R || K->rf > TDC_FILTER_MAX_R) {
        return -1;
    }
    K->rmax = K->rc > K->rf ? K->rc : K->rf;
    r = K->rc;
    for (int c = 0; c < 3; c++) {
        /* 2-D kernel (w1 g1(x) g1(y) + w2 g2(x) g2(y)) / total with
         * w = a sqrt(pi / b); each term as a separable pass whose 1-D
         * kernels carry sqrt(w / total) */
        double g1[KMAX], g2[KMAX];
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
            K->k1[c][j] = (float)(q1 * g1[j]);
            K->k2[c][j] = (float)(q2 * g2[j]);
        }
        K->two[c] = w2 > 0.0;
    }
    r = K->rf;
    double g[KMAX], d1[KMAX], d2[KMAX];
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
    for (int j = 0; j < 2 * r + 1; j++) {
        K->fg[j] = (float)(g[j] / gs);
        K->fd1[j] = (float)(d1[j] / d1p); /* antisymmetric: negative lobe sums to -1 too */
        K->fd2[j] = (float)(d2[j] > 0.0 ? d2[j] / d2p : d2[j] / d2n);
    }
    return 0;
}

typedef struct {
    const flip_kern_t *K;
    const double *lin;
    /* prepare: the reference's planes are written; vs: compared with */
    const tdc_flip_ref_t *ref;
    float *lab_out, *e_out, *p_out;
    double *map, *rows, cmax;
    const tdc_powtab_t *cb, *pq;
    /* per thread */
    float *ring;               /* 2 rmax + 1 slots of NRING rows of w */
    float *pad;                /* 4 rows of w + 2 rmax: Yy, Cx, Cz, feature */
    float *f, *f2, *gx, *gy;   /* vertical results: f 3 rows */
    float *lab, *e, *p;        /* vs: the test image's row */
    double *dmap, *dex;        /* vs: the row's map (when none is wanted) and exponents */
} flip_band_t;

static void flip_src_row(void *ctx, int yy, int slot)
{
    flip_band_t *s = ctx;
    const flip_kern_t *K = s->K;
    const int w = K->w, rm = K->rmax;
    const size_t pw = (size_t)w + 2 * (size_t)rm;
    float *pad[4] = {s->pad, s->pad + pw, s->pad + 2 * pw, s->pad + 3 * pw};
    const double *lin = s->lin + 3 * (size_t)yy * w;
    TDC_SIMD
    for (int x = 0; x < w; x++) {
        double o[3];
        rgb_to_ycxcz(lin + 3 * (size_t)x, o);
        pad[0][rm + x] = (float)o[0];
        pad[1][rm + x] = (float)o[1];
        pad[2][rm + x] = (float)o[2];
        pad[3][rm + x] = (float)((o[0] + 16.0) / 116.0);
    }
    for (int q = 0; q < 4; q++) {
        for (int i = 1; i <= rm; i++) {
            pad[q][rm - i] = pad[q][rm];
            pad[q][rm + w - 1 + i] = pad[q][rm + w - 1];
        }
    }
    float *ring = s->ring + (size_t)slot * NRING * w;
    const float *src[KMAX];
    const int kc = 2 * K->rc + 1, kf = 2 * K->rf + 1;
    for (int c = 0; c < 3; c++) {
        for (int j = 0; j < kc; j++) {
            src[j] = pad[c] + (rm - K->rc) + j;
        }
        tdc_filter_taps_f(ring + (size_t)(RC0 + c) * w, src, K->k1[c], kc, w);
        if (K->two[c]) {
            tdc_filter_taps_f(ring + (size_t)(RC2 + c) * w, src, K->k2[c], kc, w);
        }
    }
    for (int j = 0; j < kf; j++) {
        src[j] = pad[3] + (rm - K->rf) + j;
    }
    tdc_filter_taps_f(ring + (size_t)RD1 * w, src, K->fd1, kf, w);
    tdc_filter_taps_f(ring + (size_t)RG * w, src, K->fg, kf, w);
    tdc_filter_taps_f(ring + (size_t)RD2 * w, src, K->fd2, kf, w);
}

/* Vertical taps k (radius r) over ring row kind q, output row y, into o. */
static void flip_vert(const flip_band_t *s, int q, const float *k, int r, int y, float *o)
{
    const flip_kern_t *K = s->K;
    const float *src[KMAX];
    tdc_filter_ring_rows_f(src, s->ring + (size_t)q * K->w, (size_t)NRING * K->w, 2 * K->rmax + 1, y, K->h, r,
                           TDC_EDGE_CLAMP);
    tdc_filter_taps_f(o, src, k, 2 * r + 1, K->w);
}

/* Filtered YyCxCz -> clamped linear RGB -> Hunt-adjusted L*a*b* of a row:
 * YyCxCz -> XYZ -> RGB (k_xyz2rgb), the clamp and rgb_to_lab_hunt in their
 * order, written element-wise (the cube root by tdc_powtab_pos: its
 * argument t > (6/29)^3 is positive and normal) so that the loop
 * vectorises - the same bits as pixel by pixel (test_metrics' FLIP maps;
 * 1440x1600: ~9 % of the run's CPU before). */
TDC_SIMD_CLONES static void flip_lab_row(const tdc_powtab_t *cb, const float *f0, const float *f1, const float *f2,
                                         float *lab, int w)
{
    const double *mi = k_xyz2rgb, *m = k_rgb2xyz, d = 6.0 / 29.0;
    TDC_SIMD
    for (int x = 0; x < w; x++) {
        const double yr = (f0[x] + 16.0) / 116.0;
        const double X = ((double)f1[x] / 500.0 + yr) * XN, Y = yr * YN, Z = (yr - (double)f2[x] / 200.0) * ZN;
        double r = mi[0] * X + mi[1] * Y + mi[2] * Z;
        double g = mi[3] * X + mi[4] * Y + mi[5] * Z;
        double b = mi[6] * X + mi[7] * Y + mi[8] * Z;
        r = r < 0.0 ? 0.0 : (r > 1.0 ? 1.0 : r);
        g = g < 0.0 ? 0.0 : (g > 1.0 ? 1.0 : g);
        b = b < 0.0 ? 0.0 : (b > 1.0 ? 1.0 : b);
        const double tx = (m[0] * r + m[1] * g + m[2] * b) / XN;
        const double ty = (m[3] * r + m[4] * g + m[5] * b) / YN;
        const double tz = (m[6] * r + m[7] * g + m[8] * b) / ZN;
        /* both branches, then a select: no control flow in the loop */
        const double px = tdc_powtab_pos(cb, tx), py = tdc_powtab_pos(cb, ty), pz = tdc_powtab_pos(cb, tz);
        const double qx = tx / (3.0 * d * d) + 4.0 / 29.0, qy = ty / (3.0 * d * d) + 4.0 / 29.0;
        const double qz = tz / (3.0 * d * d) + 4.0 / 29.0;
        const double fx = tx > d * d * d ? px : qx, fy = ty > d * d * d ? py : qy, fz = tz > d * d * d ? pz : qz;
        const double L = 116.0 * fy - 16.0;
        lab[3 * x] = (float)L;
        lab[3 * x + 1] = (float)(0.01 * L * 500.0 * (fx - fy));
        lab[3 * x + 2] = (float)(0.01 * L * 200.0 * (fy - fz));
    }
}

/* The error of one row (reference lab_r, e_r, p_r; test lab, fe, fp) into
 * map, summed left to right; ex: w doubles of scratch.  Colour and feature
 * terms element-wise (vectorised: tdc_powtab_pos for the HyAB^0.7 of a
 * distance that is 0 or at least a float's smallest step, selects for the
 * remap and the clamps), then the pixel error dc^(1 - df) and the sum -
 * the same values as pixel by pixel. */
TDC_SIMD_CLONES static double flip_err_row(const tdc_powtab_t *pq, double cmax, const float *restrict lab_r,
                                           const float *restrict e_r, const float *restrict p_r,
                                           const float *restrict lab, const float *restrict fe,
                                           const float *restrict fp, double *restrict map, double *restrict ex,
                                           int w)
{
    const double pc = 0.4, pt = 0.95;
    TDC_SIMD
    for (int x = 0; x < w; x++) {
        const double dl = (double)lab_r[3 * x] - (double)lab[3 * x];
        const double da = (double)lab_r[3 * x + 1] - (double)lab[3 * x + 1];
        const double db = (double)lab_r[3 * x + 2] - (double)lab[3 * x + 2];
        const double hy = fabs(dl) + sqrt(da * da + db * db); /* hyab */
        const double hq = tdc_powtab_pos(pq, hy);            /* ^qc, qc = 0.7 */
        double dc = hy != hy ? hy : (hy > 0.0 ? hq : 0.0);   /* NaN as NaN, 0^0.7 = 0 */
        const double lo = pt / (pc * cmax) * dc, hi = pt + (dc - pc * cmax) / (cmax - pc * cmax) * (1.0 - pt);
        dc = dc < pc * cmax ? lo : hi;
        dc = dc > 1.0 ? 1.0 : dc;
        const double dfe = fabs((double)e_r[x] - fe[x]), dfp = fabs((double)p_r[x] - fp[x]);
        double df = sqrt((dfe > dfp ? dfe : dfp) / sqrt(2.0)); /* ^qf, qf = 0.5 */
        df = df > 1.0 ? 1.0 : df;
        map[x] = dc;
        ex[x] = 1.0 - df;
    }
    double sum = 0.0;
    for (int x = 0; x < w; x++) {
        const double e = pow(map[x], ex[x]);
        map[x] = e;
        sum += e;
    }
    return sum;
}

static void flip_out_row(void *ctx, int y)
{
    flip_band_t *s = ctx;
    const flip_kern_t *K = s->K;
    const int w = K->w;
    float *f[3] = {s->f, s->f + w, s->f + 2 * (size_t)w};
    for (int c = 0; c < 3; c++) {
        flip_vert(s, RC0 + c, K->k1[c], K->rc, y, f[c]);
        if (K->two[c]) {
            flip_vert(s, RC2 + c, K->k2[c], K->rc, y, s->f2);
            for (int x = 0; x < w; x++) {
                f[c][x] += s->f2[x];
            }
        }
    }
    const size_t i0 = (size_t)y * w;
    const int prep = s->ref == NULL;
    float *lab = prep ? s->lab_out + 3 * i0 : s->lab;
    float *fe = prep ? s->e_out + i0 : s->e, *fp = prep ? s->p_out + i0 : s->p;
    flip_lab_row(s->cb, f[0], f[1], f[2], lab, w);
    for (int pass = 0; pass < 2; pass++) {
        /* edge: d1 across, g along, and g across, d1 along; point: d2 */
        flip_vert(s, pass ? RD2 : RD1, K->fg, K->rf, y, s->gx);
        flip_vert(s, RG, pass ? K->fd2 : K->fd1, K->rf, y, s->gy);
        float *o = pass ? fp : fe;
        TDC_SIMD
        for (int x = 0; x < w; x++) {
            o[x] = sqrtf(s->gx[x] * s->gx[x] + s->gy[x] * s->gy[x]);
        }
    }
    if (prep) {
        return;
    }
    s->rows[y] = flip_err_row(s->pq, s->cmax, s->ref->buf + 3 * i0, s->ref->buf + 3 * (size_t)w * K->h + i0,
                              s->ref->buf + 4 * (size_t)w * K->h + i0, lab, fe, fp, s->map ? s->map + i0 : s->dmap,
                              s->dex, w);
}

/* Every band of rows of s0 (a template); 0, or -1 out of memory. */
static int flip_bands(const flip_band_t *s0)
{
    const flip_kern_t *K = s0->K;
    const int w = K->w, h = K->h, rm = K->rmax;
    /* bands of at least 16 rmax rows: the 2 rmax rows shared with the
     * neighbours are converted and filtered horizontally twice (+12.5 %) */
    const int band = 16 * rm > 64 ? 16 * rm : 64, nb = (h + band - 1) / band;
    const size_t slots = 2 * (size_t)rm + 1, pw = (size_t)w + 2 * (size_t)rm;
    int bad = 0;
    TDC_PAR_REGION((size_t)w * h)
    {
        flip_band_t s = *s0;
        /* the two double rows first (malloc's alignment), then the floats */
        double *mem = malloc(sizeof(double) * 2 * (size_t)w +
                             sizeof(float) * (slots * NRING * (size_t)w + 4 * pw + 11 * (size_t)w));
        if (!mem) {
            bad = 1; /* benign race: every writer stores 1 */
        } else {
            s.dmap = mem;
            s.dex = mem + w;
            s.ring = (float *)(void *)(mem + 2 * (size_t)w);
            s.pad = s.ring + slots * NRING * (size_t)w;
            s.f = s.pad + 4 * pw;
            s.f2 = s.f + 3 * (size_t)w;
            s.gx = s.f2 + w;
            s.gy = s.gx + w;
            s.lab = s.gy + w;
            s.e = s.lab + 3 * (size_t)w;
            s.p = s.e + w;
        }
        TDC_PAR_BANDS
        for (int b = 0; b < nb; b++) {
            if (mem) {
                const int y0 = b * band, y1 = y0 + band < h ? y0 + band : h;
                tdc_filter_stream(y0, y1, h, rm, flip_src_row, flip_out_row, &s);
            }
        }
        free(mem);
    }
    return bad ? -1 : 0;
}

size_t tdc_flip_work_bytes(int w, int h)
{
    (void)w;
    return sizeof(double) * (size_t)(h > 0 ? h : 1);
}

int tdc_flip_prepare(tdc_flip_ref_t *ref, const double *lin, int w, int h, double ppd, void *work)
{
    (void)work;
    size_t n = (size_t)w * h;
    flip_kern_t K;
    if (w < 1 || h < 1 || w > TDC_FILTER_MAX_W || flip_kernels(&K, w, h, ppd)) {
        return -1;
    }
    ref->buf = tdc_metrics_reserve(ref->buf, &ref->cap, sizeof(float) * 5 * n);
    if (!ref->buf) {
        return -1;
    }
    ref->w = w;
    ref->h = h;
    ref->ppd = ppd;
    flip_band_t s = {0};
    s.K = &K;
    s.lin = lin;
    s.lab_out = ref->buf;
    s.e_out = ref->buf + 3 * n;
    s.p_out = ref->buf + 4 * n;
    s.cb = tdc_powtab_metrics(TDC_POWTAB_CBRT);
    return flip_bands(&s);
}

void tdc_flip_ref_free(tdc_flip_ref_t *ref)
{
    free(ref->buf);
    memset(ref, 0, sizeof(*ref));
}

double tdc_flip_vs(const tdc_flip_ref_t *ref, const double *test, double *map, void *work)
{
    const int w = ref->w, h = ref->h;
    const size_t n = (size_t)w * h;
    flip_kern_t K;
    if (flip_kernels(&K, w, h, ref->ppd)) {
        return -1.0;
    }
    double *own = work ? NULL : malloc(tdc_flip_work_bytes(w, h));
    double *rows = work ? (double *)work : own;
    if (!rows) {
        return -1.0;
    }
    flip_band_t s = {0};
    s.K = &K;
    s.lin = test;
    s.ref = ref;
    s.map = map;
    s.rows = rows;
    s.cb = tdc_powtab_metrics(TDC_POWTAB_CBRT);
    s.pq = tdc_powtab_metrics(TDC_POWTAB_HYAB);
    const double green[3] = {0.0, 1.0, 0.0}, blue[3] = {0.0, 0.0, 1.0};
    double lg[3], lb[3];
    rgb_to_lab_hunt(s.cb, green, lg);
    rgb_to_lab_hunt(s.cb, blue, lb);
    s.cmax = tdc_powtab(s.pq, hyab(lg, lb)); /* ^qc, qc = 0.7 */
    int bad = flip_bands(&s);
    double sum = tdc_par_sum_rows(rows, h);
    free(own);
    return bad ? -1.0 : (n ? sum / (double)n : 0.0);
}

double tdc_flip(const double *ref, const double *test, int w, int h, double ppd, double *map)
{
    tdc_flip_ref_t r = {0};
    double v = tdc_flip_prepare(&r, ref, w, h, ppd, NULL) ? -1.0 : tdc_flip_vs(&r, test, map, NULL);
    tdc_flip_ref_free(&r);
    return v;
}
