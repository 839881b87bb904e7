/*
 * tdc_link.h - link protocol (docs/link-protocol.md) and the display-side
 * streaming decoder.
 *
 * The renderer sends packets: a 32-byte header (magic, version, kind, eye,
 * pixel format, stream id, flags, frame index, dimensions, payload length,
 * payload CRC-32, header CRC-32; little-endian) followed by the payload.
 * The decoder accepts the byte stream in chunks of any size (as USB bulk
 * transfers deliver it), allocates nothing, and validates a packet
 * completely (header CRC, header fields against the panel and the stream,
 * sequence, payload CRC) before it writes a single byte of frame state: the
 * payload is collected in a caller-owned staging buffer and unpacked into the
 * pipeline's buffers only after its CRC matched.  A rejected packet leaves
 * every pipeline buffer untouched (the panel keeps the last good frame), is
 * reported as an error event with its own code, counted, and the decoder
 * resynchronises on the next valid packet.
 *
 * Board main loop:
 *     static tdc_link_decoder_t dec;
 *     tdc_link_decoder_init(&dec, &cfg, &buffers);
 *     while (n) {                       // n bytes from USB at p
 *         tdc_link_event_t ev;
 *         size_t used = tdc_link_feed(&dec, p, n, &ev);
 *         p += used; n -= used;
 *         if (ev.type == TDC_LINK_EV_PACKET) run_pipeline(&ev);   // a buffer was filled
 *         else if (ev.type == TDC_LINK_EV_ERROR) log(ev.error);
 *     }
 * tdc_link_feed() returns as soon as one event happened, so the caller sees
 * a filled buffer before the next packet of the same kind can overwrite it.
 */
#ifndef TDC_LINK_H
#define TDC_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "tdc_fixed.h"
#include "tdc_pixfmt.h"

/* ------------------------------------------------------------------------
 * Wire format constants.
 * ---------------------------------------------------------------------- */
#define TDC_LINK_MAGIC 0x4C434454u /* bytes 'T' 'D' 'C' 'L' read as uint32 LE */
#define TDC_LINK_VERSION 1u
#define TDC_LINK_HEADER_BYTES 32u
#define TDC_LINK_STREAM_HEADER_BYTES 16u /* payload of a STREAM packet */

/* Header field byte offsets (all naturally aligned). */
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
    TDC_LINK_KIND_FIRST = TDC_LINK_KIND_STREAM,
    TDC_LINK_KIND_LAST = TDC_LINK_KIND_PATTERN
} tdc_link_kind_t;

/* Per-packet flags (header `flags`). */
#define TDC_LINK_PKT_MV_PER_SAMPLE 0x0001u /* MOTION: one vector per subframe sample (tile grid) */
#define TDC_LINK_PKT_KNOWN 0x0001u

/* Stream header flags: which stages the stream uses, so the controller can
 * skip the others. */
#define TDC_LINK_STREAM_REDUCED 0x0001u   /* TRM: reduced frames alternate with full ones */
#define TDC_LINK_STREAM_SUBFRAMES 0x0002u /* tile-ordered subframes (+ pattern bitmaps) */
#define TDC_LINK_STREAM_MOTION 0x0004u    /* per-pixel motion vectors are sent */
#define TDC_LINK_STREAM_MIRRORS 0x0008u   /* motion vectors include mirror reflections */
#define TDC_LINK_STREAM_SAMPLE_MV 0x0010u /* subframe samples carry their own motion vectors */
#define TDC_LINK_STREAM_KNOWN 0x001Fu

/* Motion vectors: Q4 (1/16 px), range +-2047.9375 px, BACKWARD (the point
 * now at p was at p + mv in the previous frame). */
#define TDC_LINK_MV_FRAC_BITS 4

/* Stream header (payload of a STREAM packet, 16 bytes LE on the wire). */
typedef struct {
    uint32_t flags;      /* TDC_LINK_STREAM_* */
    uint16_t r_num;      /* TRM ratio r = r_num / r_den; 1/4 <= r < 1 if REDUCED, */
    uint16_t r_den;      /* else r = 1 (1/1) */
    uint16_t width;      /* full-resolution size of one eye: must match the panel */
    uint16_t height;
    uint8_t eyes;        /* 1 or 2: must match the panel */
    uint8_t reserved;    /* 0 */
    uint16_t refresh_hz; /* rate the renderer sends frames at (informative) */
} tdc_link_stream_info_t;

/* ------------------------------------------------------------------------
 * Errors: one code per malformed class, each with its own counter.
 * ---------------------------------------------------------------------- */
typedef enum {
    TDC_LINK_OK = 0,
    TDC_LINK_ERR_MAGIC = 1,       /* sync lost: a packet boundary does not start with the magic */
    TDC_LINK_ERR_GARBAGE = 2,     /* bytes between packets discarded while resynchronising */
    TDC_LINK_ERR_HEADER_CRC = 3,  /* header CRC mismatch (corrupt header or false magic) */
    TDC_LINK_ERR_VERSION = 4,     /* unsupported protocol version */
    TDC_LINK_ERR_KIND = 5,        /* unknown packet kind */
    TDC_LINK_ERR_EYE = 6,         /* eye index >= the panel's eyes */
    TDC_LINK_ERR_FORMAT = 7,      /* unknown/unsupported pixel format or packet flags */
    TDC_LINK_ERR_DIMENSIONS = 8,  /* dimensions do not match the panel (or reduced size) */
    TDC_LINK_ERR_LENGTH = 9,      /* payload length inconsistent with kind/format/size */
    TDC_LINK_ERR_CRC = 10,        /* payload CRC mismatch */
    TDC_LINK_ERR_STREAM = 11,     /* no stream header yet, or a different stream id */
    TDC_LINK_ERR_ORDER = 12,      /* frame index lower than the current frame */
    TDC_LINK_ERR_DUPLICATE = 13,  /* same frame index, kind and eye accepted already */
    TDC_LINK_ERR_MISSING_REDUCED = 14, /* a frame whose reduced eye never arrived was passed */
    TDC_LINK_ERR_UNEXPECTED = 15, /* kind not enabled by the stream header / not due now */
    TDC_LINK_ERR_STREAM_HEADER = 16, /* stream header contents invalid (flags, r, size) */
    TDC_LINK_ERR_COUNT = 17
} tdc_link_err_t;

/* Short name of an error code ("crc", "magic", ...). */
const char *tdc_link_err_name(tdc_link_err_t e);

/* ------------------------------------------------------------------------
 * Compile-time sizes.  A board build defines TDC_LINK_MAX_WIDTH/HEIGHT from
 * its panel (or the panel config header's TDC_PANEL_WIDTH/HEIGHT); the host
 * default holds 1920x1080 and 1440x1600 per eye.
 * ---------------------------------------------------------------------- */
#ifndef TDC_LINK_MAX_WIDTH
#ifdef TDC_PANEL_WIDTH
#define TDC_LINK_MAX_WIDTH TDC_PANEL_WIDTH
#define TDC_LINK_MAX_HEIGHT TDC_PANEL_HEIGHT
#define TDC_LINK_MAX_PIXELS ((uint32_t)TDC_PANEL_WIDTH * TDC_PANEL_HEIGHT)
#else
#define TDC_LINK_MAX_WIDTH 1920
#define TDC_LINK_MAX_HEIGHT 1600
#define TDC_LINK_MAX_PIXELS (1440u * 1600u) /* >= 1920 x 1080 */
#endif
#endif
#ifndef TDC_LINK_MAX_PIXELS
#define TDC_LINK_MAX_PIXELS ((uint32_t)TDC_LINK_MAX_WIDTH * TDC_LINK_MAX_HEIGHT)
#endif

/* Pixel formats this build accepts: bit f set = tdc_pixfmt_t f compiled in.
 * A board that never receives e.g. RGB30 defines a smaller mask and the
 * unpacker for it is left out of the image; packets in a format outside the
 * mask are rejected with TDC_LINK_ERR_FORMAT. */
#ifndef TDC_LINK_FORMAT_MASK
#define TDC_LINK_FORMAT_MASK 0x1Eu /* bits 1..4: RGB888, RGB565, RGB30, YCBCR420 (numeric: used in #if) */
#endif

/* Reduced size for ratio num/den: round(n * num / den), at least 1 (the same
 * rule as TDC_TRM_REDUCED_DIM in tdc_trm.h). */
#define TDC_LINK_REDUCED_DIM(n, num, den)                                                          \
    ((((uint32_t)(n) * (num)) + (den) / 2u) / (den) < 1u ? 1u : (((uint32_t)(n) * (num)) + (den) / 2u) / (den))
#define TDC_LINK_TILES(n) (((uint32_t)(n) + 1u) / 2u) /* 2x2 tiles along a side */

/* Buffer sizes in bytes for a w x h eye. */
#define TDC_LINK_FRAME_BYTES(w, h) ((size_t)(w) * (h) * 3u)                          /* RGB888 */
#define TDC_LINK_SUBFRAME_BYTES(w, h) ((size_t)TDC_LINK_TILES(w) * TDC_LINK_TILES(h) * 3u)
#define TDC_LINK_MOTION_COUNT(w, h) ((size_t)(w) * (h) * 2u)                         /* int16s */
#define TDC_LINK_SAMPLE_MOTION_COUNT(w, h) ((size_t)TDC_LINK_TILES(w) * TDC_LINK_TILES(h) * 2u)
#define TDC_LINK_PATTERN_BYTES(w, h) (((size_t)TDC_LINK_TILES(w) * TDC_LINK_TILES(h) + 7u) / 8u)
/* Staging: the largest payload, a full frame in RGB30 (4 B/px) or the
 * per-pixel motion vectors (4 B/px). */
#define TDC_LINK_STAGING_BYTES(w, h) ((size_t)(w) * (h) * 4u + TDC_LINK_STREAM_HEADER_BYTES)
#define TDC_LINK_STAGING_MAX TDC_LINK_STAGING_BYTES(1u, TDC_LINK_MAX_PIXELS)

/* ------------------------------------------------------------------------
 * Decoder.
 * ---------------------------------------------------------------------- */
typedef struct {
    uint16_t width;  /* panel size of one eye (must match the stream) */
    uint16_t height;
    uint8_t eyes;    /* 1 or 2 */
} tdc_link_config_t;

/*
 * Caller-owned pipeline buffers the decoder writes into (per eye).  A NULL
 * pointer means this build does not support that kind: its packets are
 * rejected with TDC_LINK_ERR_UNEXPECTED and a stream header that asks for it
 * with TDC_LINK_ERR_STREAM_HEADER.  `staging` must hold the largest payload
 * accepted (TDC_LINK_STAGING_BYTES(width, height) for everything).
 */
typedef struct {
    uint8_t *staging;
    size_t staging_bytes;
    uint8_t *full[2];         /* RGB888, width x height, rows full_stride bytes apart */
    uint32_t full_stride;
    uint8_t *reduced[2];      /* RGB888, rw x rh packed (rw * 3 bytes per row) */
    size_t reduced_bytes;     /* capacity of each reduced buffer */
    uint8_t *subframe[2];     /* RGB888 samples, tiles_x x tiles_y packed */
    int16_t *motion[2];       /* (dx, dy) Q4 per pixel, width x height x 2 */
    int16_t *sample_motion[2]; /* (dx, dy) Q4 per subframe sample, tiles x 2 */
    uint8_t *pattern[2];      /* 1 bit per tile, row-major, LSB first, 1 = bowtie */
} tdc_link_buffers_t;

typedef enum {
    TDC_LINK_EV_NONE = 0,   /* input exhausted, nothing happened */
    TDC_LINK_EV_PACKET = 1, /* a packet was accepted and its buffer filled */
    TDC_LINK_EV_ERROR = 2   /* a packet/bytes were rejected (error, frame_index if known) */
} tdc_link_event_type_t;

typedef struct {
    uint8_t type;         /* tdc_link_event_type_t */
    uint8_t kind;         /* tdc_link_kind_t (0 if unknown) */
    uint8_t eye;
    uint8_t format;       /* tdc_pixfmt_t of pixel packets */
    uint16_t error;       /* tdc_link_err_t for EV_ERROR */
    uint16_t stream_id;
    uint16_t width;       /* dimensions of the packet */
    uint16_t height;
    uint16_t flags;       /* packet flags */
    uint16_t reserved;
    uint32_t frame_index;
    uint32_t detail;      /* EV_ERROR: garbage bytes / missing reduced frames; else payload bytes */
} tdc_link_event_t;

typedef struct {
    uint32_t errors[TDC_LINK_ERR_COUNT]; /* per error code (index 0 unused) */
    uint32_t packets_ok;                 /* accepted packets */
    uint32_t packets_by_kind[TDC_LINK_KIND_LAST + 1];
    uint64_t bytes_in;                   /* all bytes fed */
    uint64_t garbage_bytes;              /* bytes discarded while hunting for a packet */
    uint64_t skipped_bytes;              /* payload bytes of rejected packets skipped */
    uint32_t missing_reduced_frames;     /* reduced frames that never arrived */
    uint32_t events_dropped;             /* events lost because the queue was full (should be 0) */
} tdc_link_counters_t;

#define TDC_LINK_EVENT_QUEUE 4

/* Decoder state: public so it can be a static object; treat as opaque. */
typedef struct {
    tdc_link_config_t cfg;
    tdc_link_buffers_t buf;
    /* receive state machine */
    uint8_t state;           /* internal */
    uint8_t hdr_fill;        /* header bytes collected */
    uint8_t replay_src;      /* what is being rescanned: none, `replay` (a bad header), staging (a bad payload) */
    uint8_t hdr_in_staging;  /* the header being collected began inside a staging rescan, at hdr_start */
    uint8_t hdr[TDC_LINK_HEADER_BYTES];
    uint8_t replay[TDC_LINK_HEADER_BYTES];
    uint32_t replay_pos;     /* rescan position / end (bytes of `replay` or staging offsets) */
    uint32_t replay_len;
    uint32_t replay_gen;     /* bumped whenever a new rescan is set up */
    uint32_t hdr_start;      /* staging offset of the header's first byte (hdr_in_staging) */
    uint32_t payload_base;   /* the payload being collected lies at staging + payload_base */
    uint32_t payload_len;    /* current packet */
    uint32_t payload_fill;
    uint32_t payload_crc;    /* expected */
    uint32_t crc_state;      /* running */
    uint32_t skip_left;      /* payload bytes left to skip of a rejected packet */
    uint32_t garbage_run;    /* bytes discarded in the current hunt */
    tdc_link_event_t pkt;    /* parsed header of the current packet */
    /* stream and sequence state (changed only by accepted packets) */
    uint8_t stream_active;
    uint8_t have_frame;
    uint16_t stream_id;
    tdc_link_stream_info_t stream;
    uint16_t rw, rh;         /* reduced size of the active stream */
    uint32_t frame_index;    /* current (newest accepted) frame */
    uint32_t frame_mask;     /* (kind, eye) slots accepted in frame_index */
    /* events */
    uint8_t ev_head, ev_count;
    tdc_link_event_t ev[TDC_LINK_EVENT_QUEUE];
    tdc_link_counters_t cnt;
} tdc_link_decoder_t;

/* Validates cfg and buffers (sizes for cfg's panel) and resets everything.
 * TDC_ERR_ARG for NULLs / bad eyes, TDC_ERR_SIZE if the panel exceeds the
 * compiled maximum or the staging buffer cannot hold a minimal payload. */
TDC_MUST_CHECK
tdc_status_t tdc_link_decoder_init(tdc_link_decoder_t *dec, const tdc_link_config_t *cfg,
                                   const tdc_link_buffers_t *buffers);

/* Feeds up to n bytes; returns how many were consumed.  Stops right after
 * the first event (written to *ev; ev->type = TDC_LINK_EV_NONE if all n
 * bytes were consumed without one).  Call again with the rest.  Queued
 * events are returned first, consuming 0 bytes. */
size_t tdc_link_feed(tdc_link_decoder_t *dec, const uint8_t *bytes, size_t n, tdc_link_event_t *ev);

/* Drops any partly received packet and hunts for the next magic (e.g. after
 * a USB disconnect); stream, sequence, counters and buffers are kept.  The
 * dropped bytes count as garbage. */
void tdc_link_decoder_resync(tdc_link_decoder_t *dec);

/* Counters (live). */
const tdc_link_counters_t *tdc_link_counters(const tdc_link_decoder_t *dec);
uint32_t tdc_link_error_count(const tdc_link_decoder_t *dec, tdc_link_err_t e);

/* Active stream header, or NULL before the first accepted STREAM packet. */
const tdc_link_stream_info_t *tdc_link_stream(const tdc_link_decoder_t *dec);

/* Reduced-frame size of the active stream (0 x 0 without reduced frames). */
void tdc_link_reduced_size(const tdc_link_decoder_t *dec, uint32_t *rw, uint32_t *rh);

/* Which kind is due for (frame, eye) in a REDUCED stream: FULL or REDUCED.
 * Mono: even frames full, odd reduced.  Stereo: eye e of frame f is reduced
 * iff (f + e) is odd (one eye full, the other reduced, swapped every frame). */
static inline tdc_link_kind_t tdc_link_trm_kind(uint32_t frame, uint32_t eye)
{
    return ((frame + eye) & 1u) ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL;
}

/* Expected payload bytes of a packet (0 if the combination is invalid). */
uint32_t tdc_link_payload_bytes(tdc_link_kind_t kind, tdc_pixfmt_t fmt, uint32_t width, uint32_t height,
                                uint32_t pkt_flags);

/* Little-endian field access shared by decoder and encoder. */
static inline uint32_t tdc_link_rd16(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8);
}
static inline uint32_t tdc_link_rd32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}
static inline void tdc_link_wr16(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}
static inline void tdc_link_wr32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
}

#endif /* TDC_LINK_H */
