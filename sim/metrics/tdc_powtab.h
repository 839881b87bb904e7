/*
 * tdc_powtab.h - x^a for one fixed exponent a by tables, for the metrics'
 * colour transforms (display encoding x^(1/2.2), L*a*b*'s cube root, FLIP's
 * HyAB^0.7), which called libm pow/cbrt once or three times per sample and
 * were 25-30 % of the simulator's CPU time (perf, 640x480 stereo).
 *
 * x = m 2^e with m in [1, 2): x^a = m^a * 2^(a e).  2^(a e) is one entry per
 * binary exponent (2046 entries, exp2 at init); m^a is linear interpolation
 * in a TDC_POWTAB_N-interval table over [1, 2].  Error: the interpolation's
 * h^2/8 max|f''| with h = 1/2048, |f''| = |a (a - 1)| m^(a-2) <= 1/4 for
 * 0 < a < 1: 7.5e-9 relative (measured by test_metrics: max 7.39e-9 for
 * a = 1/2.2, 6.62e-9 for 1/3, 6.26e-9 for 0.7), plus 2 ulp of the product;
 * below float precision (FLIP keeps L*a*b* in float) and 2e-6 of an 8-bit
 * code step for the encoding.  Zero, subnormals, negatives, inf and NaN go to
 * libm pow (the same value as before for those).  The same input gives the
 * same output on every thread: results stay independent of the thread count.
 */
#ifndef TDC_POWTAB_H
#define TDC_POWTAB_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define TDC_POWTAB_BITS 11
#define TDC_POWTAB_N (1 << TDC_POWTAB_BITS)

typedef struct {
    double a;
    double man[TDC_POWTAB_N + 2]; /* (1 + i / N)^a, i = 0..N, and a pad entry */
    double ex[2048];              /* 2^(a (E - 1023)) per biased exponent E */
} tdc_powtab_t;

/* Fills t for exponent a (about 4100 libm calls: build once, reuse). */
void tdc_powtab_init(tdc_powtab_t *t, double a);

/* The metrics' tables, built once per process (pthread_once). */
typedef enum {
    TDC_POWTAB_ENCODE = 0, /* 1 / 2.2: display encoding for PSNR and SSIM */
    TDC_POWTAB_CBRT,       /* 1 / 3: CIE L*a*b* */
    TDC_POWTAB_HYAB,       /* 0.7: FLIP's colour-difference compression q_c */
    TDC_POWTAB_COUNT
} tdc_powtab_id_t;
const tdc_powtab_t *tdc_powtab_metrics(tdc_powtab_id_t id);

static inline double tdc_powtab(const tdc_powtab_t *t, double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    const uint32_t E = (uint32_t)(u >> 52); /* sign bit included: negatives fall out */
    if (E == 0u || E >= 0x7ffu) {
        return pow(x, t->a);
    }
    const uint64_t m = u & ((UINT64_C(1) << 52) - 1u);
    const uint32_t i = (uint32_t)(m >> (52 - TDC_POWTAB_BITS));
    const double f = (double)(m & ((UINT64_C(1) << (52 - TDC_POWTAB_BITS)) - 1u)) *
                     (1.0 / (double)(UINT64_C(1) << (52 - TDC_POWTAB_BITS)));
    const double lo = t->man[i];
    return (lo + (t->man[i + 1] - lo) * f) * t->ex[E];
}

/* The same value as tdc_powtab for x > 0 finite and normal, written without
 * the libm branch and with the fraction formed by bits (1 + f 2^-41, less
 * 1: exact), so that an element-wise loop over it vectorises (AVX2
 * gathers); any other x gives an unspecified value - select around it. */
static inline double tdc_powtab_pos(const tdc_powtab_t *t, double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    const uint64_t E = (u >> 52) & 0x7ffu;
    const uint64_t i = (u >> (52 - TDC_POWTAB_BITS)) & (TDC_POWTAB_N - 1u);
    const uint64_t fb = ((u & ((UINT64_C(1) << (52 - TDC_POWTAB_BITS)) - 1u)) << TDC_POWTAB_BITS) |
                        UINT64_C(0x3ff0000000000000);
    double f;
    memcpy(&f, &fb, sizeof f);
    f -= 1.0;
    const double lo = t->man[i];
    return (lo + (t->man[i + 1] - lo) * f) * t->ex[E];
}

#endif
