/*
 * tdc_math.h - integer math helpers: exp(-x), reciprocal, division in Q15,
 * integer square root, and the small generic kernels of the pixel loops
 * (mean of up to 4, division by 1..8, table square root, a 3-word hash).  Each is tested exhaustively or densely against
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

/* ---------------------------------------------------------------------
 * Small kernels of the pixel loops.  Inline (their callers are per-pixel
 * loops in other files; a call each would cost more than the body) and
 * each checked exhaustively in tests/unit/test_math.c.
 * ------------------------------------------------------------------- */

/* round(sum / n), half up, for n = 1..4 and sum <= 255 n (a mean of 1..4
 * 8-bit samples, e.g. tile-ordered assembly's window); n outside 1..4
 * gives 0.  Scaling and overflow: round(sum / n) = floor((2 sum + n) / 2n)
 * = ((2 sum + n) * ceil(2^16 / 2n)) >> 16, exact for sum <= 1020 (every sum
 * and n checked). */
static inline uint8_t tdc_mean_u8(uint32_t sum, unsigned n)
{
    static const uint16_t half_recip_q16[5] = {0, 32768, 16384, 10923, 8192};
    if (n < 1u || n > 4u) return 0;
    return (uint8_t)(((2u * sum + n) * half_recip_q16[n]) >> 16);
}

/* floor(x / n) for 1 <= n <= 8 and x < 2^29 by a reciprocal multiply (no
 * divide instruction); other n give 0.  floor(x / n) =
 * (x * ceil(2^32 / n)) >> 32: the error term x (n ceil(2^32/n) - 2^32) / 2^32
 * < x n / 2^32 stays below 1/n (checked for every x < 2^21 and the top). */
static inline uint32_t tdc_div_small(uint32_t x, uint32_t n)
{
    static const uint32_t recip32[9] = {0,          0,          2147483648u, 1431655766u, 1073741824u,
                                        858993460u, 715827883u, 613566757u,  536870912u};
    if (n < 1u || n > 8u) return 0;
    if (n == 1u) return x;
    return (uint32_t)(((uint64_t)x * recip32[n]) >> 32);
}

/* floor(4096 sqrt(i)) for i = 64 .. 255 (tdc_math.c). */
extern const uint16_t tdc_sqrt_q8_tab[192];

/* 256 sqrt(d) for 0 <= d < 2^20 (larger d saturate), table + linear
 * interpolation: |error| <= 12 in Q8 (8.3 measured over every d; the
 * exact floor is tdc_isqrt64).  Used for the assembly clamp's box edge. */
static inline uint32_t tdc_sqrt_q8(uint32_t d)
{
    /* Normalise: z even, xn = d << z in [2^30, 2^32) (z >= 12 because
     * d < 2^20); sqrt(xn) from the table by linear interpolation in
     * [32768, 65536] (chord error <= 0.25, entry floor <= 1: |error| <= 1.25
     * units of 2^-16 relative); then 256 sqrt(d) = sqrt(xn) * 2^(8 - z/2).
     * Scaling and overflow: entry differences <= 255, times the 24-bit
     * fraction < 2^32 (uint32). */
    if (d == 0) return 0;
    if (d >= (1u << 20)) d = (1u << 20) - 1u;
    const unsigned z = tdc_clz32(d) & ~1u;
    const uint32_t xn = d << z;
    const uint32_t i = (xn >> 24) - 64u, f = xn & 0xFFFFFFu;
    const uint32_t lo = tdc_sqrt_q8_tab[i], hi = i + 1u < 192u ? tdc_sqrt_q8_tab[i + 1u] : 65536u;
    const uint32_t r = lo + (((hi - lo) * f) >> 24);
    /* half = z / 2 in 6 .. 15 (z >= 12): r << (8 - half) or r >> (half - 8),
     * one shift: r << 2 <= 2^18, then >> (half - 6), exact both ways. */
    const unsigned half = z >> 1;
    return (r << 2) >> (half - 6u);
}

/* Hash of three words (murmur3 finaliser over a multiplicative mix): well
 * spread, unsigned arithmetic only (wraps the same everywhere).  Tile-
 * ordered assembly's random band draws its bit from (tile_x, tile_y,
 * frame); renderer and controller must agree, and the assembly golden
 * vectors pin it: the constants are part of the stream format's behaviour
 * (tests/unit/test_math.c checks known values). */
static inline uint32_t tdc_hash3(uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t h = a * 0x9E3779B1u ^ b * 0x85EBCA77u ^ c * 0xC2B2AE3Du;
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    h *= 0xC2B2AE35u;
    h ^= h >> 16;
    return h;
}

#endif /* TDC_MATH_H */
