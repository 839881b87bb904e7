/*
 * tdc_band_link.h - frames as row bands (docs/link-protocol.md §2.3, issue
 * 17 item 2): a FULL or REDUCED picture sent as a run of packets, each a
 * band of rows with its own payload CRC, so the controller stages one band,
 * not a frame, and its stages can start on the first rows while the rest
 * are still on the wire.
 *
 * A stream announces bands with stream flag TDC_LINK_STREAM_BANDS; every
 * FULL and REDUCED packet of it then carries packet flag TDC_LINK_PKT_BAND,
 * width x height = the whole picture (the panel's, or the reduced size), and
 * a payload of the 16-byte band header followed by the band's rows in the
 * packet's pixel format (tdc_pixfmt_payload_bytes(fmt, width, rows): a
 * YCbCr 4:2:0 band carries its own Y, Cb and Cr planes):
 *
 *    0  uint8  layout version, 1
 *    1  uint8  reserved, 0
 *    2  uint16 band index i, 0 .. count-1, sent in order
 *    4  uint16 band count n = ceil(height / band_rows)
 *    6  uint16 band_rows B >= 1: rows of every band but the last
 *              (even when n > 1 for YCbCr 4:2:0: chroma rows stay whole)
 *    8  uint16 first row = i * B
 *   10  uint16 rows = min(B, height - i * B)
 *   12  uint32 reserved, 0
 *
 * The decoder (tdc_link.c) writes each validated band straight into its
 * place in the picture's buffer (full[eye] rows or reduced[eye] rows) and
 * completes the picture's (kind, eye) slot on the last band.  Per eye one
 * picture is in flight (tdc_band_seq_t); its bands must come in order.
 *
 * Refusals (TDC_LINK_ERR_BAND, reason in the event's detail and in
 * counters.band_errors[]): the band is not written.  A picture with a
 * refused or lost band is dropped whole (TDC_LINK_ERR_BAND_DROPPED, reason
 * tdc_band_drop_t in detail and in counters.band_drops[]): later bands of it
 * are refused as DROPPED, its slot never completes, the frame loop keeps
 * the eye's last good image and never swaps it in.
 */
#ifndef TDC_BAND_LINK_H
#define TDC_BAND_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_pixfmt.h"

#define TDC_BAND_HDR_BYTES 16u
#define TDC_BAND_LAYOUT_VERSION 1u

/* Why a band was refused (a counter index: 0 = accepted). */
typedef enum {
    TDC_BAND_OK = 0,
    TDC_BAND_ERR_HEADER,   /* layout version not 1, or a reserved field not 0 */
    TDC_BAND_ERR_GEOMETRY, /* band_rows 0 (or odd for a multi-band YCbCr picture), count not ceil(height / band_rows),
                              index >= count, first row / rows not the index's, payload length not the band's */
    TDC_BAND_ERR_ORDER,    /* not the next band of its picture: repeated, skipped or backwards */
    TDC_BAND_ERR_FRAME,    /* a band after the first of a picture not in flight (another frame or kind) */
    TDC_BAND_ERR_SIZE,     /* band rows, count or pixel format differ from the picture's first band: the frame
                              changed size mid-stream */
    TDC_BAND_ERR_DROPPED,  /* a band of a picture already dropped */
    TDC_BAND_ERR_N
} tdc_band_err_t;

/* Why a picture was dropped whole (a counter index: 0 unused). */
typedef enum {
    TDC_BAND_DROP_NONE = 0,
    TDC_BAND_DROP_CRC,     /* one of its bands failed the payload CRC */
    TDC_BAND_DROP_REFUSED, /* one of its bands was refused (a band reason, or a link check such as ORDER) */
    TDC_BAND_DROP_MISSING, /* its last band never came: the next picture of the eye (or a new stream) started */
    TDC_BAND_DROP_N
} tdc_band_drop_t;

/* The band header. */
typedef struct {
    uint8_t version;
    uint8_t reserved;
    uint16_t index;
    uint16_t count;
    uint16_t band_rows;
    uint16_t first_row;
    uint16_t rows;
    uint32_t reserved2;
} tdc_band_hdr_t;

/* Bands of a picture height rows high in bands of band_rows (0 if 0). */
static inline uint32_t tdc_band_count(uint32_t height, uint32_t band_rows)
{
    return band_rows ? (height + band_rows - 1u) / band_rows : 0u;
}

/* Payload bytes of a band of `rows` rows of a width-pixel picture in fmt
 * (0 for an invalid format).  Scaling: <= 16 + 4 * width * rows, below 2^32
 * for pictures of the panel's size. */
static inline uint32_t tdc_band_payload_bytes(tdc_pixfmt_t fmt, uint32_t width, uint32_t rows)
{
    const uint32_t n = tdc_pixfmt_payload_bytes(fmt, width, rows);
    return n ? TDC_BAND_HDR_BYTES + n : 0u;
}

/* Writes the header of band `index` of a picture `height` rows high cut in
 * bands of band_rows.  Returns 0, or -1 if index or band_rows are invalid
 * for that height and format (tdc_band_hdr_parse's geometry rules). */
int tdc_band_hdr_pack(uint8_t out[TDC_BAND_HDR_BYTES], uint32_t index, uint32_t band_rows, uint32_t height,
                      tdc_pixfmt_t fmt);

/* Parses a band header of a packet of format fmt and width x height with
 * payload_len bytes: TDC_BAND_OK when the header is well formed and its
 * geometry and the payload length are the band's.  Reads only. */
tdc_band_err_t tdc_band_hdr_parse(const uint8_t *in, tdc_pixfmt_t fmt, uint32_t width, uint32_t height,
                                  uint32_t payload_len, tdc_band_hdr_t *h);

/* One eye's picture in flight. */
enum { TDC_BAND_IDLE = 0, TDC_BAND_OPEN = 1, TDC_BAND_DEAD = 2 };
typedef struct {
    uint8_t state;  /* TDC_BAND_IDLE / OPEN (bands arriving) / DEAD (dropped: its bands refused) */
    uint8_t kind;   /* tdc_link_kind_t of the picture */
    uint8_t format; /* tdc_pixfmt_t of its first band */
    uint8_t reserved;
    uint16_t count, band_rows;
    uint16_t next; /* index of the band due */
    uint16_t pad;
    uint32_t frame; /* frame index of the picture */
} tdc_band_seq_t;

/* Whether band h of picture (kind, frame) in format fmt may be taken now,
 * given the eye's picture in flight s: index 0 starts a picture (unless it
 * is a repeat of the one in flight: ORDER), a later index must continue the
 * open picture in order with its geometry.  Reads only. */
tdc_band_err_t tdc_band_seq_check(const tdc_band_seq_t *s, uint32_t kind, uint32_t frame, uint32_t fmt,
                                  const tdc_band_hdr_t *h);

/* Records an accepted band (seq_check said OK).  Returns 1 if it was the
 * picture's last band (the picture is complete; s is idle again). */
int tdc_band_seq_accept(tdc_band_seq_t *s, uint32_t kind, uint32_t frame, uint32_t fmt, const tdc_band_hdr_t *h);

/* 1 if a picture (kind, frame) is in flight (open or dead) in s. */
static inline int tdc_band_seq_is(const tdc_band_seq_t *s, uint32_t kind, uint32_t frame)
{
    return s->state != TDC_BAND_IDLE && s->kind == kind && s->frame == frame;
}

/* "TDC_BAND_ERR_ORDER"; "TDC_BAND_ERR_?" outside the enum. */
const char *tdc_band_err_name(tdc_band_err_t e);
/* "TDC_BAND_DROP_CRC"; "TDC_BAND_DROP_?" outside the enum. */
const char *tdc_band_drop_name(tdc_band_drop_t d);

#endif /* TDC_BAND_LINK_H */
