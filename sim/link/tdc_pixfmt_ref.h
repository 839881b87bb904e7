/*
 * tdc_pixfmt_ref.h - double-precision reference of the link colour
 * conversions, written straight from the BT.709 definition, against which
 * tests/unit/test_link_pixfmt.c reports the fixed-point error.
 */
#ifndef TDC_PIXFMT_REF_H
#define TDC_PIXFMT_REF_H

#include <stdint.h>

/* BT.709 full range YCbCr (8-bit codes) -> RGB in [0, 255], unrounded, unclamped. */
void tdc_pixfmt_ref_ycbcr_to_rgb(double y, double cb, double cr, double rgb[3]);
/* RGB in [0, 255] -> YCbCr codes, unrounded. */
void tdc_pixfmt_ref_rgb_to_ycbcr(double r, double g, double b, double ycc[3]);

#endif
