/* tdc_fov_metrics.c - see tdc_fov_metrics.h. */
#include "tdc_fov_metrics.h"

#include <math.h>

#define BUCKETS 100

double tdc_flip_weighted_median(const double *map, size_t n)
{
    double hist[BUCKETS] = {0}, vmax = 0;
    for (size_t i = 0; i < n; i++) {
        const double v = map[i] < 0 ? 0 : (map[i] > 1 ? 1 : map[i]);
        vmax = v > vmax ? v : vmax;
        int b = (int)(v * BUCKETS);
        hist[b >= BUCKETS ? BUCKETS - 1 : b] += 1;
    }
    /* bucket weight = count x the bucket's centre value; the median of that */
    double total = 0;
    for (int b = 0; b < BUCKETS; b++) total += hist[b] * (b + 0.5) / BUCKETS;
    if (total <= 0 || vmax <= 0) return 0; /* no error anywhere */
    double acc = 0;
    for (int b = 0; b < BUCKETS; b++) {
        const double wb = hist[b] * (b + 0.5) / BUCKETS;
        if (acc + wb >= total / 2) {
            const double f = wb > 0 ? (total / 2 - acc) / wb : 0; /* within the bucket */
            return (b + f) / BUCKETS;
        }
        acc += wb;
    }
    return 1;
}

double tdc_ecc_weighted_mean(const double *map, int w, int h, double gx, double gy, double ppd)
{
    double sw = 0, s = 0;
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            const double e = hypot(i + 0.5 - gx, j + 0.5 - gy) / ppd;
            const double wt = TDC_FOV_E2_DEG / (TDC_FOV_E2_DEG + e);
            s += wt * map[(size_t)j * w + i];
            sw += wt;
        }
    }
    return sw > 0 ? s / sw : 0;
}

double tdc_disk_mean(const double *map, int w, int h, double gx, double gy, double r, int inside)
{
    double s = 0;
    long n = 0;
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            const int in = hypot(i + 0.5 - gx, j + 0.5 - gy) <= r;
            if (in == (inside != 0)) {
                s += map[(size_t)j * w + i];
                n++;
            }
        }
    }
    return n ? s / (double)n : 0;
}
