/*
 * tdc_fov_metrics.h - error statistics for foveated streams (issue 14),
 * over a per-pixel error map (e.g. the FLIP map of tdc_flip):
 *   - the thesis's condensed figure (Tables 5.1-5.3): FLIP's weighted
 *     median, the median of the error histogram whose buckets are weighted
 *     by their error value (larger errors count for more);
 *   - eccentricity-weighted mean: weight E2 / (E2 + e), e = eccentricity in
 *     degrees (distance to the gaze / pixels per degree), E2 = 2.3 deg, the
 *     inverse cortical magnification M(0)/M(e) = 1 + e/E2 (Strasburger et al.
 *     2011, thesis ref. [26]): an error at 10 deg counts ~1/5 of one at the
 *     fovea;
 *   - the mean inside a disk (the foveal region) and outside it.
 */
#ifndef TDC_FOV_METRICS_H
#define TDC_FOV_METRICS_H

#include <stddef.h>

#define TDC_FOV_E2_DEG 2.3

/* FLIP's weighted median of n values in [0, 1] (100 buckets; values
 * outside are clamped).  0 for n == 0 or an all-zero map. */
double tdc_flip_weighted_median(const double *map, size_t n);
/* The statistics of a w x h map around the gaze (gx, gy) in pixels (pixel
 * centres at i + 0.5), ppd pixels per degree, foveal disk radius r pixels
 * (a pixel is inside when its squared distance <= r^2): in one pass,
 * threaded over rows (sim/tdc_par.h: row sums in row order, so the result
 * does not depend on the thread count).  It replaced three serial passes
 * with a hypot per pixel each: 1.51 of 14.5 s wall of the stereo headline
 * run (docs/simulator-performance.md).  0, or -1 out of memory. */
typedef struct {
    double ecc;     /* eccentricity-weighted mean */
    double fovea;   /* mean within the disk; 0 when no pixel qualifies */
    double periph;  /* mean beyond it; 0 when none */
    double wmedian; /* tdc_flip_weighted_median of the map */
} tdc_fov_stats_t;
int tdc_fov_stats(const double *map, int w, int h, double gx, double gy, double ppd, double r, tdc_fov_stats_t *st);
/* Single statistics of tdc_fov_stats (-1 out of memory). */
double tdc_ecc_weighted_mean(const double *map, int w, int h, double gx, double gy, double ppd);
double tdc_disk_mean(const double *map, int w, int h, double gx, double gy, double r, int inside);

#endif
