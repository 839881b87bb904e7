/* tdc_filter.c - streamed separable convolution, float and double (see tdc_filter.h). */
#include "metrics/tdc_filter.h"

#include "tdc_par.h"

long tdc_par_min_work = 32768;

int tdc_filter_edge(int i, int n, tdc_edge_t e)
{
    if (e == TDC_EDGE_CLAMP || n == 1) {
        return i < 0 ? 0 : (i >= n ? n - 1 : i);
    }
    int period = 2 * n;
    i %= period;
    if (i < 0) {
        i += period;
    }
    return i < n ? i : period - 1 - i;
}

/*
 * Tap index outside, pixel index inside: the inner loop is element-wise (no
 * reassociation), so the vector and scalar code give the same bits
 * (TDC_SIMD_CLONES: tdc_par.h).  Blocks of 4 vectors (GCC/clang vector
 * extensions: 16 floats or doubles in the AVX2 clone, lowered to SSE2 pairs
 * in the default one) accumulate over all taps in registers - one store of
 * o per block - then the tail.  Every output is 0 + k[0] src[0] + k[1]
 * src[1] + ... in tap order either way, so the bits are the same.
 */
typedef float tdc_vf __attribute__((vector_size(32), aligned(4)));
typedef double tdc_vd __attribute__((vector_size(32), aligned(8)));
#define ROW_KERNEL(T, V, NAME)                                                                                \
    TDC_SIMD_CLONES void NAME(T *restrict o, const T *const *src, const T *restrict k, int kn, int w)         \
    {                                                                                                         \
        const int L = (int)(sizeof(V) / sizeof(T));                                                           \
        int x0 = 0;                                                                                           \
        for (; x0 + 4 * L <= w; x0 += 4 * L) {                                                                \
            V a0 = {0}, a1 = {0}, a2 = {0}, a3 = {0};                                                         \
            for (int j = 0; j < kn; j++) {                                                                    \
                const V kj = (V){0} + k[j];                                                                   \
                const V *p = (const V *)(const void *)(src[j] + x0);                                          \
                a0 += kj * p[0];                                                                              \
                a1 += kj * p[1];                                                                              \
                a2 += kj * p[2];                                                                              \
                a3 += kj * p[3];                                                                              \
            }                                                                                                 \
            V *q = (V *)(void *)(o + x0);                                                                     \
            q[0] = a0;                                                                                        \
            q[1] = a1;                                                                                        \
            q[2] = a2;                                                                                        \
            q[3] = a3;                                                                                        \
        }                                                                                                     \
        for (int x = x0; x < w; x++) {                                                                        \
            T a = 0;                                                                                          \
            for (int j = 0; j < kn; j++) {                                                                    \
                a += k[j] * src[j][x];                                                                        \
            }                                                                                                 \
            o[x] = a;                                                                                         \
        }                                                                                                     \
    }
ROW_KERNEL(float, tdc_vf, tdc_filter_taps_f)
ROW_KERNEL(double, tdc_vd, tdc_filter_taps_d)

#define RING_ROWS(T, NAME)                                                                                   \
    void NAME(const T **src, T *ring, size_t stride, int slots, int y, int h, int r, tdc_edge_t e)         \
    {                                                                                                        \
        for (int j = 0; j <= 2 * r; j++) {                                                                   \
            src[j] = ring + (size_t)(tdc_filter_edge(y + j - r, h, e) % slots) * stride;                     \
        }                                                                                                    \
    }
RING_ROWS(float, tdc_filter_ring_rows_f)
RING_ROWS(double, tdc_filter_ring_rows_d)

void tdc_filter_stream(int y0, int y1, int h, int rmax, void (*src_row)(void *ctx, int yy, int slot),
                       void (*out_row)(void *ctx, int y), void *ctx)
{
    const int slots = 2 * rmax + 1;
    int next = y0 - rmax > 0 ? y0 - rmax : 0;
    for (int y = y0; y < y1; y++) {
        const int last = y + rmax < h - 1 ? y + rmax : h - 1;
        for (; next <= last; next++) {
            src_row(ctx, next, next % slots);
        }
        out_row(ctx, y);
    }
}
