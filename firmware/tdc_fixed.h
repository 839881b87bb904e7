/*
 * tdc_fixed.h - the one header that decides numeric representation in the
 * firmware.  Every Q format and every saturating / rounding operator live
 * here, so that a stage never invents its own arithmetic (the status enum,
 * included from here, is tdc_status.h).
 *
 * Rules (docs/design.md §3): C11, no floating point, no implementation-defined
 * behaviour.  In particular:
 *   - right shifts of negative values are implementation-defined in C11, so
 *     every signed shift goes through tdc_asr32()/tdc_asr64(), which only
 *     ever shift non-negative values;
 *   - left shifts of negative values are undefined, so signed values are
 *     scaled up by multiplication (TDC_SHL32 multiplies);
 *   - signed overflow is undefined, so every operator that can leave its
 *     range widens to 64 bits first and saturates.
 *
 * Q formats used across the pipeline (value = integer / 2^frac_bits):
 *   q15_t   int16_t  Q1.15   weights in [-1, 1)
 *   q31_t   int32_t  Q1.31   (generic)
 *   tdc_lin_t int32_t Q7.24  linear light, 1.0 = TDC_LIN_ONE = 2^24.
 *            The TRM compensation beta = 2I - lin(UDI) spans [-1, 2], the
 *            sum of two frames [0, 2]; Q7.24 holds +-127 with 6e-8 steps,
 *            fine enough that the darkest 8-bit code (1/255)^2.3 = 2.9e-6
 *            is still 49 steps.
 *   tdc_gval_t uint16_t "code Q8": a gamma-compressed value in units of the
 *            panel's output code with 8 fractional bits (8-bit panels:
 *            0 .. 255*256).  Gaussian D and bilinear U work on these.
 *   tdc_res_t int32_t Q7.24  the TRM residual rho, linear light in [-1, 1].
 *            32 bits, not 16: the reduced frame adds w*rho to alpha, and
 *            where the two nearly cancel (dark side of an edge, a
 *            checkerboard) the output sits near black, where one 8-bit code
 *            is ~1e-6 of linear light.  A Q15 residual (step 3e-5) was
 *            measured at 2-3 LSB error there against the double reference
 *            (tests/unit/test_trm_ref.c); Q24 keeps it within 1.
 */
#ifndef TDC_FIXED_H
#define TDC_FIXED_H

#include <stdint.h>
#include <stddef.h>

#include "tdc_status.h"

typedef int16_t q15_t;
typedef int32_t q31_t;
typedef int32_t tdc_lin_t;
typedef uint16_t tdc_gval_t;
typedef int32_t tdc_res_t;

#define TDC_LIN_FRAC 24
#define TDC_LIN_ONE ((tdc_lin_t)1 << TDC_LIN_FRAC)
#define TDC_Q15_ONE 32768 /* 1.0 in Q15: not representable in q15_t, use int32 */
#define TDC_GVAL_FRAC 8

/* ---------------------------------------------------------------------
 * Shifts without implementation-defined behaviour.
 * tdc_asr32(x, n): floor(x / 2^n) for 0 <= n <= 31.  For x < 0 we use
 * ~x = -x - 1 >= 0, shift that, and complement back: floor semantics.
 * gcc and clang compile this to a single arithmetic shift.
 * ------------------------------------------------------------------- */
static inline int32_t tdc_asr32(int32_t x, unsigned n)
{
    return x >= 0 ? (int32_t)((uint32_t)x >> n) : (int32_t) ~((uint32_t)~x >> n);
}

static inline int64_t tdc_asr64(int64_t x, unsigned n)
{
    return x >= 0 ? (int64_t)((uint64_t)x >> n) : (int64_t) ~((uint64_t)~x >> n);
}

/* Round-half-up shift: floor((x + 2^(n-1)) / 2^n), n >= 1, computed in 64 bits. */
static inline int32_t tdc_rshr_round32(int32_t x, unsigned n)
{
    return (int32_t)tdc_asr64((int64_t)x + ((int64_t)1 << (n - 1)), n);
}

static inline int64_t tdc_rshr_round64(int64_t x, unsigned n)
{
    /* Caller guarantees |x| < 2^62 so the bias add cannot overflow. */
    return tdc_asr64(x + ((int64_t)1 << (n - 1)), n);
}

/* Round-half-up shift of an unsigned value, (x + 2^(n-1)) >> n for
 * 1 <= n <= 31 (63), in the operand's own width: the caller keeps
 * x + 2^(n-1) in range (the Scaling notes at each use). */
static inline uint32_t tdc_urshr32(uint32_t x, unsigned n)
{
    return (x + (1u << (n - 1u))) >> n;
}

static inline uint64_t tdc_urshr64(uint64_t x, unsigned n)
{
    return (x + ((uint64_t)1 << (n - 1u))) >> n;
}

/* Left shift of a signed value by multiplication (defined for negatives). */
#define TDC_SHL32(x, n) ((int32_t)(x) * ((int32_t)1 << (n)))

/* ---------------------------------------------------------------------
 * Saturation.
 * ------------------------------------------------------------------- */
static inline int32_t tdc_sat32(int64_t x)
{
    return x > INT32_MAX ? INT32_MAX : (x < INT32_MIN ? INT32_MIN : (int32_t)x);
}

static inline int16_t tdc_sat16(int32_t x)
{
    return x > INT16_MAX ? INT16_MAX : (x < INT16_MIN ? INT16_MIN : (int16_t)x);
}

static inline int32_t tdc_clamp32(int32_t x, int32_t lo, int32_t hi)
{
    return x < lo ? lo : (x > hi ? hi : x);
}

static inline int32_t tdc_abs32(int32_t x)
{
    /* INT32_MIN has no positive counterpart: saturate it. */
    return x >= 0 ? x : (x == INT32_MIN ? INT32_MAX : -x);
}

/* ---------------------------------------------------------------------
 * Multiplies.  Names say operand widths and the shift applied to the
 * product (libopus style).  All round half up and saturate to 32 bits.
 * ------------------------------------------------------------------- */

/* (a * b) >> 16 with rounding: Q16 x Qn -> Qn (the LCD model's linear
 * terms, the YCbCr chroma offsets).  |a*b| < 2^62: exact in 64 bits;
 * result saturated.  Where a kernel proves its product in range and runs
 * per pixel on the boards it writes tdc_rshr_round64(a * b, n) instead
 * (TRM's w rho): the saturation is a 64-bit compare pair there. */
static inline int32_t tdc_mul_q16_32(int32_t a_q16, int32_t b)
{
    return tdc_sat32(tdc_rshr_round64((int64_t)a_q16 * b, 16));
}

/* Saturating add of two 32-bit values. */
static inline int32_t tdc_add_sat32(int32_t a, int32_t b)
{
    return tdc_sat32((int64_t)a + b);
}

#endif /* TDC_FIXED_H */
