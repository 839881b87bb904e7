/*
 * zeng_eval.h - Zeng §6's metrics on display-encoded frames: RMSE and SSIM
 * over the whole frame and over an effect's region (a pixel mask).  SSIM is
 * the map of tdc_ssim (sim/metrics/tdc_metrics.h: Wang et al. 2004, 11-tap
 * Gaussian sigma 1.5, interior cropped by 5 px, mean over channels) kept per
 * pixel so that a region's mean can be taken; over the whole interior it
 * equals tdc_ssim (test_zeng checks it).
 */
#ifndef ZENG_EVAL_H
#define ZENG_EVAL_H

#include <stdint.h>

#define ZE_SSIM_R 5

/* lin (W*H*3 linear) -> enc: clamp to [0, 1], ^(1/2.2). */
void ze_encode(const double *lin, double *enc, int w, int h);
/* SSIM map (W*H; border pixels set to NaN) of a against b (data range 1). */
void ze_ssim_map(const double *a, const double *b, int w, int h, double *map);
/* RMSE (over channels) and mean SSIM of the pixels with mask[p] != 0 (mask
 * NULL: all); SSIM over interior pixels only.  Returns the pixel count. */
long ze_region(const double *a, const double *b, const double *map, const uint8_t *mask, int w, int h, double *rmse,
               double *ssim);

#endif
