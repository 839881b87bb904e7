/*
 * tdc_wire.h - the one place the bytes on the wire are defined
 * (docs/link-protocol.md, docs/usb-protocol.md).  Integer only, no heap, no
 * state: used by the firmware's link decoder and USB protocol and by every
 * host program that writes or reads link packets (encoder, .tdcs files,
 * simulator link accounting, fuzzer, tdc-usb).
 *
 *   1. Little-endian load/store of 16/32-bit fields: tdc_bytes.h, below
 *      this header (the payload formats use them without the packet layer).
 *   2. The 32-byte link packet header: offsets, tdc_link_header_t and its
 *      pack/unpack (the only code that reads or writes header bytes).
 *   3. The STREAM payload (16 bytes): offsets, pack/unpack.
 *   4. Packet kinds: a table with each kind's name and payload-size rule,
 *      payload and packet sizes, buffer sizes for a panel.
 *   5. The decoder's rejection reasons (tdc_link_err_t), which also name
 *      what header unpacking found.
 *
 * Adding a packet kind (e.g. layered subframes): a value in
 * tdc_link_kind_t, a row in the kind table of tdc_wire.c (name, payload
 * rule, grid), and its accept/unpack case in the decoder.
 */
#ifndef TDC_WIRE_H
#define TDC_WIRE_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_bytes.h"
#include "tdc_geom.h"
#include "tdc_pixfmt.h"

/* ------------------------------------------------------------------------
 * 2. Link packet header: 32 bytes, little-endian, naturally aligned fields.
 * ---------------------------------------------------------------------- */
#define TDC_LINK_MAGIC 0x4C434454u /* bytes 'T' 'D' 'C' 'L' read as uint32 LE */
#define TDC_LINK_VERSION 1u
#define TDC_LINK_HEADER_BYTES 32u

#define TDC_LINK_OFF_MAGIC 0u        /* uint32 */
#define TDC_LINK_OFF_VERSION 4u      /* uint8 */
#define TDC_LINK_OFF_KIND 5u         /* uint8  tdc_link_kind_t */
#define TDC_LINK_OFF_EYE 6u          /* uint8  0 = left / mono, 1 = right */
#define TDC_LINK_OFF_FORMAT 7u       /* uint8  tdc_pixfmt_t, 0 for non-pixel kinds */
#define TDC_LINK_OFF_STREAM_ID 8u    /* uint16 */
#define TDC_LINK_OFF_FLAGS 10u       /* uint16 TDC_LINK_PKT_* */
#define TDC_LINK_OFF_FRAME 12u       /* uint32 frame index */
#define TDC_LINK_OFF_WIDTH 16u       /* uint16 */
#define TDC_LINK_OFF_HEIGHT 18u      /* uint16 */
#define TDC_LINK_OFF_PAYLOAD_LEN 20u /* uint32 */
#define TDC_LINK_OFF_PAYLOAD_CRC 24u /* uint32 CRC-32 of the payload */
#define TDC_LINK_OFF_HEADER_CRC 28u  /* uint32 CRC-32 of header bytes 0..27 */

typedef enum {
    TDC_LINK_KIND_STREAM = 1,   /* stream header / reset: starts a stream (payload 16 B) */
    TDC_LINK_KIND_FULL = 2,     /* full-resolution frame of one eye */
    TDC_LINK_KIND_REDUCED = 3,  /* reduced-resolution frame (TRM, ratio r) */
    TDC_LINK_KIND_SUBFRAME = 4, /* one sample per 2x2 tile (tile-ordered assembly) */
    TDC_LINK_KIND_MOTION = 5,   /* motion vectors, int16 (dx, dy) Q4 pairs */
    TDC_LINK_KIND_PATTERN = 6,  /* tile-ordering bitmap, 1 bit per tile */
    TDC_LINK_KIND_FOVEATED = 7, /* kernel log-polar buffer + foveal disk (tdc_fov_link.h) */
    TDC_LINK_KIND_LAYERS = 8, /* layered subframe: per-sample layers + own vectors (tdc_layer_link.h) */
    TDC_LINK_KIND_FIRST = TDC_LINK_KIND_STREAM,
    TDC_LINK_KIND_LAST = TDC_LINK_KIND_LAYERS
} tdc_link_kind_t;

/* Per-packet flags (header `flags`). */
#define TDC_LINK_PKT_MV_PER_SAMPLE 0x0001u /* MOTION: one vector per subframe sample (tile grid) */
#define TDC_LINK_PKT_BAND 0x0002u          /* FULL/REDUCED: one row band of the picture (tdc_band_link.h) */
#define TDC_LINK_PKT_FOV_REDUCED 0x0004u   /* FOVEATED: fills the eye's REDUCED slot of a TRM stream (rW x rH grid) */
#define TDC_LINK_PKT_KNOWN 0x0007u

/* Every header field; magic and header CRC are implied (pack writes them,
 * unpack checks them). */
typedef struct {
    uint8_t version; /* TDC_LINK_VERSION */
    uint8_t kind;    /* tdc_link_kind_t */
    uint8_t eye;
    uint8_t format; /* tdc_pixfmt_t */
    uint16_t stream_id;
    uint16_t flags; /* TDC_LINK_PKT_* */
    uint32_t frame_index;
    uint16_t width; /* dimensions of the packet (REDUCED: the reduced size) */
    uint16_t height;
    uint32_t payload_len;
    uint32_t payload_crc;
} tdc_link_header_t;

/* ------------------------------------------------------------------------
 * Rejection reasons of the link decoder (tdc_link.h), one counter each.
 * Header unpacking reports the first two it can see (magic, header CRC).
 * Not a tdc_status_t: a dense counter index carried in decoder events.
 * ---------------------------------------------------------------------- */
typedef enum {
    TDC_LINK_OK = 0,
    TDC_LINK_ERR_MAGIC = 1,            /* sync lost: a packet boundary does not start with the magic */
    TDC_LINK_ERR_GARBAGE = 2,          /* bytes between packets discarded while resynchronising */
    TDC_LINK_ERR_HEADER_CRC = 3,       /* header CRC mismatch (corrupt header or false magic) */
    TDC_LINK_ERR_VERSION = 4,          /* unsupported protocol version */
    TDC_LINK_ERR_KIND = 5,             /* unknown packet kind */
    TDC_LINK_ERR_EYE = 6,              /* eye index >= the panel's eyes */
    TDC_LINK_ERR_FORMAT = 7,           /* unknown/unsupported pixel format or packet flags */
    TDC_LINK_ERR_DIMENSIONS = 8,       /* dimensions do not match the panel (or reduced size) */
    TDC_LINK_ERR_LENGTH = 9,           /* payload length inconsistent with kind/format/size */
    TDC_LINK_ERR_CRC = 10,             /* payload CRC mismatch */
    TDC_LINK_ERR_STREAM = 11,          /* no stream header yet, or a different stream id */
    TDC_LINK_ERR_ORDER = 12,           /* frame index lower than the current frame */
    TDC_LINK_ERR_DUPLICATE = 13,       /* same frame index, kind and eye accepted already */
    TDC_LINK_ERR_MISSING_REDUCED = 14, /* a frame whose reduced eye never arrived was passed */
    TDC_LINK_ERR_UNEXPECTED = 15,      /* kind not enabled by the stream header / not due now */
    TDC_LINK_ERR_STREAM_HEADER = 16,   /* stream header contents invalid (flags, r, size) */
    TDC_LINK_ERR_LAYERS = 17,          /* layered payload refused (reason: tdc_layer_err_t, counted apart) */
    TDC_LINK_ERR_FOVEATION = 18,       /* foveation header refused (reason: counters' fov_refused) */
    TDC_LINK_ERR_BAND = 19,            /* row band refused (reason: tdc_band_err_t in detail, counters' band_errors) */
    TDC_LINK_ERR_BAND_DROPPED = 20,    /* a banded picture dropped whole (reason: tdc_band_drop_t, band_drops) */
    TDC_LINK_ERR_COUNT = 21
} tdc_link_err_t;

/* Short name of an error code ("crc", "magic", ...; "?" if out of range). */
const char *tdc_link_err_name(tdc_link_err_t e);

/* Writes the 32 header bytes of h to out: magic, every field of h, and the
 * header CRC over bytes 0..27. */
void tdc_link_header_pack(uint8_t out[TDC_LINK_HEADER_BYTES], const tdc_link_header_t *h);

/* Reads the 32 header bytes at in into *h (every field, always: a caller
 * may look at a damaged header) and checks them: TDC_LINK_OK,
 * TDC_LINK_ERR_MAGIC, or TDC_LINK_ERR_HEADER_CRC.  Nothing else is
 * validated here (version, kind, sizes: the decoder's job). */
tdc_link_err_t tdc_link_header_unpack(const uint8_t in[TDC_LINK_HEADER_BYTES], tdc_link_header_t *h);

/* ------------------------------------------------------------------------
 * 3. STREAM payload: which stages the stream uses, 16 bytes LE.
 * ---------------------------------------------------------------------- */
#define TDC_LINK_STREAM_HEADER_BYTES 16u

#define TDC_LINK_STREAM_OFF_FLAGS 0u     /* uint32 TDC_LINK_STREAM_* */
#define TDC_LINK_STREAM_OFF_R_NUM 4u     /* uint16 */
#define TDC_LINK_STREAM_OFF_R_DEN 6u     /* uint16 */
#define TDC_LINK_STREAM_OFF_WIDTH 8u     /* uint16 */
#define TDC_LINK_STREAM_OFF_HEIGHT 10u   /* uint16 */
#define TDC_LINK_STREAM_OFF_EYES 12u     /* uint8 */
#define TDC_LINK_STREAM_OFF_RESERVED 13u /* uint8, 0 */
#define TDC_LINK_STREAM_OFF_REFRESH 14u  /* uint16 Hz */

/* Stream header flags: which stages the stream uses, so the controller can
 * skip the others. */
#define TDC_LINK_STREAM_REDUCED 0x0001u   /* TRM: reduced frames alternate with full ones */
#define TDC_LINK_STREAM_SUBFRAMES 0x0002u /* tile-ordered subframes (+ pattern bitmaps) */
#define TDC_LINK_STREAM_MOTION 0x0004u    /* per-pixel motion vectors are sent */
#define TDC_LINK_STREAM_MIRRORS 0x0008u   /* motion vectors include mirror reflections */
#define TDC_LINK_STREAM_SAMPLE_MV 0x0010u /* subframe samples carry their own motion vectors */
#define TDC_LINK_STREAM_LAYERS 0x0020u    /* layered subframes (LAYERS packets; needs SUBFRAMES) */
#define TDC_LINK_STREAM_FOVEATED 0x0040u  /* FOVEATED packets (kernel log-polar + disk) may replace FULL ones */
#define TDC_LINK_STREAM_BANDS 0x0080u     /* FULL and REDUCED pictures come as row bands (tdc_band_link.h) */
#define TDC_LINK_STREAM_LAYER_HIST 0x0100u /* layered: exponential history per layer (tdc_layers.h; needs LAYERS) */
#define TDC_LINK_STREAM_KNOWN 0x01FFu

/* Motion vectors: Q4 (1/16 px), range +-2047.9375 px, BACKWARD (the point
 * now at p was at p + mv in the previous frame). */
#define TDC_LINK_MV_FRAC_BITS 4

typedef struct {
    uint32_t flags; /* TDC_LINK_STREAM_* */
    uint16_t r_num; /* TRM ratio r = r_num / r_den; 1/4 <= r < 1 if REDUCED, */
    uint16_t r_den; /* else r = 1 (1/1) */
    uint16_t width; /* full-resolution size of one eye: must match the panel */
    uint16_t height;
    uint8_t eyes;        /* 1 or 2: must match the panel */
    uint8_t reserved;    /* 0 */
    uint16_t refresh_hz; /* rate the renderer sends frames at (informative) */
} tdc_link_stream_info_t;

void tdc_link_stream_pack(uint8_t out[TDC_LINK_STREAM_HEADER_BYTES], const tdc_link_stream_info_t *s);
void tdc_link_stream_unpack(const uint8_t in[TDC_LINK_STREAM_HEADER_BYTES], tdc_link_stream_info_t *s);

/* ------------------------------------------------------------------------
 * 4. Kinds and sizes.
 * ---------------------------------------------------------------------- */

/* Geometry (reduced size TDC_REDUCED_DIM, tiles TDC_TILES, pattern bytes
 * TDC_PATTERN_BYTES): tdc_geom.h. */

/* How a kind's payload length follows from the header (format, w x h,
 * flags): `rule` over the elements of `grid`. */
typedef enum {
    TDC_LINK_PAYLOAD_FIXED = 0,    /* always `unit` bytes */
    TDC_LINK_PAYLOAD_PIXELS = 1,   /* an image of the grid in the packet's pixel format */
    TDC_LINK_PAYLOAD_PER_ELEM = 2, /* `unit` bytes per grid element */
    TDC_LINK_PAYLOAD_BITS = 3,     /* 1 bit per grid element, rounded up to bytes */
    TDC_LINK_PAYLOAD_LAYERS = 4,   /* layered: from the packet flags (tdc_layer_payload_bytes) */
    TDC_LINK_PAYLOAD_STATED = 5    /* stated by a kind header at the payload's start (FOVEATED:
                                      tdc_fov_link.h), checked after the payload CRC;
                                      tdc_link_payload_bytes() returns 0 */
} tdc_link_payload_rule_t;

typedef enum {
    TDC_LINK_GRID_NONE = 0,   /* FIXED payloads */
    TDC_LINK_GRID_PIXELS = 1, /* w x h of the header */
    TDC_LINK_GRID_TILES = 2,  /* ceil(w/2) x ceil(h/2): one element per 2x2 tile */
    TDC_LINK_GRID_MV = 3      /* TILES with TDC_LINK_PKT_MV_PER_SAMPLE, else PIXELS */
} tdc_link_grid_t;

typedef struct {
    const char *name;  /* "stream", "full", ... (tools, logs) */
    uint8_t rule;      /* tdc_link_payload_rule_t */
    uint8_t grid;      /* tdc_link_grid_t */
    uint8_t unit;      /* FIXED: payload bytes; PER_ELEM: bytes per element */
    uint8_t pkt_flags; /* TDC_LINK_PKT_* a packet of this kind may carry */
} tdc_link_kind_info_t;

/* The row of a kind, NULL for an unknown kind. */
const tdc_link_kind_info_t *tdc_link_kind_info(uint32_t kind);
/* Its name, "?" for an unknown kind. */
const char *tdc_link_kind_name(uint32_t kind);

/* Expected payload bytes of a packet (0 if the kind is unknown or the
 * format invalid for a pixel kind).  The products stay below 2^32 only for
 * w * h < 2^30: the decoder compares dimensions with the panel first, the
 * encoder uses tdc_link_packet_bytes(). */
uint32_t tdc_link_payload_bytes(tdc_link_kind_t kind, tdc_pixfmt_t fmt, uint32_t width, uint32_t height,
                                uint32_t pkt_flags);

/* Total packet bytes (header + payload), 0 if invalid or beyond 2^28
 * pixels (so a 4 B/px payload cannot wrap 32 bits). */
size_t tdc_link_packet_bytes(tdc_link_kind_t kind, tdc_pixfmt_t fmt, uint32_t width, uint32_t height,
                             uint32_t pkt_flags);

/* Pipeline buffer sizes for a w x h eye, one per kind (PATTERN:
 * TDC_PATTERN_BYTES of tdc_geom.h). */
#define TDC_LINK_FRAME_BYTES(w, h) ((size_t)(w) * (h)*3u) /* RGB888 */
#define TDC_LINK_SUBFRAME_BYTES(w, h) (TDC_TILE_COUNT(w, h) * 3u)
#define TDC_LINK_MOTION_COUNT(w, h) ((size_t)(w) * (h)*2u) /* int16s */
#define TDC_LINK_SAMPLE_MOTION_COUNT(w, h) (TDC_TILE_COUNT(w, h) * 2u)

#endif /* TDC_WIRE_H */
