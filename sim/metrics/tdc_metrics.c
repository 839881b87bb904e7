/* tdc_metrics.c - PSNR, SSIM (scikit-image compatible) and display encoding. */
#include "metrics/tdc_metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/tdc_filter.h"
#include "metrics/tdc_powtab.h"
#include "tdc_par.h"

double tdc_psnr(const double *a, const double *b, size_t n, double peak)
{
    /* rows of 4096 values, summed per row then in row order */
    const size_t chunk = 4096;
    int nrows = (int)((n + chunk - 1) / chunk);
    double *rows = malloc(sizeof(double) * (size_t)(nrows > 0 ? nrows : 1));
    if (!rows) {
        return -1.0;
    }
    TDC_PAR_FOR(n)
    for (int r = 0; r < nrows; r++) {
        size_t i0 = (size_t)r * chunk, i1 = i0 + chunk < n ? i0 + chunk : n;
        double se = 0.0;
        for (size_t i = i0; i < i1; i++) {
            double d = a[i] - b[i];
            se += d * d;
        }
        rows[r] = se;
    }
    double se = tdc_par_sum_rows(rows, nrows);
    free(rows);
    double mse = n ? se / (double)n : 0.0;
    if (mse <= peak * peak * 1e-10) {
        return TDC_PSNR_CAP;
    }
    double p = 10.0 * log10(peak * peak / mse);
    return p > TDC_PSNR_CAP ? TDC_PSNR_CAP : p;
}

void tdc_metrics_encode(const double *lin, double *enc, size_t n)
{
    const tdc_powtab_t *t = tdc_powtab_metrics(TDC_POWTAB_ENCODE);
    const size_t chunk = 4096;
    int nrows = (int)((n + chunk - 1) / chunk);
    TDC_PAR_FOR(n)
    for (int r = 0; r < nrows; r++) {
        size_t i0 = (size_t)r * chunk, i1 = i0 + chunk < n ? i0 + chunk : n;
        for (size_t i = i0; i < i1; i++) {
            double v = lin[i] < 0.0 ? 0.0 : (lin[i] > 1.0 ? 1.0 : lin[i]);
            enc[i] = tdc_powtab(t, v); /* v^(1/2.2) within 7.5e-9 relative */
        }
    }
}

/* SSIM's Gaussian window: 11 taps (sigma 1.5, truncate 3.5, as scipy.ndimage). */
#define SSIM_R 5
#define SSIM_SLOTS (2 * SSIM_R + 1)
/* Output rows per band.  A band filters the 2r source rows it shares with
 * each neighbour horizontally again: +16 % on the horizontal half at 64. */
#define SSIM_BAND 64
static void ssim_kernel(double k[2 * SSIM_R + 1])
{
    const double sigma = 1.5;
    double ks = 0.0;
    for (int j = -SSIM_R; j <= SSIM_R; j++) {
        k[j + SSIM_R] = exp(-0.5 * j * j / (sigma * sigma));
        ks += k[j + SSIM_R];
    }
    for (int j = 0; j <= 2 * SSIM_R; j++) {
        k[j] /= ks;
    }
}

/*
 * Only the interior (rows and columns [r, n - r)) enters the mean, and its
 * taps never leave the image, so only interior outputs are computed; they
 * are the values the whole-plane filter with 'reflect' edges gives there.
 * Per channel c the quantities q are b, b^2 (prepare: the reference's
 * windowed mean mu_b and mean square, kept as planes 2c and 2c + 1 of n) or
 * a, a^2, a b (vs), streamed through a ring of horizontal results
 * (tdc_filter.h), reduced row by row: the SSIM map is never stored.
 */
typedef struct {
    const double *a, *b; /* a: the test image (vs), NULL in prepare; b: the reference */
    const double *planes; /* vs: the reference's mu_b, mean b^2 planes */
    double *out;          /* prepare: where those planes go */
    double *rows;         /* vs: per-channel row sums, 3 x h */
    double k[2 * SSIM_R + 1];
    double c1, c2;
    int w, h, wi, nq; /* wi = w - 2r interior columns; nq = 2 (prepare) or 3 (vs) */
    double *ring;     /* SSIM_SLOTS x 3 channels x nq rows of wi */
    double *in;       /* nq rows of w: one channel's quantities of a source row */
    double *v;        /* nq rows of wi: the vertical results of an output row */
} ssim_band_t;

static void ssim_src_row(void *ctx, int yy, int slot)
{
    ssim_band_t *s = ctx;
    const int w = s->w, nq = s->nq;
    const double *src[2 * SSIM_R + 1];
    for (int c = 0; c < 3; c++) {
        double *q0 = s->in, *q1 = s->in + w, *q2 = s->in + 2 * (size_t)w;
        const double *b = s->b + 3 * (size_t)yy * w + c;
        if (s->a) {
            const double *a = s->a + 3 * (size_t)yy * w + c;
            for (int x = 0; x < w; x++) {
                q0[x] = a[3 * x];
                q1[x] = q0[x] * q0[x];
                q2[x] = q0[x] * b[3 * x];
            }
        } else {
            for (int x = 0; x < w; x++) {
                q0[x] = b[3 * x];
                q1[x] = q0[x] * q0[x];
            }
        }
        for (int q = 0; q < nq; q++) {
            for (int j = 0; j <= 2 * SSIM_R; j++) {
                src[j] = s->in + (size_t)q * w + j;
            }
            double *o = s->ring + (((size_t)slot * 3 + c) * nq + q) * s->wi;
            tdc_filter_taps_d(o, src, s->k, 2 * SSIM_R + 1, s->wi);
        }
    }
}

/* The SSIM map of one interior row, summed left to right: the terms
 * element-wise first (vectorised, the divisions too), into t, then the sum
 * - the same value as term by term. */
TDC_SIMD_CLONES static double ssim_row_sum(const double *restrict ux, const double *restrict uxx,
                                           const double *restrict uxy, const double *restrict uy,
                                           const double *restrict uyy, double c1, double c2, double *restrict t,
                                           int wi)
{
    TDC_SIMD
    for (int x = 0; x < wi; x++) {
        double vx = uxx[x] - ux[x] * ux[x];
        double vy = uyy[x] - uy[x] * uy[x];
        double vxy = uxy[x] - ux[x] * uy[x];
        double num = (2.0 * ux[x] * uy[x] + c1) * (2.0 * vxy + c2);
        double den = (ux[x] * ux[x] + uy[x] * uy[x] + c1) * (vx + vy + c2);
        t[x] = num / den;
    }
    double sum = 0.0;
    for (int x = 0; x < wi; x++) {
        sum += t[x];
    }
    return sum;
}

static void ssim_out_row(void *ctx, int y)
{
    ssim_band_t *s = ctx;
    const int w = s->w, h = s->h, wi = s->wi, nq = s->nq, r = SSIM_R;
    const size_t n = (size_t)w * h, stride = (size_t)3 * nq * wi;
    const double *src[2 * SSIM_R + 1];
    for (int c = 0; c < 3; c++) {
        for (int q = 0; q < nq; q++) {
            double *o = s->out ? s->out + (2 * (size_t)c + q) * n + (size_t)y * w + r : s->v + (size_t)q * wi;
            tdc_filter_ring_rows_d(src, s->ring + ((size_t)c * nq + q) * wi, stride, SSIM_SLOTS, y, h, r,
                                   TDC_EDGE_REFLECT);
            tdc_filter_taps_d(o, src, s->k, 2 * SSIM_R + 1, wi);
        }
        if (s->out) {
            continue;
        }
        const double *ux = s->v, *uxx = s->v + wi, *uxy = s->v + 2 * (size_t)wi;
        const double *uy = s->planes + 2 * (size_t)c * n + (size_t)y * w + r, *uyy = uy + n;
        s->rows[(size_t)c * h + y] = ssim_row_sum(ux, uxx, uxy, uy, uyy, s->c1, s->c2, s->in, wi);
    }
}

/* Every band of interior rows of s (a template: its pointers and sizes);
 * 0, or -1 out of memory. */
static int ssim_bands(const ssim_band_t *s0)
{
    const int h = s0->h, r = SSIM_R, nb = (h - 2 * r + SSIM_BAND - 1) / SSIM_BAND;
    int bad = 0;
    TDC_PAR_REGION((size_t)s0->w * h)
    {
        ssim_band_t s = *s0;
        const size_t nq = (size_t)s.nq, wi = (size_t)s.wi;
        double *mem = malloc(sizeof(double) * (SSIM_SLOTS * 3 * nq * wi + nq * (size_t)s.w + nq * wi));
        s.ring = mem;
        s.in = mem + SSIM_SLOTS * 3 * nq * wi;
        s.v = s.in + nq * (size_t)s.w;
        if (!mem) {
            bad = 1; /* benign race: every writer stores 1 */
        }
        TDC_PAR_BANDS
        for (int b = 0; b < nb; b++) {
            if (mem) {
                const int y0 = r + b * SSIM_BAND, y1 = y0 + SSIM_BAND < h - r ? y0 + SSIM_BAND : h - r;
                tdc_filter_stream(y0, y1, h, r, ssim_src_row, ssim_out_row, &s);
            }
        }
        free(mem);
    }
    return bad ? -1 : 0;
}

static void ssim_setup(ssim_band_t *s, int w, int h)
{
    memset(s, 0, sizeof(*s));
    ssim_kernel(s->k);
    s->w = w;
    s->h = h;
    s->wi = w - 2 * SSIM_R;
}

size_t tdc_ssim_work_bytes(int w, int h)
{
    (void)w;
    return sizeof(double) * 3 * (size_t)(h > 0 ? h : 1);
}

int tdc_ssim_prepare(tdc_ssim_ref_t *ref, const double *b, int w, int h, void *work)
{
    (void)work;
    size_t n = (size_t)w * h;
    if (w < 1 || h < 1) {
        return -1;
    }
    ref->buf = tdc_metrics_reserve(ref->buf, &ref->cap, sizeof(double) * 6 * n);
    if (!ref->buf) {
        return -1;
    }
    ref->b = b;
    ref->w = w;
    ref->h = h;
    if (w <= 2 * SSIM_R || h <= 2 * SSIM_R) {
        return 0; /* no interior: SSIM is 1 by definition (below) */
    }
    ssim_band_t s;
    ssim_setup(&s, w, h);
    s.b = b;
    s.out = ref->buf;
    s.nq = 2;
    return ssim_bands(&s);
}

void tdc_ssim_ref_free(tdc_ssim_ref_t *ref)
{
    free(ref->buf);
    memset(ref, 0, sizeof(*ref));
}

double tdc_ssim_vs(const tdc_ssim_ref_t *ref, const double *a, double data_range, void *work)
{
    const int w = ref->w, h = ref->h, r = SSIM_R;
    if (w <= 2 * r || h <= 2 * r) {
        return 1.0; /* mean over an empty interior: 1 per channel, as before */
    }
    double *own = work ? NULL : malloc(tdc_ssim_work_bytes(w, h));
    double *rows = work ? (double *)work : own;
    if (!rows) {
        return -1.0;
    }
    ssim_band_t s;
    ssim_setup(&s, w, h);
    s.a = a;
    s.b = ref->b;
    s.planes = ref->buf;
    s.rows = rows;
    s.nq = 3;
    s.c1 = (0.01 * data_range) * (0.01 * data_range);
    s.c2 = (0.03 * data_range) * (0.03 * data_range);
    int bad = ssim_bands(&s);
    /* per channel: the interior's mean, rows summed in row order */
    const size_t cnt = (size_t)(h - 2 * r) * (size_t)(w - 2 * r);
    double total = 0.0;
    for (int c = 0; c < 3; c++) {
        total += tdc_par_sum_rows(rows + (size_t)c * h + r, h - 2 * r) / (double)cnt;
    }
    free(own);
    return bad ? -1.0 : total / 3.0;
}

double tdc_ssim(const double *a, const double *b, int w, int h, double data_range)
{
    tdc_ssim_ref_t ref = {0};
    double v = tdc_ssim_prepare(&ref, b, w, h, NULL) ? -1.0 : tdc_ssim_vs(&ref, a, data_range, NULL);
    tdc_ssim_ref_free(&ref);
    return v;
}
