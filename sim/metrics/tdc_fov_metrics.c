/* tdc_fov_metrics.c - see tdc_fov_metrics.h. */
#include "tdc_fov_metrics.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "tdc_par.h"

#define BUCKETS 100

static int bucket(double v)
{
    int b = (int)(v * BUCKETS);
    return b >= BUCKETS ? BUCKETS - 1 : b;
}

static double clamp01(double v)
{
    return v < 0 ? 0 : (v > 1 ? 1 : v);
}

/* The weighted median of a histogram of clamped values (count per bucket,
 * vmax their maximum). */
static double weighted_median(const int64_t hist[BUCKETS], double vmax)
{
    /* bucket weight = count x the bucket's centre value; the median of that */
    double total = 0;
    for (int b = 0; b < BUCKETS; b++) total += (double)hist[b] * (b + 0.5) / BUCKETS;
    if (total <= 0 || vmax <= 0) return 0; /* no error anywhere */
    double acc = 0;
    for (int b = 0; b < BUCKETS; b++) {
        const double wb = (double)hist[b] * (b + 0.5) / BUCKETS;
        if (acc + wb >= total / 2) {
            const double f = wb > 0 ? (total / 2 - acc) / wb : 0; /* within the bucket */
            return (b + f) / BUCKETS;
        }
        acc += wb;
    }
    return 1;
}

double tdc_flip_weighted_median(const double *map, size_t n)
{
    int64_t hist[BUCKETS] = {0};
    double vmax = 0;
    for (size_t i = 0; i < n; i++) {
        const double v = clamp01(map[i]);
        vmax = v > vmax ? v : vmax;
        hist[bucket(v)]++;
    }
    return weighted_median(hist, vmax);
}

int tdc_fov_stats(const double *map, int w, int h, double gx, double gy, double ppd, double r, tdc_fov_stats_t *st)
{
    /* per row: eccentricity-weighted sum and weight, sum and count inside
     * and outside the disk, added in row order afterwards; the histogram's
     * integer counts and the maximum do not depend on the order at all */
    double *rows = malloc(sizeof(double) * 6 * (size_t)(h > 0 ? h : 1));
    if (!rows) {
        return -1;
    }
    int64_t hist[BUCKETS] = {0};
    double vmax = 0;
    const double r2 = r * r;
    TDC_PAR_REGION((size_t)w * h)
    {
        int64_t lh[BUCKETS] = {0};
        double lmax = 0;
        TDC_PAR_BANDS
        for (int j = 0; j < h; j++) {
            const double *m = map + (size_t)j * w, dy = j + 0.5 - gy;
            double s = 0, sw = 0, si = 0, ni = 0, so = 0, no = 0;
            for (int i = 0; i < w; i++) {
                const double dx = i + 0.5 - gx, d2 = dx * dx + dy * dy;
                const double e = sqrt(d2) / ppd;
                const double wt = TDC_FOV_E2_DEG / (TDC_FOV_E2_DEG + e);
                s += wt * m[i];
                sw += wt;
                if (d2 <= r2) {
                    si += m[i];
                    ni += 1;
                } else {
                    so += m[i];
                    no += 1;
                }
                const double v = clamp01(m[i]);
                lmax = v > lmax ? v : lmax;
                lh[bucket(v)]++;
            }
            double *o = rows + 6 * (size_t)j;
            o[0] = s;
            o[1] = sw;
            o[2] = si;
            o[3] = ni;
            o[4] = so;
            o[5] = no;
        }
#ifdef _OPENMP
#pragma omp critical(tdc_fov_stats)
#endif
        {
            for (int b = 0; b < BUCKETS; b++) hist[b] += lh[b];
            vmax = lmax > vmax ? lmax : vmax;
        }
    }
    double t[6] = {0};
    for (int j = 0; j < h; j++) {
        for (int k = 0; k < 6; k++) t[k] += rows[6 * (size_t)j + k];
    }
    free(rows);
    st->ecc = t[1] > 0 ? t[0] / t[1] : 0;
    st->fovea = t[3] > 0 ? t[2] / t[3] : 0;
    st->periph = t[5] > 0 ? t[4] / t[5] : 0;
    st->wmedian = weighted_median(hist, vmax);
    return 0;
}

double tdc_ecc_weighted_mean(const double *map, int w, int h, double gx, double gy, double ppd)
{
    tdc_fov_stats_t st;
    return tdc_fov_stats(map, w, h, gx, gy, ppd, 0, &st) ? -1 : st.ecc;
}

double tdc_disk_mean(const double *map, int w, int h, double gx, double gy, double r, int inside)
{
    tdc_fov_stats_t st;
    if (tdc_fov_stats(map, w, h, gx, gy, 1, r, &st)) {
        return -1;
    }
    return inside ? st.fovea : st.periph;
}
