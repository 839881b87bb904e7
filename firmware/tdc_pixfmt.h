/*
 * tdc_pixfmt.h - link pixel formats and their unpacking to the pipeline's
 * RGB888 (docs/link-protocol.md §5).  Integer only, bit-exact on every
 * compiler and CPU.
 *
 * Formats (numbers are the wire values of the packet header `format` byte):
 *   TDC_PIXFMT_RGB888    3 bytes per pixel R, G, B.                 3 B/px
 *   TDC_PIXFMT_RGB565    uint16 LE: R bits 15..11, G 10..5, B 4..0. 2 B/px
 *                        Expanded to 8 bits by bit replication
 *                        (r8 = r5 << 3 | r5 >> 2, g8 = g6 << 2 | g6 >> 4).
 *   TDC_PIXFMT_RGB30     uint32 LE: R bits 9..0, G 19..10, B 29..20,
 *                        bits 31..30 zero.  To 8 bits: round(v * 255 / 1023)
 *                        = (v * 255 + 511) / 1023.                  4 B/px
 *   TDC_PIXFMT_YCBCR420  planar: Y plane w x h bytes, then Cb plane and Cr
 *                        plane of cw x ch bytes, cw = ceil(w/2), ch = ceil(h/2).
 *                        Chroma sample (i, j) covers luma pixels (2i..2i+1,
 *                        2j..2j+1) (partial at odd sizes); it is replicated
 *                        over them (nearest).  BT.709 full range:
 *                          R = Y + 1.5748 (Cr - 128)
 *                          G = Y - 0.187324 (Cb - 128) - 0.468124 (Cr - 128)
 *                          B = Y + 1.8556 (Cb - 128)
 *                        evaluated in Q16 with round half up and clamped to
 *                        [0, 255] (tdc_pixfmt_ycbcr_to_rgb).  ~1.5 B/px
 * Rows of every payload are packed (no padding).  The destination is RGB888
 * interleaved with `dst_stride` bytes between rows.
 */
#ifndef TDC_PIXFMT_H
#define TDC_PIXFMT_H

#include <stddef.h>
#include <stdint.h>

typedef enum {
    TDC_PIXFMT_NONE = 0, /* non-pixel packets (stream header, motion, pattern) */
    TDC_PIXFMT_RGB888 = 1,
    TDC_PIXFMT_RGB565 = 2,
    TDC_PIXFMT_RGB30 = 3,
    TDC_PIXFMT_YCBCR420 = 4,
    TDC_PIXFMT_COUNT
} tdc_pixfmt_t;

/* Q16 coefficients of the BT.709 full-range YCbCr -> RGB matrix:
 * round(c * 65536) of 2(1-Kr), 2 Kb(1-Kb)/Kg, 2 Kr(1-Kr)/Kg, 2(1-Kb)
 * with Kr = 0.2126, Kb = 0.0722, Kg = 0.7152. */
#define TDC_YCC_CR_R_Q16 103206 /* 1.5748    */
#define TDC_YCC_CB_G_Q16 12276  /* 0.1873243 */
#define TDC_YCC_CR_G_Q16 30679  /* 0.4681243 */
#define TDC_YCC_CB_B_Q16 121609 /* 1.8556    */

/* 1 if f is a pixel format a frame/subframe packet may carry. */
int tdc_pixfmt_valid(uint32_t f);

/* Payload bytes of a w x h image in format f; 0 for an invalid format.
 * w, h <= 65535 so the result fits in 32 bits for every format. */
uint32_t tdc_pixfmt_payload_bytes(tdc_pixfmt_t f, uint32_t w, uint32_t h);

/* Unpacks a w x h image in format f from src (exactly
 * tdc_pixfmt_payload_bytes(f, w, h) bytes) to RGB888 at dst. */
void tdc_pixfmt_unpack(tdc_pixfmt_t f, const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride);

void tdc_pixfmt_unpack_rgb888(const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride);
void tdc_pixfmt_unpack_rgb565(const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride);
void tdc_pixfmt_unpack_rgb30(const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride);
void tdc_pixfmt_unpack_ycbcr420(const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t dst_stride);

/* One YCbCr (full-range 8-bit) triple to RGB888, BT.709, Q16. */
void tdc_pixfmt_ycbcr_to_rgb(uint8_t y, uint8_t cb, uint8_t cr, uint8_t rgb[3]);

/* 10-bit -> 8-bit code, round(v * 255 / 1023), v in [0, 1023]. */
static inline uint8_t tdc_pixfmt_u10_to_u8(uint32_t v)
{
    return (uint8_t)((v * 255u + 511u) / 1023u);
}

/* The row walk of every per-pixel converter of the packed formats (the
 * encoder's packers, the decoder's unpackers): h rows of w pixels, source
 * row y at in + in_row * y with IN_PX bytes a pixel, destination row y at
 * out + out_row * y with OUT_PX bytes a pixel; PIXEL(s, d) converts one.
 * A macro, so each format's loop is compiled with its pixel code inline. */
#define TDC_PIXFMT_ROWS(in, in_row, IN_PX, out, out_row, OUT_PX, w, h, PIXEL)                                          \
    do {                                                                                                               \
        for (uint32_t rows_y_ = 0; rows_y_ < (h); rows_y_++) {                                                         \
            const uint8_t *rows_s_ = (in) + (size_t)(in_row) * rows_y_;                                                \
            uint8_t *rows_d_ = (out) + (size_t)(out_row) * rows_y_;                                                    \
            for (uint32_t rows_x_ = 0; rows_x_ < (w); rows_x_++) {                                                     \
                PIXEL(rows_s_ + (IN_PX) * rows_x_, rows_d_ + (OUT_PX) * rows_x_);                                      \
            }                                                                                                          \
        }                                                                                                              \
    } while (0)

#endif /* TDC_PIXFMT_H */
