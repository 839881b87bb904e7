/* tdc_filter.c - separable convolution, float and double (see tdc_filter.h). */
#include "metrics/tdc_filter.h"

#include "tdc_par.h"

long tdc_par_min_work = 32768;

static int edge_index(int i, int n, tdc_edge_t e)
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
 * The row kernel of both passes: o[x] = sum_j k[j] * src[j][x], j ascending
 * (horizontal: src[j] = the padded row + j; vertical: src[j] = row y + j - r
 * of the horizontal result).  Tap index outside, pixel index inside: the
 * inner loop is element-wise (no reassociation), so the vector and scalar
 * code give the same bits (TDC_SIMD, TDC_SIMD_CLONES: tdc_par.h).  Measured on 640x480 stereo
 * (perf, 1 thread): the filters fell from 31 % to ~13 % of the run's CPU.
 */
/* Blocks of 4 vectors (GCC/clang vector extensions: 16 floats or doubles in
 * the AVX2 clone, lowered to SSE2 pairs in the default one) accumulate over
 * all taps in registers - one load/store of o per block instead of one per
 * tap (1440x1600 stereo: the double kernel fell from 9.9 % to ~5 % of the
 * run) - then the tail as before.  Every output is 0 + k[0] src[0] +
 * k[1] src[1] + ... in tap order either way, so the bits are the same. */
typedef float tdc_vf __attribute__((vector_size(32), aligned(4)));
typedef double tdc_vd __attribute__((vector_size(32), aligned(8)));
#define ROW_KERNEL(T, V, NAME)                                                                               \
    TDC_SIMD_CLONES static void NAME(T *restrict o, const T *const *src, const T *restrict k, int kn, int w) \
    {                                                                                                        \
        const int L = (int)(sizeof(V) / sizeof(T));                                                          \
        int x0 = 0;                                                                                          \
        for (; x0 + 4 * L <= w; x0 += 4 * L) {                                                               \
            V a0 = {0}, a1 = {0}, a2 = {0}, a3 = {0};                                                        \
            for (int j = 0; j < kn; j++) {                                                                   \
                const V kj = (V){0} + k[j];                                                                  \
                const V *p = (const V *)(const void *)(src[j] + x0);                                         \
                a0 += kj * p[0];                                                                             \
                a1 += kj * p[1];                                                                             \
                a2 += kj * p[2];                                                                             \
                a3 += kj * p[3];                                                                             \
            }                                                                                                \
            V *q = (V *)(void *)(o + x0);                                                                    \
            q[0] = a0;                                                                                       \
            q[1] = a1;                                                                                       \
            q[2] = a2;                                                                                       \
            q[3] = a3;                                                                                       \
        }                                                                                                    \
        for (int x = x0; x < w; x++) {                                                                       \
            o[x] = 0;                                                                                        \
        }                                                                                                    \
        for (int j = 0; j < kn; j++) {                                                                       \
            const T kj = k[j];                                                                               \
            const T *restrict p = src[j];                                                                    \
            for (int x = x0; x < w; x++) {                                                                   \
                o[x] += kj * p[x];                                                                           \
            }                                                                                                \
        }                                                                                                    \
    }
ROW_KERNEL(float, tdc_vf, row_kernel_f)
ROW_KERNEL(double, tdc_vd, row_kernel_d)

/* One body for both precisions: T the element type, RK its row kernel. */
#define SEP_FILTER_BODY(T, RK)                                                     \
    if (w < 1 || h < 1 || w > TDC_FILTER_MAX_W || r < 0 || r > TDC_FILTER_MAX_R) { \
        return -1;                                                                 \
    }                                                                              \
    const int kn = 2 * r + 1;                                                      \
    TDC_PAR_FOR((size_t)w *h)                                                      \
    for (int y = 0; y < h; y++) {                                                  \
        T pad[TDC_FILTER_MAX_W + 2 * TDC_FILTER_MAX_R];                            \
        const T *src[2 * TDC_FILTER_MAX_R + 1];                                    \
        const T *row = in + (size_t)y * w;                                         \
        for (int i = 0; i < w + 2 * r; i++) {                                      \
            int s = i - r;                                                         \
            pad[i] = row[s >= 0 && s < w ? s : edge_index(s, w, edge)];            \
        }                                                                          \
        for (int j = 0; j < kn; j++) {                                             \
            src[j] = pad + j;                                                      \
        }                                                                          \
        RK(tmp + (size_t)y * w, src, kx, kn, w);                                   \
    }                                                                              \
    TDC_PAR_FOR((size_t)w *h)                                                      \
    for (int y = 0; y < h; y++) {                                                  \
        const T *src[2 * TDC_FILTER_MAX_R + 1];                                    \
        for (int j = 0; j < kn; j++) {                                             \
            src[j] = tmp + (size_t)edge_index(y + j - r, h, edge) * w;             \
        }                                                                          \
        RK(out + (size_t)y * w, src, ky, kn, w);                                   \
    }                                                                              \
    return 0;

int tdc_sep_filter_f(const float *in, float *out, float *tmp, int w, int h, const float *kx, const float *ky, int r,
                     tdc_edge_t edge)
{
    SEP_FILTER_BODY(float, row_kernel_f)
}

int tdc_sep_filter_d(const double *in, double *out, double *tmp, int w, int h, const double *kx, const double *ky,
                     int r, tdc_edge_t edge)
{
    SEP_FILTER_BODY(double, row_kernel_d)
}
