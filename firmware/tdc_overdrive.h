/*
 * tdc_overdrive.h - overdrive table lookup (as monitor scalers do it) and
 * the packed previous-frame buffers of the LCD stage.
 *
 * Table convention (also in tdc_lcd.h): N x N int16, N = 17 or 33, nodes
 * equally spaced in NORMALISED value: node i <-> i / (N-1).
 *   row    i = PREVIOUS drive value u,
 *   column j = TARGET merged value m (the gamma-compressed pair mean),
 *   entry [i * N + j] = DELTA drive - target, in 1/16 output code
 *   (TDC_OD_DELTA_FRAC = 4): drive = m + delta.
 * Delta, not absolute: the identity part (drive = target) is then exact
 * between nodes and only the smooth overdrive correction is interpolated.
 * Because N-1 is a power of two, a Q16 value x lies at node x >> (16 - log2(N-1))
 * with fraction x & (2^(16 - log2(N-1)) - 1): no division per pixel.
 */
#ifndef TDC_OVERDRIVE_H
#define TDC_OVERDRIVE_H

#include "tdc_fixed.h"

/*
 * Drive code for previous drive u and target m (both Q16, [0, 65536]) from
 * table t of n x n (n = 17 or 33), for a panel with max_code = C-1.
 * Bilinear interpolation of the delta; result rounded and clamped to
 * [0, max_code].
 * Scaling and overflow: entries |e| < 2^15, fraction < 2^12, so each
 * interpolation product < 2^28 in int32; m * max_code < 2^26.
 */
uint32_t tdc_od_lookup(const int16_t *t, unsigned n, uint32_t u_q16, uint32_t m_q16, uint32_t max_code);

/*
 * Packed sample buffers: sample s occupies bits [s*b, s*b + b) of the byte
 * array (little-endian bit order), b in 4..8.  The buffer needs one byte of
 * slack past the last sample (TDC_LCD_PACKED_BYTES) because access reads a
 * 16-bit window.
 */
static inline uint32_t tdc_od_unpack(const uint8_t *buf, size_t s, unsigned b)
{
    size_t bit = s * b;
    size_t byte = bit >> 3;
    uint32_t win = (uint32_t)buf[byte] | ((uint32_t)buf[byte + 1u] << 8);
    return (win >> (bit & 7u)) & ((1u << b) - 1u);
}

static inline void tdc_od_pack(uint8_t *buf, size_t s, unsigned b, uint32_t v)
{
    size_t bit = s * b;
    size_t byte = bit >> 3;
    unsigned sh = (unsigned)(bit & 7u);
    uint32_t mask = ((1u << b) - 1u) << sh;
    uint32_t win = (uint32_t)buf[byte] | ((uint32_t)buf[byte + 1u] << 8);
    win = (win & ~mask) | ((v << sh) & mask);
    buf[byte] = (uint8_t)win;
    buf[byte + 1u] = (uint8_t)(win >> 8);
}

/* Reduced-precision code maps for b bits: enc[k] = round(k (2^b-1) / 255),
 * dec[q] = round(q 255 / (2^b-1)); b = 8 gives the identity. */
void tdc_od_quant_tables(unsigned b, uint8_t enc[256], uint8_t dec[256]);

#endif /* TDC_OVERDRIVE_H */
