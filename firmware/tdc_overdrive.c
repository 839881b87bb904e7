/*
 * tdc_overdrive.c - overdrive table interpolation and previous-frame
 * quantisation maps (conventions in tdc_overdrive.h).
 */
#include "tdc_overdrive.h"

uint32_t tdc_od_lookup(const int16_t *t, unsigned n, uint32_t u_q16, uint32_t m_q16, uint32_t max_code)
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
    int64_t code = tdc_asr64(v + 32768, 16);
    if (code < 0) {
        return 0;
    }
    return code > (int64_t)max_code ? max_code : (uint32_t)code;
}

void tdc_od_quant_tables(unsigned b, uint8_t enc[256], uint8_t dec[256])
{
    const uint32_t qmax = (1u << b) - 1u;
    for (uint32_t k = 0; k < 256u; k++) {
        enc[k] = (uint8_t)((k * qmax + 127u) / 255u);
        dec[k] = (uint8_t)(k <= qmax ? (k * 255u + qmax / 2u) / qmax : 255u);
    }
}
