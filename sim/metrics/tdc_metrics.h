/*
 * tdc_metrics.h - image error metrics on perceived images.
 *
 * Images are W*H*3 interleaved doubles.  PSNR and SSIM take display-encoded
 * values in [0, 1] (the simulator encodes linear light with gamma 2.2 so the
 * numbers are comparable with the usual 8-bit figures); FLIP takes linear RGB
 * in [0, 1].
 *
 *  - PSNR: 10 log10(peak^2 / MSE) over all samples; identical images give
 *    TDC_PSNR_CAP.
 *  - SSIM (Wang et al. 2004) exactly as scikit-image's structural_similarity
 *    with gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
 *    data_range=1: 11-tap Gaussian (truncate 3.5), 'reflect' borders, mean
 *    over the image cropped by 5 px, averaged over the channels.
 *  - FLIP (Andersson et al., HPG 2020, "FLIP: A Difference Evaluator for
 *    Alternating Images"), LDR version, written from the paper's
 *    definition: YyCxCz opponent space, CSF filtering with the paper's
 *    sum-of-Gaussians CSFs at the viewing condition's pixels per degree,
 *    back to linear RGB, clamped, to L*a*b* with the Hunt adjustment,
 *    HyAB distance, compressed (q_c = 0.7) and remapped (p_c = 0.4,
 *    p_t = 0.95) against the green-blue maximum; edge and point feature
 *    differences (Gaussian derivatives, sigma = 0.5 * 0.082 deg) give
 *    Delta_f = (max diff / sqrt 2)^0.5; the pixel error is
 *    Delta_c^(1 - Delta_f); the FLIP value is the mean.
 */
#ifndef TDC_METRICS_H
#define TDC_METRICS_H

#include <stddef.h>

#define TDC_PSNR_CAP 100.0

/* Default FLIP viewing condition: 0.7 m from a 0.7 m wide 3840-px monitor. */
#define TDC_FLIP_DEFAULT_PPD 67.0206

double tdc_psnr(const double *a, const double *b, size_t n, double peak);

/* SSIM of two W x H x 3 images (values in [0, data_range]). */
double tdc_ssim(const double *a, const double *b, int w, int h, double data_range);

/* FLIP of linear-RGB reference and test; map (optional, W*H) receives the
 * per-pixel error.  Returns the mean, or -1 on allocation failure. */
double tdc_flip(const double *ref, const double *test, int w, int h, double ppd, double *map);

/* Linear light -> display encoding used for PSNR/SSIM (gamma 2.2, clamped). */
void tdc_metrics_encode(const double *lin, double *enc, size_t n);

#endif
