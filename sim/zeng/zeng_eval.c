/*
 * zeng_eval.c - RMSE and SSIM per frame and per region (zeng_eval.h).
 */
#include "zeng/zeng_eval.h"

#include <math.h>
#include <stdlib.h>

void ze_encode(const double *lin, double *enc, int w, int h)
{
    const size_t n = (size_t)w * h * 3;
    for (size_t i = 0; i < n; i++) {
        double v = lin[i] < 0 ? 0 : (lin[i] > 1 ? 1 : lin[i]);
        enc[i] = pow(v, 1.0 / 2.2);
    }
}

void ze_ssim_map(const double *a, const double *b, int w, int h, double *map)
{
    double k[2 * ZE_SSIM_R + 1], ks = 0;
    for (int j = -ZE_SSIM_R; j <= ZE_SSIM_R; j++) {
        k[j + ZE_SSIM_R] = exp(-0.5 * j * j / (1.5 * 1.5));
        ks += k[j + ZE_SSIM_R];
    }
    for (int j = 0; j <= 2 * ZE_SSIM_R; j++) {
        k[j] /= ks;
    }
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const size_t p = (size_t)y * w + x;
            if (x < ZE_SSIM_R || y < ZE_SSIM_R || x >= w - ZE_SSIM_R || y >= h - ZE_SSIM_R) {
                map[p] = NAN;
                continue;
            }
            double s = 0;
            for (int c = 0; c < 3; c++) {
                double ux = 0, uy = 0, uxx = 0, uyy = 0, uxy = 0;
                for (int j = -ZE_SSIM_R; j <= ZE_SSIM_R; j++) {
                    for (int i = -ZE_SSIM_R; i <= ZE_SSIM_R; i++) {
                        const double wk = k[i + ZE_SSIM_R] * k[j + ZE_SSIM_R];
                        const size_t q = ((size_t)(y + j) * w + x + i) * 3 + c;
                        ux += wk * a[q];
                        uy += wk * b[q];
                        uxx += wk * a[q] * a[q];
                        uyy += wk * b[q] * b[q];
                        uxy += wk * a[q] * b[q];
                    }
                }
                const double vx = uxx - ux * ux, vy = uyy - uy * uy, vxy = uxy - ux * uy;
                s += (2 * ux * uy + c1) * (2 * vxy + c2) / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
            }
            map[p] = s / 3.0;
        }
    }
}

long ze_region(const double *a, const double *b, const double *map, const uint8_t *mask, int w, int h, double *rmse,
               double *ssim)
{
    double se = 0, ss = 0;
    long n = 0, ns = 0;
    for (size_t p = 0; p < (size_t)w * h; p++) {
        if (mask && !mask[p]) {
            continue;
        }
        for (int c = 0; c < 3; c++) {
            const double d = a[3 * p + c] - b[3 * p + c];
            se += d * d;
        }
        n++;
        if (!isnan(map[p])) {
            ss += map[p];
            ns++;
        }
    }
    *rmse = n ? sqrt(se / (3.0 * n)) : NAN;
    *ssim = ns ? ss / ns : NAN;
    return n;
}
