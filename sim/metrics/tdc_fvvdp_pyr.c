/*
 * tdc_fvvdp_pyr.c - the decimated Laplacian pyramid FovVideoVDP decomposes
 * each temporal channel into (paper section 3.2; Burt & Adelson 1983).
 *
 * Kernel: the 5-tap binomial-like [1/4 - a/2, 1/4, a, 1/4, 1/4 - a/2] with
 * a = 0.4 (the reference's kernel_a).  Reduce filters and keeps every second
 * sample (ceil(n/2) samples, half-sample symmetric edges: x[-1] = x[0],
 * x[-2] = x[1], x[n] = x[n-1], x[n+1] = x[n-2]).  Expand puts the samples on
 * the even positions of a zero-interleaved line, adds one copy of the first
 * sample two positions before the start and one of the last just past the
 * end (as the reference pads), and filters with twice the kernel.  The two
 * are exact inverses only together with the band they leave (L = G -
 * expand(reduce G)), which is what reconstruction needs.
 *
 * Bands: peak frequencies ppd/2 for band 0 and 0.3228 * 2^-k * ppd/2 after
 * it (the reference's band_freqs); bands whose frequency falls to 0.5 cpd or
 * below end the pyramid, and it never goes below a 2 x 2 level.
 *
 * Both passes run over rows in parallel (sim/tdc_par.h); each output sample
 * is the same sum in the same order whatever the thread count.
 */
#include <math.h>
#include <string.h>

#include "metrics/tdc_fvvdp.h"
#include "tdc_par.h"

#define KA 0.4
static const double K[5] = { 0.25 - KA / 2.0, 0.25, KA, 0.25, 0.25 - KA / 2.0 };

int tdc_fvvdp_pyr_layout(tdc_fvvdp_pyr_t *p, int w, int h, double ppd)
{
    int mn = w < h ? w : h;
    if (mn < 4 || ppd <= 0.0) {
        return -1;
    }
    int max_levels = (int)floor(log2((double)mn)) - 1;
    int max_band = max_levels;
    for (int k = 0; k < 15; k++) {
        double f = (k == 0 ? 1.0 : 0.3228 * pow(2.0, -(k - 1))) * ppd / 2.0;
        if (f <= 0.5) {
            max_band = k;
            break;
        }
    }
    int height = max_band + 1 < max_levels ? max_band + 1 : max_levels;
    if (height + 1 > TDC_FVVDP_MAX_LEVELS) {
        return -1;
    }
    p->levels = height + 1;
    int cw = w, ch = h;
    for (int l = 0; l < p->levels; l++) {
        p->w[l] = cw;
        p->h[l] = ch;
        p->rho[l] = (l == 0 ? 1.0 : 0.3228 * pow(2.0, -(l - 1))) * ppd / 2.0;
        cw = (cw + 1) / 2;
        ch = (ch + 1) / 2;
    }
    return 0;
}

static inline int refl(int j, int n)
{
    return j < 0 ? -1 - j : j >= n ? 2 * n - 1 - j : j;
}

void tdc_fvvdp_reduce(const double *src, int w, int h, double *dst, double *tmp)
{
    int w2 = (w + 1) / 2, h2 = (h + 1) / 2;
    /* Row i: vertical into tmp row i (w), then horizontal from it into dst
     * row i (w2): one parallel loop, no barrier between the passes and the
     * tmp row still in cache (the same operations as two passes) */
    TDC_PAR_FOR((long)w * h2)
    for (int i = 0; i < h2; i++) {
        const double *r0 = src + (size_t)refl(2 * i - 2, h) * w, *r1 = src + (size_t)refl(2 * i - 1, h) * w;
        const double *r2 = src + (size_t)refl(2 * i, h) * w, *r3 = src + (size_t)refl(2 * i + 1, h) * w;
        const double *r4 = src + (size_t)refl(2 * i + 2, h) * w;
        double *t = tmp + (size_t)i * w;
        TDC_SIMD
        for (int x = 0; x < w; x++) {
            t[x] = K[0] * r0[x] + K[1] * r1[x] + K[2] * r2[x] + K[3] * r3[x] + K[4] * r4[x];
        }
        double *o = dst + (size_t)i * w2;
        for (int x = 0; x < w2; x++) {
            int c = 2 * x;
            if (c >= 2 && c + 2 < w) {
                o[x] = K[0] * t[c - 2] + K[1] * t[c - 1] + K[2] * t[c] + K[3] * t[c + 1] + K[4] * t[c + 2];
            } else {
                double s = 0.0;
                for (int k = 0; k < 5; k++) {
                    s += K[k] * t[refl(c + k - 2, w)];
                }
                o[x] = s;
            }
        }
    }
}

/* Sample j of the zero-interleaved, padded line of an expand to n samples
 * from m = ceil(n/2) samples x (stride s); the padding is x[0] at j = -2 and
 * x[m-1] just past the end (j = n for even n, n + 1 for odd n). */
static inline double up(const double *x, int s, int n, int j)
{
    if (j >= 0 && j < n) {
        return (j & 1) ? 0.0 : x[(size_t)(j / 2) * s];
    }
    if (j == -2) {
        return x[0];
    }
    if (j == ((n & 1) ? n + 1 : n)) {
        return x[(size_t)((n + 1) / 2 - 1) * s];
    }
    return 0.0;
}

void tdc_fvvdp_expand_row(const double *src, int w, int h, int i, double *t, double *o)
{
    int w2 = (w + 1) / 2;
    /* Vertical into t (w2): output row i takes rows j = i-2..i+2 of the
     * interleaved column; only the even (or padding) ones are non-zero. */
    for (int x = 0; x < w2; x++) {
        t[x] = 0.0;
    }
    for (int k = 0; k < 5; k++) {
        int j = i + k - 2;
        const double *row;
        if (j >= 0 && j < h) {
            if (j & 1) {
                continue;
            }
            row = src + (size_t)(j / 2) * w2;
        } else if (j == -2) {
            row = src;
        } else if (j == ((h & 1) ? h + 1 : h)) {
            row = src + (size_t)((h + 1) / 2 - 1) * w2;
        } else {
            continue;
        }
        double kk = 2.0 * K[k];
        TDC_SIMD
        for (int x = 0; x < w2; x++) {
            t[x] += kk * row[x];
        }
    }
    /* Horizontal from t into o (w). */
    for (int x = 0; x < w; x++) {
        double s = 0.0;
        if (x >= 2 && x + 2 < w) {
            /* Even x: taps x-2, x, x+2 (k = 0, 2, 4); odd x: x-1, x+1. */
            if (x & 1) {
                s = 2.0 * K[1] * t[(x - 1) / 2] + 2.0 * K[3] * t[(x + 1) / 2];
            } else {
                s = 2.0 * K[0] * t[x / 2 - 1] + 2.0 * K[2] * t[x / 2] + 2.0 * K[4] * t[x / 2 + 1];
            }
        } else {
            for (int k = 0; k < 5; k++) {
                s += 2.0 * K[k] * up(t, 1, w, x + k - 2);
            }
        }
        o[x] = s;
    }
}

void tdc_fvvdp_expand(const double *src, int w, int h, double *dst, double *tmp)
{
    int w2 = (w + 1) / 2;
    TDC_PAR_FOR((long)w * h)
    for (int i = 0; i < h; i++) {
        tdc_fvvdp_expand_row(src, w, h, i, tmp + (size_t)i * w2, dst + (size_t)i * w);
    }
}
