/*
 * tdc_math.h - integer math helpers: exp(-x), reciprocal, division in Q15,
 * integer square root.  Each is tested exhaustively or densely against
 * double precision in tests/unit/test_math.c, which asserts the error bounds
 * stated here.
 */
#ifndef TDC_MATH_H
#define TDC_MATH_H

#include "tdc_fixed.h"

/* 1 where the CPU divides 64 by 64 bits in hardware (x86-64, AArch64): the
 * reciprocal and the square root then divide directly; elsewhere (Cortex-M:
 * 32-bit UDIV only) they use long division in 16-bit digits.  Both give the
 * same bits; -DTDC_HW_DIV64=0 builds the Cortex-M arithmetic on a host
 * (tests/unit/test_math runs both ways). */
#ifndef TDC_HW_DIV64
#if defined(__x86_64__) || defined(__aarch64__)
#define TDC_HW_DIV64 1
#else
#define TDC_HW_DIV64 0
#endif
#endif

/* Count leading zeros of a non-zero 32-bit value (x == 0 gives 32). */
static inline unsigned tdc_clz32(uint32_t x)
{
    return x ? (unsigned)__builtin_clz(x) : 32u;
}

/*
 * exp(-x) for x >= 0.
 * Input: x in unsigned Q16.16 (0 .. 65535.99998).
 * Output: Q15 in int32, exp(0) = 32768 exactly, monotone non-increasing.
 * Method: exp(-x) = 2^-(x/ln2) = 2^-n * 2^-g; 2^-g by a quintic in Q30.
 * Scaling and overflow: products in int64, no intermediate exceeds 2^62.
 * Error: |out - 32768*exp(-x)| <= 0.5 LSB + 0.01 LSB (asserted <= 0.51
 * over all 2^20 inputs x < 16 and a sparse sweep of the rest).
 */
int32_t tdc_exp_neg_q16(uint32_t x_q16);

/* The same exp(-x) in Q30 (exp(0) = 2^30), for tables that interpolate
 * and round once.  Error: <= 0.5 LSB + 1.7e-7 relative (polynomial). */
uint32_t tdc_exp_neg_q16_q30(uint32_t x_q16);

/*
 * Reciprocal of a normalised value.
 * Input: dn in [2^31, 2^32), read as the Q32 fraction dn / 2^32 in [0.5, 1).
 * Output: 1/(dn/2^32) in Q30, i.e. round(2^62 / dn), in (2^30, 2^31].
 * Exactly floor((2^62 + floor(dn/2)) / dn): within 0.5 LSB of Q30.
 * Method: on targets with a 64-bit hardware divide (x86-64, AArch64) that
 * division; elsewhere (Cortex-M: 32-bit divide only) tdc_recip_norm_q30_div32.
 * All three versions give the same bits (tests/unit/test_math.c compares them).
 */
uint32_t tdc_recip_norm_q30(uint32_t dn);
/* Long division in 16-bit digits with two 32-bit divides. */
uint32_t tdc_recip_norm_q30_div32(uint32_t dn);
/* Linear seed 48/17 - 32/17*d, three Newton steps, then a correction to
 * exactly the value above. */
uint32_t tdc_recip_norm_q30_newton(uint32_t dn);

/*
 * num / den in Q15 for 0 <= num <= den, den > 0 (both any 32-bit scale).
 * Output: in [0, 32768]; den == 0 returns 0 (callers define c = 0 there).
 * Uses tdc_recip_norm_q30, so no hardware 64-bit divide is needed.
 * Error: <= 1 LSB of Q15 against double (asserted on a dense sweep).
 */
int32_t tdc_div_q15(uint32_t num, uint32_t den);

/*
 * num / den in Q30 for 0 <= num <= den, den > 0.
 * Output: in [0, 2^30]; den == 0 returns 0.
 * Error: <= 1 LSB of Q30 against double (asserted on a dense sweep).
 * Used where a ratio is multiplied by a large gain afterwards (the TRM
 * motion weight exp(-s c) with s up to hundreds).
 */
int32_t tdc_div_q30(uint32_t num, uint32_t den);

/*
 * Integer hash: a 32-bit mix with full avalanche (xorshift-multiply
 * "lowbias32" constants).  Unsigned arithmetic only, so it wraps the same
 * on every CPU.  Used for deterministic noise and jitter in test contents,
 * the renderer's sampling and the simulator's scenes.
 */
static inline uint32_t tdc_mix32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

/* floor(sqrt(x)) for a 64-bit unsigned x, exact: integer Newton from
 * above with a digit-method start (two or three 64/32 divisions). */
uint32_t tdc_isqrt64(uint64_t x);
/* The same by the digit-by-digit method (2 bits per step): the reference
 * the tests compare with, and the path for the top of the range. */
uint32_t tdc_isqrt64_digits(uint64_t x);

/* floor(u / v) for (u >> 32) < v: the hardware divide (TDC_HW_DIV64) or
 * tdc_udiv64_32_digits, long division with two 32-bit divides. */
uint32_t tdc_udiv64_32(uint64_t u, uint32_t v);
uint32_t tdc_udiv64_32_digits(uint64_t u, uint32_t v);

#endif /* TDC_MATH_H */
