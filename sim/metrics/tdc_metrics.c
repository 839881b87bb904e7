/* tdc_metrics.c - PSNR, SSIM (scikit-image compatible) and display encoding. */
#include "metrics/tdc_metrics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

double tdc_psnr(const double *a, const double *b, size_t n, double peak)
{
    double se = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = a[i] - b[i];
        se += d * d;
    }
    double mse = n ? se / (double)n : 0.0;
    if (mse <= peak * peak * 1e-10) {
        return TDC_PSNR_CAP;
    }
    double p = 10.0 * log10(peak * peak / mse);
    return p > TDC_PSNR_CAP ? TDC_PSNR_CAP : p;
}

void tdc_metrics_encode(const double *lin, double *enc, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double v = lin[i] < 0.0 ? 0.0 : (lin[i] > 1.0 ? 1.0 : lin[i]);
        enc[i] = pow(v, 1.0 / 2.2);
    }
}

/* scipy.ndimage 'reflect' (half-sample symmetric) index. */
static int reflect_index(int i, int n)
{
    if (n == 1) {
        return 0;
    }
    int period = 2 * n;
    i %= period;
    if (i < 0) {
        i += period;
    }
    return i < n ? i : period - 1 - i;
}

/* Separable Gaussian filter of one plane (w x h), kernel k of radius r. */
static void filter_plane(const double *in, double *out, double *tmp, int w, int h, const double *k, int r)
{
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double s = 0.0;
            for (int j = -r; j <= r; j++) {
                s += k[j + r] * in[(size_t)y * w + reflect_index(x + j, w)];
            }
            tmp[(size_t)y * w + x] = s;
        }
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double s = 0.0;
            for (int j = -r; j <= r; j++) {
                s += k[j + r] * tmp[(size_t)reflect_index(y + j, h) * w + x];
            }
            out[(size_t)y * w + x] = s;
        }
    }
}

double tdc_ssim(const double *a, const double *b, int w, int h, double data_range)
{
    const double sigma = 1.5, truncate = 3.5;
    const int r = (int)(truncate * sigma + 0.5); /* 5, as scipy.ndimage */
    double k[32];
    double ks = 0.0;
    for (int j = -r; j <= r; j++) {
        k[j + r] = exp(-0.5 * j * j / (sigma * sigma));
        ks += k[j + r];
    }
    for (int j = 0; j <= 2 * r; j++) {
        k[j] /= ks;
    }
    size_t n = (size_t)w * h;
    double *buf = malloc(sizeof(double) * n * 11);
    if (!buf) {
        return -1.0;
    }
    double *x = buf, *y = buf + n, *xx = buf + 2 * n, *yy = buf + 3 * n, *xy = buf + 4 * n;
    double *ux = buf + 5 * n, *uy = buf + 6 * n, *uxx = buf + 7 * n, *uyy = buf + 8 * n, *uxy = buf + 9 * n;
    double *tmp = buf + 10 * n;
    const double c1 = (0.01 * data_range) * (0.01 * data_range);
    const double c2 = (0.03 * data_range) * (0.03 * data_range);
    const int pad = r; /* (win_size - 1) / 2 with win_size = 2r + 1 */
    double total = 0.0;
    for (int c = 0; c < 3; c++) {
        for (size_t i = 0; i < n; i++) {
            x[i] = a[3 * i + c];
            y[i] = b[3 * i + c];
            xx[i] = x[i] * x[i];
            yy[i] = y[i] * y[i];
            xy[i] = x[i] * y[i];
        }
        filter_plane(x, ux, tmp, w, h, k, r);
        filter_plane(y, uy, tmp, w, h, k, r);
        filter_plane(xx, uxx, tmp, w, h, k, r);
        filter_plane(yy, uyy, tmp, w, h, k, r);
        filter_plane(xy, uxy, tmp, w, h, k, r);
        double s = 0.0;
        size_t cnt = 0;
        for (int yy0 = pad; yy0 < h - pad; yy0++) {
            for (int xx0 = pad; xx0 < w - pad; xx0++) {
                size_t i = (size_t)yy0 * w + xx0;
                double vx = uxx[i] - ux[i] * ux[i];
                double vy = uyy[i] - uy[i] * uy[i];
                double vxy = uxy[i] - ux[i] * uy[i];
                double num = (2.0 * ux[i] * uy[i] + c1) * (2.0 * vxy + c2);
                double den = (ux[i] * ux[i] + uy[i] * uy[i] + c1) * (vx + vy + c2);
                s += num / den;
                cnt++;
            }
        }
        total += cnt ? s / (double)cnt : 1.0;
    }
    free(buf);
    return total / 3.0;
}
