/*
 * tdc_filter.h - separable 2-D convolution for the metrics (single
 * precision for FLIP, double for SSIM, which must agree with scikit-image
 * to 1e-6), streamed row by row: the horizontal pass of a source row goes
 * into a ring of 2r + 1 rows, and every output row is the vertical pass
 * over the ring as soon as its last source row is in - a band of rows is
 * filtered, converted and reduced while it is in cache, without a
 * horizontal-result plane or an output plane in memory.
 *
 * out(x, y) = sum_j ky[j] * (sum_i kx[i] * in(x + i - r, y + j - r)), i, j
 * ascending from 0, edges per `edge`.  Each output value is the same sum in
 * the same order whichever band or thread computes it (the bands overlap by
 * 2r source rows, recomputed by each), so results do not depend on the band
 * size or the thread count.
 */
#ifndef TDC_FILTER_H
#define TDC_FILTER_H

#include <stdlib.h>

typedef enum {
    TDC_EDGE_CLAMP = 0, /* repeat the edge pixel (numpy 'edge', FLIP) */
    TDC_EDGE_REFLECT    /* half-sample symmetric (scipy.ndimage 'reflect', SSIM) */
} tdc_edge_t;

#define TDC_FILTER_MAX_W 4096
#define TDC_FILTER_MAX_R 256

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

/* Index i of a row or column of n values, mapped inside per `e`. */
int tdc_filter_edge(int i, int n, tdc_edge_t e);

/* The row kernel of both passes: o[x] = 0 + k[0] src[0][x] + k[1] src[1][x]
 * + ... (taps ascending), x in [0, w).  Horizontal: src[j] = a padded row
 * + j; vertical: src[j] = the horizontal results of row y + j - r. */
void tdc_filter_taps_f(float *o, const float *const *src, const float *k, int kn, int w);
void tdc_filter_taps_d(double *o, const double *const *src, const double *k, int kn, int w);

/* The vertical taps of output row y: src[j] = ring + (edge(y + j - r) mod
 * slots) * stride, j in [0, 2r]. */
void tdc_filter_ring_rows_f(const float **src, float *ring, size_t stride, int slots, int y, int h, int r,
                            tdc_edge_t e);
void tdc_filter_ring_rows_d(const double **src, double *ring, size_t stride, int slots, int y, int h, int r,
                            tdc_edge_t e);

/* Streams output rows [y0, y1) of an image of h rows through a ring of
 * slots = 2 rmax + 1 source rows: src_row(ctx, yy, yy % slots) for
 * every source row yy in [max(0, y0 - rmax), min(h, y1 + rmax)) in order,
 * out_row(ctx, y) as soon as rows up to y + rmax are in.  Every edge-mapped
 * tap row of y within rmax is then in the ring (clamp, and reflect by at
 * most rmax, map into [y - rmax, y + rmax]). */
void tdc_filter_stream(int y0, int y1, int h, int rmax, void (*src_row)(void *ctx, int yy, int slot),
                       void (*out_row)(void *ctx, int y), void *ctx);

#endif
