/*
 * tdc_bilinear.h - the simulator's one bilinear sampler, for every element
 * type it samples (one body, generated per type): double frames (eye),
 * float error planes (flicker, temporal model), RGB888 codes (ASW warp).
 *
 * Channel c of pixel (x, y) of an image of `ch` interleaved channels, in
 * pixel-centre coordinates (pixel i's centre at i), edges clamped; the
 * arithmetic is in double whatever the element type:
 *   (a + (b - a) fx) (1 - fy) + (d + (e - d) fx) fy.
 */
#ifndef TDC_BILINEAR_H
#define TDC_BILINEAR_H

#include <stddef.h>
#include <stdint.h>

#define TDC_BILINEAR_DEFINE(T, NAME)                                                             \
    static inline double NAME(const T *img, int w, int h, int ch, double x, double y, int c)     \
    {                                                                                            \
        x = x < 0.0 ? 0.0 : (x > w - 1 ? w - 1 : x);                                             \
        y = y < 0.0 ? 0.0 : (y > h - 1 ? h - 1 : y);                                             \
        int x0 = (int)x, y0 = (int)y;                                                            \
        int x1 = x0 + 1 < w ? x0 + 1 : x0, y1 = y0 + 1 < h ? y0 + 1 : y0;                        \
        double fx = x - x0, fy = y - y0;                                                         \
        double a = img[ch * ((size_t)y0 * w + x0) + c], b = img[ch * ((size_t)y0 * w + x1) + c]; \
        double d = img[ch * ((size_t)y1 * w + x0) + c], e = img[ch * ((size_t)y1 * w + x1) + c]; \
        return (a + (b - a) * fx) * (1.0 - fy) + (d + (e - d) * fx) * fy;                        \
    }
TDC_BILINEAR_DEFINE(double, tdc_bilinear_d)
TDC_BILINEAR_DEFINE(float, tdc_bilinear_f)
TDC_BILINEAR_DEFINE(uint8_t, tdc_bilinear_u8)
#undef TDC_BILINEAR_DEFINE

#endif
