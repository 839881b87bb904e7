/* tdc_pixfmt_ref.c - float reference of BT.709 full-range YCbCr (ITU-R BT.709-6, Kr = 0.2126, Kb = 0.0722). */
#include "link/tdc_pixfmt_ref.h"

static const double KR = 0.2126, KB = 0.0722;

void tdc_pixfmt_ref_ycbcr_to_rgb(double y, double cb, double cr, double rgb[3])
{
    const double kg = 1.0 - KR - KB;
    const double u = cb - 128.0, v = cr - 128.0;
    rgb[0] = y + 2.0 * (1.0 - KR) * v;
    rgb[2] = y + 2.0 * (1.0 - KB) * u;
    rgb[1] = (y - KR * rgb[0] - KB * rgb[2]) / kg;
}

void tdc_pixfmt_ref_rgb_to_ycbcr(double r, double g, double b, double ycc[3])
{
    const double y = KR * r + (1.0 - KR - KB) * g + KB * b;
    ycc[0] = y;
    ycc[1] = 128.0 + (b - y) / (2.0 * (1.0 - KB));
    ycc[2] = 128.0 + (r - y) / (2.0 * (1.0 - KR));
}
