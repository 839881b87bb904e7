/*
 * tdc_overdrive.c - overdrive table interpolation and previous-frame
 * quantisation maps (conventions in tdc_overdrive.h).
 */
#include "tdc_overdrive.h"

uint32_t tdc_od_lookup(const int16_t *t, unsigned n, uint32_t u_q16, uint32_t m_q16, uint32_t max_code)
{
    return n == 33u ? tdc_od_lookup_inline(t, 33u, u_q16, m_q16, max_code)
                    : tdc_od_lookup_inline(t, 17u, u_q16, m_q16, max_code);
}

void tdc_od_quant_tables(unsigned b, uint8_t enc[256], uint8_t dec[256])
{
    const uint32_t qmax = (1u << b) - 1u;
    for (uint32_t k = 0; k < 256u; k++) {
        enc[k] = (uint8_t)((k * qmax + 127u) / 255u);
        dec[k] = (uint8_t)(k <= qmax ? (k * 255u + qmax / 2u) / qmax : 255u);
    }
}
