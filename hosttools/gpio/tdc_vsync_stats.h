/*
 * tdc_vsync_stats.h - refresh rate, jitter and missed frames from vsync /
 * tearing-effect edge timestamps (host code, double precision).
 */
#ifndef TDC_VSYNC_STATS_H
#define TDC_VSYNC_STATS_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    size_t edges;         /* timestamps analysed */
    double period_us;     /* nominal frame period used to count frames, microseconds */
    double refresh_hz;    /* measured: frames / elapsed time, missed frames included */
    double jitter_rms_us; /* RMS of (interval - k * measured period) */
    double jitter_pp_us;  /* peak-to-peak of the same deviation */
    double min_interval_us, max_interval_us;
    uint32_t missed; /* frames with no edge (interval ~ k periods, k >= 2) */
} tdc_vsync_stats_t;

/* ts_ns: n >= 2 increasing kernel timestamps in nanoseconds.  expect_hz > 0:
 * nominal refresh used to count frames per interval; 0: the median interval.
 * Returns 0, or -1 if n < 2, timestamps do not increase, or expect_hz < 0. */
int tdc_vsync_analyse(const uint64_t *ts_ns, size_t n, double expect_hz, tdc_vsync_stats_t *out);

#endif
