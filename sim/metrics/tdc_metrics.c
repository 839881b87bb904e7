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

/* The filtered planes of b per channel c: mean mu_b (buf + 2cn) and mean
 * of b^2 (buf + (2c+1)n); work: 2n scratch. */
static int ssim_ref_planes(const double *b, int w, int h, double *buf, double *work)
{
    double k[2 * SSIM_R + 1];
    ssim_kernel(k);
    size_t n = (size_t)w * h;
    double *y = work, *tmp = work + n;
    int bad = 0;
    for (int c = 0; c < 3 && !bad; c++) {
        double *uy = buf + 2 * c * n, *uyy = buf + (2 * c + 1) * n;
        TDC_PAR_FOR((size_t)w * h)
        for (int yr = 0; yr < h; yr++) {
            for (size_t i = (size_t)yr * w; i < (size_t)(yr + 1) * w; i++) {
                y[i] = b[3 * i + c];
            }
        }
        bad |= tdc_sep_filter_d(y, uy, tmp, w, h, k, k, SSIM_R, TDC_EDGE_REFLECT);
        TDC_PAR_FOR((size_t)w * h)
        for (int yr = 0; yr < h; yr++) {
            for (size_t i = (size_t)yr * w; i < (size_t)(yr + 1) * w; i++) {
                y[i] *= y[i];
            }
        }
        bad |= tdc_sep_filter_d(y, uyy, tmp, w, h, k, k, SSIM_R, TDC_EDGE_REFLECT);
    }
    return bad;
}

size_t tdc_ssim_work_bytes(int w, int h)
{
    return sizeof(double) * ((size_t)w * h * 7 + (size_t)h);
}

int tdc_ssim_prepare(tdc_ssim_ref_t *ref, const double *b, int w, int h, void *work)
{
    size_t n = (size_t)w * h;
    if (w < 1 || h < 1) {
        return -1;
    }
    ref->buf = tdc_metrics_reserve(ref->buf, &ref->cap, sizeof(double) * 6 * n);
    double *own = work ? NULL : malloc(tdc_ssim_work_bytes(w, h));
    if (!ref->buf || (!work && !own)) {
        free(own);
        return -1;
    }
    ref->b = b;
    ref->w = w;
    ref->h = h;
    int bad = ssim_ref_planes(b, w, h, ref->buf, work ? (double *)work : own);
    free(own);
    return bad ? -1 : 0;
}

void tdc_ssim_ref_free(tdc_ssim_ref_t *ref)
{
    free(ref->buf);
    memset(ref, 0, sizeof(*ref));
}

double tdc_ssim_vs(const tdc_ssim_ref_t *ref, const double *a, double data_range, void *work)
{
    double k[2 * SSIM_R + 1];
    ssim_kernel(k);
    const int w = ref->w, h = ref->h, r = SSIM_R;
    const double *b = ref->b;
    size_t n = (size_t)w * h;
    double *own = work ? NULL : malloc(tdc_ssim_work_bytes(w, h));
    double *buf = work ? (double *)work : own;
    if (!buf) {
        return -1.0;
    }
    double *x = buf, *xx = buf + n, *xy = buf + 2 * n;
    double *ux = buf + 3 * n, *uxx = buf + 4 * n, *uxy = buf + 5 * n;
    double *tmp = buf + 6 * n, *rows = buf + 7 * n;
    const double c1 = (0.01 * data_range) * (0.01 * data_range);
    const double c2 = (0.03 * data_range) * (0.03 * data_range);
    const int pad = r; /* (win_size - 1) / 2 with win_size = 2r + 1 */
    double total = 0.0;
    int bad = 0;
    for (int c = 0; c < 3 && !bad; c++) {
        const double *uy = ref->buf + 2 * c * n, *uyy = ref->buf + (2 * c + 1) * n;
        TDC_PAR_FOR((size_t)w * h)
        for (int yr = 0; yr < h; yr++) {
            for (size_t i = (size_t)yr * w; i < (size_t)(yr + 1) * w; i++) {
                x[i] = a[3 * i + c];
                xx[i] = x[i] * x[i];
                xy[i] = x[i] * b[3 * i + c];
            }
        }
        bad |= tdc_sep_filter_d(x, ux, tmp, w, h, k, k, r, TDC_EDGE_REFLECT);
        bad |= tdc_sep_filter_d(xx, uxx, tmp, w, h, k, k, r, TDC_EDGE_REFLECT);
        bad |= tdc_sep_filter_d(xy, uxy, tmp, w, h, k, k, r, TDC_EDGE_REFLECT);
        TDC_PAR_FOR((size_t)w * h)
        for (int yy0 = pad; yy0 < h - pad; yy0++) {
            double s = 0.0;
            for (int xx0 = pad; xx0 < w - pad; xx0++) {
                size_t i = (size_t)yy0 * w + xx0;
                double vx = uxx[i] - ux[i] * ux[i];
                double vy = uyy[i] - uy[i] * uy[i];
                double vxy = uxy[i] - ux[i] * uy[i];
                double num = (2.0 * ux[i] * uy[i] + c1) * (2.0 * vxy + c2);
                double den = (ux[i] * ux[i] + uy[i] * uy[i] + c1) * (vx + vy + c2);
                s += num / den;
            }
            rows[yy0] = s;
        }
        size_t cnt = h > 2 * pad && w > 2 * pad ? (size_t)(h - 2 * pad) * (size_t)(w - 2 * pad) : 0;
        double s = h > 2 * pad ? tdc_par_sum_rows(rows + pad, h - 2 * pad) : 0.0;
        total += cnt ? s / (double)cnt : 1.0;
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
