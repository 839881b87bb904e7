/*
 * tdc_math_log2.c - log2 in Q24 (tdc_math.h), from the generated mantissa
 * table; used by the foveation stage (eq. 2.2, the radial table) and its
 * log-rectilinear warp.
 */
#include "tdc_fov_tables.h"
#include "tdc_math.h"

int32_t tdc_log2_q24(uint64_t x)
{
    if (x == 0) {
        return 0;
    }
    const unsigned e = 63u - tdc_clz64(x);
    const uint64_t m = x << (63u - e);
    const uint32_t idx = (uint32_t)(m >> 55) & 255u;
    const uint32_t fr = (uint32_t)(m >> 39) & 0xFFFFu;
    const uint32_t a = tdc_fov_log2_tab[idx], b = tdc_fov_log2_tab[idx + 1u];
    const uint32_t val = a + (uint32_t)tdc_urshr64((uint64_t)(b - a) * fr, 16); /* Q30 <= 2^30 */
    return (int32_t)(e << 24) + (int32_t)tdc_urshr32(val, 6); /* Q30 -> Q24 */
}
