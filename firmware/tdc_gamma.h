/*
 * tdc_gamma.h - per-channel gamma decode (code -> linear light) and encode
 * (linear light -> code) through the panel's generated integer tables.
 *
 * Formats: codes are the panel's N-bit drive values; gval is a code in Q8
 * (tdc_gval_t, see tdc_fixed.h); linear light is Q24 (TDC_LIN_ONE = 1.0).
 */
#ifndef TDC_GAMMA_H
#define TDC_GAMMA_H

#include "tdc_panel.h"

/* Linear light of an integer code: exact table value round(2^24 v^gamma). */
static inline tdc_lin_t tdc_gamma_decode(const tdc_gamma_table_t *t, uint32_t code)
{
    return (tdc_lin_t)t->decode[code];
}

/*
 * Linear light of a fractional code g (Q8).  Linear interpolation between
 * neighbouring codes.  Scaling and overflow: table step < 2^24, times a
 * fraction < 2^8, fits 32 bits.  Error against (g/255)^gamma in double:
 * <= 0.5 LSB (Q24) rounding plus the interpolation error, which is at most
 * gamma(gamma-1)/8 / 255^2 + 2^-25 <= 5.8e-6 of full scale for gamma <= 2.3
 * (asserted in tests/unit/test_math.c).
 */
static inline tdc_lin_t tdc_gamma_decode_gval(const tdc_gamma_table_t *t, uint32_t g_q8)
{
    uint32_t k = g_q8 >> TDC_GVAL_FRAC;
    uint32_t f = g_q8 & ((1u << TDC_GVAL_FRAC) - 1u);
    uint32_t a = t->decode[k];
    uint32_t b = t->decode[k + 1u]; /* decode[C] duplicates decode[C-1] */
    return (tdc_lin_t)(a + (((b - a) * f + (1u << (TDC_GVAL_FRAC - 1))) >> TDC_GVAL_FRAC));
}

/*
 * Linear light of a fractional code g in Q16 (g = code * 2^16 + fraction),
 * for values that come out of interpolation with more precision than Q8
 * (TRM's U).  The fraction is used to 12 bits (1/4096 code).
 * Scaling and overflow: a table step is < 2^19 for gamma <= 4, times 2^12
 * < 2^31.  Error: as tdc_gamma_decode_gval plus <= 2^-12 code of slope.
 */
static inline tdc_lin_t tdc_gamma_decode_q16(const tdc_gamma_table_t *t, uint32_t g_q16)
{
    uint32_t k = g_q16 >> 16;
    uint32_t f = (g_q16 >> 4) & 0xfffu;
    uint32_t a = t->decode[k];
    uint32_t b = t->decode[k + 1u];
    return (tdc_lin_t)(a + (((b - a) * f + 0x800u) >> 12));
}

/*
 * Code for linear light L (Q24), clamped to [0, 1]: exactly the double
 * precision round((C-1) * L^(1/gamma)) applied to the Q24 value, because
 * the thresholds are the exact decision points (see tdc_panel.h).
 * Cost: one index lookup plus a short forward scan (at most 8 steps, in
 * the darkest bucket only; asserted by the exhaustive test).
 */
static inline uint32_t tdc_gamma_encode(const tdc_gamma_table_t *t, tdc_lin_t lin, uint32_t max_code)
{
    uint32_t l = lin <= 0 ? 0u : (lin >= TDC_LIN_ONE ? (uint32_t)TDC_LIN_ONE : (uint32_t)lin);
    uint32_t k = t->enc_index[l >> (TDC_LIN_FRAC - TDC_ENC_INDEX_BITS)];
    while (k < max_code && l >= t->enc_thresh[k + 1u]) {
        k++;
    }
    return k;
}

#endif /* TDC_GAMMA_H */
