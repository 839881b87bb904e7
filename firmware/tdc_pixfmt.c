/*
 * tdc_pixfmt.c - unpacking of the link pixel formats to RGB888.  See
 * tdc_pixfmt.h for the wire layouts.  Integer only; every conversion is a
 * pure function of the input bytes, so host and ARM agree bit for bit.
 */
#include "tdc_pixfmt.h"

#include <string.h>

#include "tdc_fixed.h"
#include "tdc_bytes.h"

int tdc_pixfmt_valid(uint32_t f)
{
    return f >= (uint32_t)TDC_PIXFMT_RGB888 && f < (uint32_t)TDC_PIXFMT_COUNT;
}

uint32_t tdc_pixfmt_payload_bytes(tdc_pixfmt_t f, uint32_t w, uint32_t h)
{
    /* w, h <= 65535: w * h * 4 < 2^34 could overflow 32 bits, so callers
     * bound w * h first (the decoder checks against the panel size). */
    switch (f) {
    case TDC_PIXFMT_RGB888: return w * h * 3u;
    case TDC_PIXFMT_RGB565: return w * h * 2u;
    case TDC_PIXFMT_RGB30: return w * h * 4u;
    case TDC_PIXFMT_YCBCR420: return w * h + 2u * (((w + 1u) / 2u) * ((h + 1u) / 2u));
    default: return 0;
    }
}

void tdc_pixfmt_unpack_rgb888(const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride)
{
    const size_t row = (size_t)w * 3u;
    for (uint32_t y = 0; y < h; y++) {
        const uint8_t *s = src + row * y;
        memcpy(dst + (size_t)dst_stride * y, s, row);
    }
}

static inline void rgb565_px(const uint8_t *s, uint8_t *d)
{
    const uint32_t v = tdc_get_le16(s);
    const uint32_t r5 = v >> 11, g6 = (v >> 5) & 0x3Fu, b5 = v & 0x1Fu;
    /* Bit replication: 0 -> 0, max -> 255, monotone. */
    d[0] = (uint8_t)((r5 << 3) | (r5 >> 2));
    d[1] = (uint8_t)((g6 << 2) | (g6 >> 4));
    d[2] = (uint8_t)((b5 << 3) | (b5 >> 2));
}

void tdc_pixfmt_unpack_rgb565(const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride)
{
    TDC_PIXFMT_ROWS(src, w * 2u, 2u, dst, dst_stride, 3u, w, h, rgb565_px);
}

static inline void rgb30_px(const uint8_t *s, uint8_t *d)
{
    const uint32_t v = tdc_get_le32(s);
    d[0] = tdc_pixfmt_u10_to_u8(v & 0x3FFu);
    d[1] = tdc_pixfmt_u10_to_u8((v >> 10) & 0x3FFu);
    d[2] = tdc_pixfmt_u10_to_u8((v >> 20) & 0x3FFu);
}

void tdc_pixfmt_unpack_rgb30(const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride)
{
    TDC_PIXFMT_ROWS(src, w * 4u, 4u, dst, dst_stride, 3u, w, h, rgb30_px);
}

/* Q16 value + rounding -> 8-bit code, clamped.  Scaling and overflow:
 * |v_q16| <= 255 * 2^16 + 121609 * 128 < 2^25, no overflow in int32. */
static inline uint8_t tdc_q16_to_u8_sat(int32_t v_q16)
{
    const int32_t v = tdc_rshr_round32(v_q16, 16);
    return (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
}

void tdc_pixfmt_ycbcr_to_rgb(uint8_t y, uint8_t cb, uint8_t cr, uint8_t rgb[3])
{
    const int32_t u = (int32_t)cb - 128, v = (int32_t)cr - 128;
    const int32_t yq = (int32_t)y * 65536;
    rgb[0] = tdc_q16_to_u8_sat(yq + TDC_YCC_CR_R_Q16 * v);
    rgb[1] = tdc_q16_to_u8_sat(yq - TDC_YCC_CB_G_Q16 * u - TDC_YCC_CR_G_Q16 * v);
    rgb[2] = tdc_q16_to_u8_sat(yq + TDC_YCC_CB_B_Q16 * u);
}

/* Y + offset clamped to [0, 255]; |offset| <= 240 so no overflow. */
static inline uint8_t tdc_u8_add_sat(int32_t y, int32_t off)
{
    const int32_t v = y + off;
    return (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
}

/*
 * Scaling: the Q16 sum Y * 2^16 + c * (C - 128) + 2^15 is a multiple of 2^16
 * plus the chroma term, so floor(sum / 2^16) = Y + floor((c * (C - 128) +
 * 2^15) / 2^16) exactly.  The chroma part is therefore reduced to one
 * integer offset per channel per chroma sample, shared by the (up to) four
 * pixels of its 2x2 block: bit-identical to tdc_pixfmt_ycbcr_to_rgb().
 */
void tdc_pixfmt_unpack_ycbcr420(const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride)
{
    const uint32_t cw = (w + 1u) / 2u, ch = (h + 1u) / 2u;
    const uint8_t *cb_plane = src + (size_t)w * h;
    const uint8_t *cr_plane = cb_plane + (size_t)cw * ch;
    for (uint32_t cy = 0; cy < ch; cy++) {
        const uint32_t y0 = 2u * cy;
        const uint32_t rows = y0 + 1u < h ? 2u : 1u;
        const uint8_t *cbs = cb_plane + (size_t)cw * cy;
        const uint8_t *crs = cr_plane + (size_t)cw * cy;
        for (uint32_t cx = 0; cx < cw; cx++) {
            const int32_t u = (int32_t)cbs[cx] - 128, v = (int32_t)crs[cx] - 128;
            const int32_t orr = tdc_mul_q16_32(TDC_YCC_CR_R_Q16, v);
            const int32_t og = tdc_rshr_round32(-TDC_YCC_CB_G_Q16 * u - TDC_YCC_CR_G_Q16 * v, 16);
            const int32_t ob = tdc_mul_q16_32(TDC_YCC_CB_B_Q16, u);
            const uint32_t x0 = 2u * cx;
            const uint32_t cols = x0 + 1u < w ? 2u : 1u;
            for (uint32_t r = 0; r < rows; r++) {
                const uint8_t *ys = src + (size_t)w * (y0 + r) + x0;
                uint8_t *p = dst + (size_t)dst_stride * (y0 + r) + 3u * x0;
                for (uint32_t k = 0; k < cols; k++) {
                    const int32_t yv = ys[k];
                    p[3u * k + 0u] = tdc_u8_add_sat(yv, orr);
                    p[3u * k + 1u] = tdc_u8_add_sat(yv, og);
                    p[3u * k + 2u] = tdc_u8_add_sat(yv, ob);
                }
            }
        }
    }
}

void tdc_pixfmt_unpack(tdc_pixfmt_t f, const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride)
{
    switch (f) {
    case TDC_PIXFMT_RGB888: tdc_pixfmt_unpack_rgb888(src, w, h, dst, dst_stride); break;
    case TDC_PIXFMT_RGB565: tdc_pixfmt_unpack_rgb565(src, w, h, dst, dst_stride); break;
    case TDC_PIXFMT_RGB30: tdc_pixfmt_unpack_rgb30(src, w, h, dst, dst_stride); break;
    case TDC_PIXFMT_YCBCR420: tdc_pixfmt_unpack_ycbcr420(src, w, h, dst, dst_stride); break;
    default: break;
    }
}
