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

/* The same in two halves, so that one reference b (the ground truth of an
 * eye and instant) is filtered once for every image compared with it:
 * tdc_ssim_prepare keeps b's windowed mean and mean square per channel
 * (6 W*H doubles, reused across calls; b itself is referenced, not copied,
 * and must stay valid), tdc_ssim_vs(ref, a, range, work) == tdc_ssim(a, b,
 * ...) to the last bit.  work: tdc_ssim_work_bytes(w, h) of scratch, 8-byte
 * aligned, or NULL to allocate per call (a fresh mapping of that size costs
 * page faults: at 1440x1600 they were ~11 % of the run).  Zero-initialise a
 * tdc_ssim_ref_t before the first prepare; prepare returns 0 or -1. */
typedef struct {
    const double *b;
    int w, h;
    double *buf;
    size_t cap; /* bytes */
} tdc_ssim_ref_t;
size_t tdc_ssim_work_bytes(int w, int h);
int tdc_ssim_prepare(tdc_ssim_ref_t *ref, const double *b, int w, int h, void *work);
double tdc_ssim_vs(const tdc_ssim_ref_t *ref, const double *a, double data_range, void *work);
void tdc_ssim_ref_free(tdc_ssim_ref_t *ref);

/* FLIP of linear-RGB reference and test; map (optional, W*H) receives the
 * per-pixel error.  Returns the mean, or -1 on allocation failure. */
double tdc_flip(const double *ref, const double *test, int w, int h, double ppd, double *map);

/* The same in two halves (as tdc_ssim_prepare): the reference's prefiltered
 * L*a*b* and feature planes (5 W*H floats, reused across calls) once, then
 * tdc_flip_vs(ref, test, map, work) == tdc_flip(ref image, test, ...) to the
 * last bit; work as SSIM's, tdc_flip_work_bytes(w, h) or NULL.
 * Zero-initialise before the first prepare; 0 or -1 (size, memory). */
typedef struct {
    int w, h;
    double ppd;
    float *buf;
    size_t cap; /* bytes */
} tdc_flip_ref_t;
size_t tdc_flip_work_bytes(int w, int h);
int tdc_flip_prepare(tdc_flip_ref_t *ref, const double *lin, int w, int h, double ppd, void *work);
double tdc_flip_vs(const tdc_flip_ref_t *ref, const double *test, double *map, void *work);
void tdc_flip_ref_free(tdc_flip_ref_t *ref);

/* Linear light -> display encoding used for PSNR/SSIM (gamma 2.2, clamped). */
void tdc_metrics_encode(const double *lin, double *enc, size_t n);

#endif
