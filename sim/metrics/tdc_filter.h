/*
 * tdc_filter.h - separable 2-D convolution of one plane, threaded over rows
 * (sim/tdc_par.h), for the metrics: single precision for FLIP, double for
 * SSIM (which must agree with scikit-image to 1e-6).
 *
 * out(x, y) = sum_j ky[j] * (sum_i kx[i] * in(x + i - r, y + j - r)), i, j
 * ascending from 0, edges per `edge`.  The loops run the tap index outside
 * and the pixel index inside (contiguous, vectorisable); each output value
 * is the same sum in the same order whichever thread computes it, so the
 * result does not depend on the thread count.
 */
#ifndef TDC_FILTER_H
#define TDC_FILTER_H

typedef enum {
    TDC_EDGE_CLAMP = 0, /* repeat the edge pixel (numpy 'edge', FLIP) */
    TDC_EDGE_REFLECT    /* half-sample symmetric (scipy.ndimage 'reflect', SSIM) */
} tdc_edge_t;

#include <stdlib.h>

#define TDC_FILTER_MAX_W 4096

/* A buffer kept across calls (the metrics' reference planes): buf as it
 * is, or grown to `bytes` when smaller (*cap in bytes); NULL out of memory
 * (the old buffer freed). */
static inline void *tdc_metrics_reserve(void *buf, size_t *cap, size_t bytes)
{
    if (!buf || *cap < bytes) {
        free(buf);
        buf = malloc(bytes);
        *cap = buf ? bytes : 0;
    }
    return buf;
}
#define TDC_FILTER_MAX_R 256

/* tmp: w*h scratch.  Returns 0, or -1 if w or r exceeds the limits above. */
int tdc_sep_filter_f(const float *in, float *out, float *tmp, int w, int h, const float *kx, const float *ky, int r,
                     tdc_edge_t edge);
int tdc_sep_filter_d(const double *in, double *out, double *tmp, int w, int h, const double *kx, const double *ky,
                     int r, tdc_edge_t edge);

#endif
