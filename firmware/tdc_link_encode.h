/*
 * tdc_link_encode.h - link encoder (docs/link-protocol.md), the sending side
 * beside the decoder (tdc_link.h): turns frames, reduced frames, subframes,
 * motion vectors and tile-pattern bitmaps into link packets the decoder
 * accepts.  Used by the renderer, the simulator, hosttools and tests;
 * header and STREAM bytes are written by tdc_wire.h's packers.
 *
 * Integer only and allocation-free (the caller owns the output buffer): it
 * lives in firmware/ so the golden-vector and bench runners have it on the
 * ARM boards too (a board image that does not call it does not link it).  Every function
 * writes one complete packet (header + payload) to out[0 .. cap) and returns
 * its size in bytes, or 0 if cap is too small or an argument is invalid.
 * tdc_link_packet_bytes() (tdc_wire.h) tells the size in advance.
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

void tdc_link_encoder_init(tdc_link_encoder_t *enc, uint16_t stream_id, const tdc_link_stream_info_t *info);

/* Raw packet: header fields (payload_len and payload_crc are replaced) + an
 * already formatted payload (any length). */
size_t tdc_link_encode_raw(uint8_t *out, size_t cap, const tdc_link_header_t *f, const uint8_t *payload,
                           uint32_t payload_len);

/* STREAM packet from the encoder's stream info (frame index 0). */
size_t tdc_link_encode_stream(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap);

/* FULL or REDUCED frame: w x h RGB888 source (rows `stride` bytes apart)
 * packed into `fmt`.  For REDUCED, w x h is the reduced size. */
size_t tdc_link_encode_frame(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, tdc_link_kind_t kind,
                             uint32_t eye, uint32_t frame, tdc_pixfmt_t fmt, const uint8_t *rgb, uint32_t w, uint32_t h,
                             uint32_t stride);

/* One row band (tdc_band_link.h) of a FULL or REDUCED picture: band
 * `index` of the w x h RGB888 picture rgb (rows `stride` apart; the whole
 * picture, the band's rows are taken from it) in bands of band_rows, packed
 * into fmt, with packet flag TDC_LINK_PKT_BAND.  0 for an invalid band
 * geometry (tdc_band_hdr_pack) or a short cap. */
size_t tdc_link_encode_band(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, tdc_link_kind_t kind,
                            uint32_t eye, uint32_t frame, tdc_pixfmt_t fmt, const uint8_t *rgb, uint32_t w, uint32_t h,
                            uint32_t stride, uint32_t band_rows, uint32_t index);

/* SUBFRAME: tiles_x x tiles_y RGB888 samples (packed, row-major) of a
 * w x h eye (header dimensions are w x h, the full-resolution size). */
size_t tdc_link_encode_subframe(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                                tdc_pixfmt_t fmt, const uint8_t *samples, uint32_t w, uint32_t h);

/* MOTION: per_sample = 0: w x h (dx, dy) Q4 pairs; per_sample = 1: one pair
 * per subframe sample (tiles_x x tiles_y).  Header dimensions are w x h. */
size_t tdc_link_encode_motion(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                              const int16_t *mv, uint32_t w, uint32_t h, int per_sample);

/* PATTERN: tile bitmap (TDC_PATTERN_BYTES(w, h) bytes) of a w x h eye. */
size_t tdc_link_encode_pattern(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                               const uint8_t *bits, uint32_t w, uint32_t h);

/* LAYERS (tdc_layer_link.h): the planes of src for the layer set `flags`
 * (TDC_LAYER_PKT_*), vector kind mv_kind[t - 1] of each present type t, of a
 * w x h eye.  0 if src lacks a plane the flags name or a kind is invalid.
 * Values are sent as they are (a sentinel vector or a weight above 1 goes
 * out and is refused by the decoder: tests use that). */
size_t tdc_link_encode_layers(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                              const tdc_layer_frame_t *src, uint32_t flags, const uint8_t mv_kind[TDC_LAYER_MAX],
                              uint32_t w, uint32_t h);

/* FOVEATED: the foveation header of p (delta_q15, TDC_FOV_FLAG_MV if mv)
 * for the encoder's w x h eye, then the samples in payload order
 * (tdc_fov_link.h: samples = the lp samples of columns [u0, lp_w), rows
 * j = 0..lp_h-1, then the disk pixels row by row, RGB888 packed; mv = one
 * (dx, dy) Q4 pair per lp sample or NULL).  0 if p is refused by
 * tdc_fov_hdr_pack or cap is too small; *g (if not NULL) gets the geometry. */
size_t tdc_link_encode_foveated(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, uint32_t eye, uint32_t frame,
                                const tdc_fov_params_t *p, uint16_t delta_q15, const uint8_t *samples,
                                const int16_t *mv, tdc_fov_geom_t *g);
/* The same for a slot of the stream: TDC_LINK_KIND_FULL (the call above)
 * or TDC_LINK_KIND_REDUCED, the reduced frame of a TRM stream foveated: p
 * and the samples on the rW x rH grid of the encoder's ratio (rW =
 * TDC_REDUCED_DIM(W, r_num, r_den)), packet width x height rW x rH and
 * flag TDC_LINK_PKT_FOV_REDUCED (docs/link-protocol.md §2.2).  The encoder
 * does not check the stream's flags (tests send refused packets with it);
 * 0 for another slot, r_den 0, or as above. */
size_t tdc_link_encode_foveated_slot(const tdc_link_encoder_t *enc, uint8_t *out, size_t cap, tdc_link_kind_t slot,
                                     uint32_t eye, uint32_t frame, const tdc_fov_params_t *p, uint16_t delta_q15,
                                     const uint8_t *samples, const int16_t *mv, tdc_fov_geom_t *g);

/* Pixel packing from RGB888 (the inverse of firmware/tdc_pixfmt.c). */
void tdc_pixfmt_pack(tdc_pixfmt_t fmt, const uint8_t *rgb, uint32_t w, uint32_t h, uint32_t stride, uint8_t *out);
/* RGB888 -> BT.709 full-range YCbCr in Q16 integer arithmetic (chroma from
 * the mean of each 2x2 block, rounded). */
void tdc_pixfmt_rgb_to_ycbcr(int32_t r, int32_t g, int32_t b, uint8_t ycc[3]);

#endif /* TDC_LINK_ENCODE_H */
