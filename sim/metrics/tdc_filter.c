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

/* One body for both precisions: T the element type. */
#define SEP_FILTER_BODY(T)                                                            \
    if (w < 1 || h < 1 || w > TDC_FILTER_MAX_W || r < 0 || r > TDC_FILTER_MAX_R) {    \
        return -1;                                                                    \
    }                                                                                 \
    const int kn = 2 * r + 1;                                                         \
    TDC_PAR_FOR((size_t)w *h)                                                         \
    for (int y = 0; y < h; y++) {                                                     \
        T pad[TDC_FILTER_MAX_W + 2 * TDC_FILTER_MAX_R];                               \
        const T *row = in + (size_t)y * w;                                            \
        for (int i = 0; i < w + 2 * r; i++) {                                         \
            int s = i - r;                                                            \
            pad[i] = row[s >= 0 && s < w ? s : edge_index(s, w, edge)];               \
        }                                                                             \
        T *o = tmp + (size_t)y * w;                                                   \
        for (int x = 0; x < w; x++) {                                                 \
            o[x] = 0;                                                                 \
        }                                                                             \
        for (int j = 0; j < kn; j++) {                                                \
            const T k = kx[j], *p = pad + j;                                          \
            for (int x = 0; x < w; x++) {                                             \
                o[x] += k * p[x];                                                     \
            }                                                                         \
        }                                                                             \
    }                                                                                 \
    TDC_PAR_FOR((size_t)w *h)                                                         \
    for (int y = 0; y < h; y++) {                                                     \
        T *o = out + (size_t)y * w;                                                   \
        for (int x = 0; x < w; x++) {                                                 \
            o[x] = 0;                                                                 \
        }                                                                             \
        for (int j = 0; j < kn; j++) {                                                \
            const T k = ky[j], *p = tmp + (size_t)edge_index(y + j - r, h, edge) * w; \
            for (int x = 0; x < w; x++) {                                             \
                o[x] += k * p[x];                                                     \
            }                                                                         \
        }                                                                             \
    }                                                                                 \
    return 0;

int tdc_sep_filter_f(const float *in, float *out, float *tmp, int w, int h, const float *kx, const float *ky, int r,
                     tdc_edge_t edge)
{
    SEP_FILTER_BODY(float)
}

int tdc_sep_filter_d(const double *in, double *out, double *tmp, int w, int h, const double *kx, const double *ky,
                     int r, tdc_edge_t edge)
{
    SEP_FILTER_BODY(double)
}
