/*
 * tdc_link_encode.h - host-side link encoder (docs/link-protocol.md): turns
 * frames, reduced frames, subframes, motion vectors and tile-pattern bitmaps
 * into link packets the firmware decoder (firmware/tdc_link.h) accepts.
 * Used by the renderer, the simulator and hosttools.
 *
 * Integer only and allocation-free (the caller owns the output buffer), so
 * the golden-vector runner can use it on the ARM boards too.  Every function
 * writes one complete packet (header + payload) to out[0 .. cap) and returns
 * its size in bytes, or 0 if cap is too small or an argument is invalid.
 * tdc_link_packet_bytes() tells the size in advance.
 *
 *     tdc_link_encoder_t enc;
 *     tdc_link_encoder_init(&enc, stream_id, &info);       // info: flags, r, size, eyes
 *     n = tdc_link_encode_stream(&enc, buf, cap);          // first packet of a stream
 *     n = tdc_link_encode_frame(&enc, buf, cap, TDC_LINK_KIND_FULL, eye, frame,
 *                               TDC_PIXFMT_YCBCR420, rgb, w, h, stride);
 */
#ifndef TDC_LINK_ENCODE_H
#define TDC_LINK_ENCODE_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_link.h"

typedef struct {
    uint16_t stream_id;
    tdc_link_stream_info_t info;
} tdc_link_encoder_t;

/* Header fields of one packet (payload_len/CRCs are filled in by the encoder). */
typedef struct {
    uint8_t version; /* TDC_LINK_VERSION */
    uint8_t kind;
    uint8_t eye;
    uint8_t format;
    uint16_t stream_id;
    uint16_t flags;
    uint32_t frame_index;
    uint16_t width;
    uint16_t height;
} tdc_link_header_fields_t;

void tdc_link_encoder_init(tdc_link_encoder_t *enc, uint16_t stream_id, const tdc_link_stream_info_t *info);

/* Total packet bytes (header + payload) for these fields, 0 if invalid. */
size_t tdc_link_packet_bytes(tdc_link_kind_t kind, tdc_pixfmt_t fmt, uint32_t width, uint32_t height,
                             uint32_t pkt_flags);

/* Writes a 32-byte header for `f` with the given payload length and CRC. */
void tdc_link_write_header(uint8_t *out, const tdc_link_header_fields_t *f, uint32_t payload_len,
                           uint32_t payload_crc);

/* Parses a header (no validation besides reading fields); returns 1 if the
 * magic and header CRC are right. */
int tdc_link_parse_header(const uint8_t *hdr, tdc_link_header_fields_t *f, uint32_t *payload_len,
                          uint32_t *payload_crc);

/* Raw packet: header fields + an already formatted payload (any length). */
size_t tdc_link_encode_raw(uint8_t *out, size_t cap, const tdc_link_header_fields_t *f, const uint8_t *payload,
                           uint32_t payload_len);

/* STREAM packet from the encoder's stream info (frame index 0). */
size_t tdc_link_encode_stream(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap);

/* FULL or REDUCED frame: w x h RGB888 source (rows `stride` bytes apart)
 * packed into `fmt`.  For REDUCED, w x h is the reduced size. */
size_t tdc_link_encode_frame(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, tdc_link_kind_t kind,
                             uint32_t eye, uint32_t frame, tdc_pixfmt_t fmt, const uint8_t *rgb, uint32_t w,
                             uint32_t h, uint32_t stride);

/* SUBFRAME: tiles_x x tiles_y RGB888 samples (packed, row-major) of a
 * w x h eye (header dimensions are w x h, the full-resolution size). */
size_t tdc_link_encode_subframe(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye,
                                uint32_t frame, tdc_pixfmt_t fmt, const uint8_t *samples, uint32_t w, uint32_t h);

/* MOTION: per_sample = 0: w x h (dx, dy) Q4 pairs; per_sample = 1: one pair
 * per subframe sample (tiles_x x tiles_y).  Header dimensions are w x h. */
size_t tdc_link_encode_motion(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye,
                              uint32_t frame, const int16_t *mv, uint32_t w, uint32_t h, int per_sample);

/* PATTERN: tile bitmap (TDC_LINK_PATTERN_BYTES(w, h) bytes) of a w x h eye. */
size_t tdc_link_encode_pattern(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye,
                               uint32_t frame, const uint8_t *bits, uint32_t w, uint32_t h);

/* Pixel packing from RGB888 (the inverse of firmware/tdc_pixfmt.c). */
void tdc_pixfmt_pack(tdc_pixfmt_t fmt, const uint8_t *rgb, uint32_t w, uint32_t h, uint32_t stride, uint8_t *out);
/* RGB888 -> BT.709 full-range YCbCr in Q16 integer arithmetic (chroma from
 * the mean of each 2x2 block, rounded). */
void tdc_pixfmt_rgb_to_ycbcr(int32_t r, int32_t g, int32_t b, uint8_t ycc[3]);

#endif /* TDC_LINK_ENCODE_H */
