/*
 * tdc_link_gen.h - deterministic synthetic link streams (stream header,
 * then per frame the packets a renderer would send for the stream flags:
 * full/reduced frames alternating per TRM, subframes with pattern bitmaps
 * at each 4-frame cycle, motion vectors).  Used by the tests, the fuzz seed
 * corpus, the golden vectors and the benchmark.  Integer only, no
 * allocation (the golden runner includes it on the boards).
 */
#ifndef TDC_LINK_GEN_H
#define TDC_LINK_GEN_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_link_encode.h"

typedef struct {
    uint16_t stream_id;
    tdc_link_stream_info_t info; /* flags, r, width, height, eyes */
    tdc_pixfmt_t fmt;            /* format of every pixel packet */
    uint32_t first_frame;
    uint32_t frames;
    uint32_t seed;
    int with_stream_header; /* 1: begin with the STREAM packet */
} tdc_link_gen_opts_t;

typedef struct {
    uint32_t offset; /* packet start in the stream */
    uint32_t size;   /* header + payload */
    uint8_t kind, eye;
    uint16_t flags;
    uint32_t frame;
} tdc_link_gen_packet_t;

/* Options of a plain stream: stream header first, r = 1 (no reduced
 * frames), no flags, frames from 0.  Callers change what they test. */
void tdc_link_gen_opts_plain(tdc_link_gen_opts_t *o, uint16_t stream_id, uint16_t w, uint16_t h, uint8_t eyes,
                             uint16_t refresh_hz, tdc_pixfmt_t fmt, uint32_t frames, uint32_t seed);

/* Scratch bytes tdc_link_gen_stream needs for a w x h eye (4-byte aligned:
 * it also holds int16 motion vectors). */
#define TDC_LINK_GEN_SCRATCH_BYTES(w, h) ((size_t)(w) * (h)*4u)

/* Source content the generator encodes: RGB888 of (frame, eye) at w x h
 * (stride w * 3), and motion vectors (Q4 pairs) for `count` vectors. */
void tdc_link_gen_rgb(uint8_t *rgb, uint32_t w, uint32_t h, uint32_t frame, uint32_t eye, uint32_t seed);
void tdc_link_gen_mv(int16_t *mv, size_t count, uint32_t frame, uint32_t eye, uint32_t seed);
void tdc_link_gen_pattern(uint8_t *bits, size_t nbytes, uint32_t tiles, uint32_t frame, uint32_t eye, uint32_t seed);

/* Writes the stream to out (cap bytes); returns its size or 0 if it does
 * not fit.  Packet table: up to pk_cap entries in pk (may be NULL),
 * *pk_count = number of packets written. */
size_t tdc_link_gen_stream(uint8_t *out, size_t cap, const tdc_link_gen_opts_t *o, uint8_t *scratch,
                           size_t scratch_bytes, tdc_link_gen_packet_t *pk, uint32_t pk_cap, uint32_t *pk_count);

#endif
