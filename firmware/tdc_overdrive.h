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

/* The lookup itself, inline so that the stage's loop specialises n. */
static inline uint32_t tdc_od_lookup_inline(const int16_t *t, unsigned n, uint32_t u_q16, uint32_t m_q16,
                                            uint32_t max_code)
{
    /* n - 1 = 16 -> 12 fraction bits, n - 1 = 32 -> 11. */
    const unsigned fb = n == 33u ? 11u : 12u;
    const uint32_t fmask = (1u << fb) - 1u;
    const unsigned last = n - 1u;
    if (u_q16 > 65536u) {
        u_q16 = 65536u;
    }
    if (m_q16 > 65536u) {
        m_q16 = 65536u;
    }
    unsigned iu = (unsigned)(u_q16 >> fb);
    unsigned im = (unsigned)(m_q16 >> fb);
    int32_t fu = (int32_t)(u_q16 & fmask);
    int32_t fm = (int32_t)(m_q16 & fmask);
    if (iu >= last) { /* u == 1.0 exactly: last node, no fraction */
        iu = last - 1u;
        fu = (int32_t)fmask + 1;
    }
    if (im >= last) {
        im = last - 1u;
        fm = (int32_t)fmask + 1;
    }
    const int16_t *r0 = t + (size_t)iu * n + im;
    const int16_t *r1 = r0 + n;
    /* Delta along m on both rows, then along u; Q4 code units scaled by 2^fb. */
    int32_t a = TDC_SHL32(r0[0], fb) + (r0[1] - r0[0]) * fm;
    int32_t b = TDC_SHL32(r1[0], fb) + (r1[1] - r1[0]) * fm;
    /* |a|, |b| < 2^27; (b - a) * fu < 2^28 * 2^12: widen to 64 bits. */
    int64_t d = (int64_t)a * ((int64_t)1 << fb) + (int64_t)(b - a) * fu; /* Q4 * 2^(2 fb) */
    /* drive in Q16 code units: m * max_code + delta * 2^(16 - 4). */
    int64_t v = (int64_t)m_q16 * max_code + tdc_asr64(d, 2u * fb - 12u);
    int64_t code = tdc_rshr_round64(v, 16);
    if (code < 0) {
        return 0;
    }
    return code > (int64_t)max_code ? max_code : (uint32_t)code;
}


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
