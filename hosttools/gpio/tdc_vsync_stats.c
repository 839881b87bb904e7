/*
 * tdc_vsync_stats.c - see tdc_vsync_stats.h.
 *
 * Each interval d_i between consecutive edges spans k_i = round(d_i / T)
 * frames, T the nominal period (given, or the median interval, which is
 * robust to a few missed frames).  k_i - 1 frames were missed.  The measured
 * period is the elapsed time over the frame count, sum(d_i) / sum(k_i), and
 * the jitter is the deviation of each interval from k_i measured periods.
 */
#include "tdc_vsync_stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int tdc_vsync_analyse(const uint64_t *ts_ns, size_t n, double expect_hz, tdc_vsync_stats_t *out)
{
    if (ts_ns == NULL || out == NULL || n < 2 || expect_hz < 0) return -1;
    size_t m = n - 1;
    double *d = malloc(m * sizeof *d), *sorted = malloc(m * sizeof *sorted);
    if (d == NULL || sorted == NULL) {
        free(d);
        free(sorted);
        return -1;
    }
    for (size_t i = 0; i < m; i++) {
        if (ts_ns[i + 1] <= ts_ns[i]) {
            free(d);
            free(sorted);
            return -1;
        }
        d[i] = (double)(ts_ns[i + 1] - ts_ns[i]) * 1e-3; /* microseconds */
    }
    memcpy(sorted, d, m * sizeof *d);
    qsort(sorted, m, sizeof *sorted, cmp_double);
    double nominal =
        expect_hz > 0 ? 1e6 / expect_hz : (m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]));
    double frames = 0, elapsed = 0;
    uint32_t missed = 0;
    for (size_t i = 0; i < m; i++) {
        double k = floor(d[i] / nominal + 0.5);
        if (k < 1) k = 1; /* a spurious early edge still closes one frame */
        frames += k;
        elapsed += d[i];
        missed += (uint32_t)(k - 1);
    }
    double period = elapsed / frames;
    double sum2 = 0, lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < m; i++) {
        double k = floor(d[i] / nominal + 0.5);
        if (k < 1) k = 1;
        double dev = d[i] - k * period;
        sum2 += dev * dev;
        lo = fmin(lo, dev);
        hi = fmax(hi, dev);
    }
    memset(out, 0, sizeof *out);
    out->edges = n;
    out->period_us = nominal;
    out->refresh_hz = 1e6 / period;
    out->jitter_rms_us = sqrt(sum2 / (double)m);
    out->jitter_pp_us = hi - lo;
    out->min_interval_us = sorted[0];
    out->max_interval_us = sorted[m - 1];
    out->missed = missed;
    free(d);
    free(sorted);
    return 0;
}
