/*
 * tdc_link.h - link protocol (docs/link-protocol.md) and the display-side
 * streaming decoder.
 *
 * The renderer sends packets: a 32-byte header (magic, version, kind, eye,
 * pixel format, stream id, flags, frame index, dimensions, payload length,
 * payload CRC-32, header CRC-32; little-endian, tdc_wire.h) followed by the
 * payload.
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

#include "tdc_band_link.h"
#include "tdc_fixed.h"
#include "tdc_layer_link.h"
#include "tdc_fov_link.h"
#include "tdc_pixfmt.h"
#include "tdc_wire.h"

/* Wire format (header, kinds, STREAM payload, rejection reasons, sizes):
 * tdc_wire.h, included here. */

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

/* Staging: the largest payload, a full frame in RGB30 (4 B/px) or the
 * per-pixel motion vectors (4 B/px). */
#define TDC_LINK_STAGING_BYTES(w, h) ((size_t)(w) * (h)*4u + TDC_LINK_STREAM_HEADER_BYTES)
#define TDC_LINK_STAGING_MAX TDC_LINK_STAGING_BYTES(1u, TDC_LINK_MAX_PIXELS)
/* Staging for a build that takes layered subframes: the largest LAYERS
 * payload (all four layers + falloff: 16 + 28 bytes per tile = 7 B/px)
 * exceeds TDC_LINK_STAGING_BYTES. */
#define TDC_LINK_STAGING_LAYERS_BYTES(w, h) ((size_t)TDC_LAYER_HDR_BYTES + TDC_TILE_COUNT(w, h) * 28u)
/* Staging for a build that takes FULL and REDUCED pictures only as row
 * bands (stream flag BANDS) of at most `rows` rows, bpp bytes per pixel
 * in the widest compiled-in format: one band, not a frame (tdc_band_link.h). */
#define TDC_LINK_STAGING_BAND_BYTES(w, rows, bpp) ((size_t)TDC_BAND_HDR_BYTES + (size_t)(w) * (rows) * (bpp))

/* ------------------------------------------------------------------------
 * Decoder.
 * ---------------------------------------------------------------------- */
typedef struct {
    uint16_t width; /* panel size of one eye (must match the stream) */
    uint16_t height;
    uint8_t eyes; /* 1 or 2 */
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
    uint8_t *full[2]; /* RGB888, width x height, rows full_stride bytes apart */
    uint32_t full_stride;
    uint8_t *reduced[2];       /* RGB888, rw x rh packed (rw * 3 bytes per row) */
    size_t reduced_bytes;      /* capacity of each reduced buffer */
    uint8_t *subframe[2];      /* RGB888 samples, tiles_x x tiles_y packed */
    int16_t *motion[2];        /* (dx, dy) Q4 per pixel, width x height x 2 */
    int16_t *sample_motion[2]; /* (dx, dy) Q4 per subframe sample, tiles x 2 */
    uint8_t *pattern[2];       /* 1 bit per tile, row-major, LSB first, 1 = bowtie */
    tdc_layer_frame_t *layers[2]; /* layered subframes (tdc_layer_link.h); NULL: not in this build */
    /* 1: a stream may announce per-pixel MOTION that no stage of this build
     * uses (motion[] NULL): its packets are not staged or stored, their
     * payloads skipped (the header CRC vouches for the length, which must
     * be the expected one) and counted in packets_skipped -- not errors. */
    uint8_t skip_motion;
    /* 1: FULL packets (and FULL row bands) are validated and accepted but not unpacked (full[]
     * may then be NULL): the payload stays in `staging` until the next
     * tdc_link_feed() call that processes bytes, and the caller unpacks it
     * with tdc_link_unpack_full() where and if it wants.  A frame loop
     * sets this so that a packet it does not use (another mode's kind, a
     * later frame, a late resend) never touches the frame buffer being
     * shown (firmware/board/tdc_main.c: unpacked on arrival, a FULL
     * packet would change an eye the loop keeps, tests/fuzz/findings/). */
    uint8_t defer_full;
    /* FOVEATED packets (stream flag TDC_LINK_STREAM_FOVEATED, tdc_fov_link.h):
     * the kernel log-polar samples, lp_w x lp_h RGB888 with rows lp_w * 3
     * bytes apart (columns [u0, lp_w) written), at most fov_lp_bytes; their
     * motion vectors (TAA streams), int16 pairs with rows lp_w * 2 apart, at
     * most fov_mv_count int16s (NULL: packets with vectors are refused); the
     * disk pixels go into full[eye] (the stage reads each before it writes
     * it), or, for a TRM stream's reduced slot (packet flag
     * TDC_LINK_PKT_FOV_REDUCED), into reduced[eye] (rows rW * 3 bytes apart).
     * fov_lp NULL: the build has no foveation stage. */
    uint8_t *fov_lp[2];
    size_t fov_lp_bytes;
    int16_t *fov_mv[2];
    size_t fov_mv_count;
} tdc_link_buffers_t;

typedef enum {
    TDC_LINK_EV_NONE = 0,   /* input exhausted, nothing happened */
    TDC_LINK_EV_PACKET = 1, /* a packet was accepted and its buffer filled */
    TDC_LINK_EV_ERROR = 2   /* a packet/bytes were rejected (error, frame_index if known) */
} tdc_link_event_type_t;

typedef struct {
    uint8_t type; /* tdc_link_event_type_t */
    uint8_t kind; /* tdc_link_kind_t (0 if unknown) */
    uint8_t eye;
    uint8_t format; /* tdc_pixfmt_t of pixel packets */
    uint16_t error; /* tdc_link_err_t for EV_ERROR */
    uint16_t stream_id;
    uint16_t width; /* dimensions of the packet */
    uint16_t height;
    uint16_t flags; /* packet flags */
    uint16_t reserved;
    uint32_t frame_index;
    uint32_t detail; /* EV_ERROR: garbage bytes / missing reduced frames; else payload bytes */
} tdc_link_event_t;

typedef struct {
    uint32_t errors[TDC_LINK_ERR_COUNT]; /* per error code (index 0 unused) */
    uint32_t packets_ok;                 /* accepted packets */
    uint32_t packets_skipped;            /* packets of kinds no stage uses (skip_motion), not stored */
    uint32_t packets_by_kind[TDC_LINK_KIND_LAST + 1];
    uint64_t bytes_in;               /* all bytes fed */
    uint64_t garbage_bytes;          /* bytes discarded while hunting for a packet */
    uint64_t skipped_bytes;          /* payload bytes of rejected packets skipped */
    uint32_t missing_reduced_frames; /* reduced frames that never arrived */
    uint32_t events_dropped;         /* events lost because the queue was full (should be 0) */
    uint32_t layer_errors[TDC_LAYER_ERR_N]; /* TDC_LINK_ERR_LAYERS by reason (index 0 unused) */
    uint32_t fov_refused[TDC_FOV_HDR_COUNT]; /* TDC_LINK_ERR_FOVEATION by reason (index 0 unused) */
    uint32_t band_errors[TDC_BAND_ERR_N];    /* TDC_LINK_ERR_BAND by reason (index 0 unused) */
    uint32_t band_drops[TDC_BAND_DROP_N];    /* TDC_LINK_ERR_BAND_DROPPED by reason (index 0 unused) */
    uint32_t bands_ok;                       /* accepted row bands (each also in packets_ok) */
} tdc_link_counters_t;

#define TDC_LINK_EVENT_QUEUE 4

/* Decoder state: public so it can be a static object; treat as opaque. */
typedef struct {
    tdc_link_config_t cfg;
    tdc_link_buffers_t buf;
    /* receive state machine */
    uint8_t state;          /* internal */
    uint8_t hdr_fill;       /* header bytes collected */
    uint8_t replay_src;     /* what is being rescanned: none, `replay` (a bad header), staging (a bad payload) */
    uint8_t hdr_in_staging; /* the header being collected began inside a staging rescan, at hdr_start */
    uint8_t hdr[TDC_LINK_HEADER_BYTES];
    uint8_t replay[TDC_LINK_HEADER_BYTES];
    uint32_t replay_pos; /* rescan position / end (bytes of `replay` or staging offsets) */
    uint32_t replay_len;
    uint32_t replay_gen;   /* bumped whenever a new rescan is set up */
    uint32_t hdr_start;    /* staging offset of the header's first byte (hdr_in_staging) */
    uint32_t payload_base; /* the payload being collected lies at staging + payload_base */
    uint32_t payload_len;  /* current packet */
    uint32_t payload_fill;
    uint32_t payload_crc; /* expected */
    uint32_t crc_state;   /* running */
    uint32_t skip_left;   /* payload bytes left to skip of a rejected packet */
    uint32_t garbage_run; /* bytes discarded in the current hunt */
    tdc_link_event_t pkt; /* parsed header of the current packet */
    /* stream and sequence state (changed only by accepted packets) */
    uint8_t stream_active;
    uint8_t have_frame;
    uint16_t stream_id;
    tdc_link_stream_info_t stream;
    uint16_t rw, rh;      /* reduced size of the active stream */
    uint32_t frame_index; /* current (newest accepted) frame */
    uint32_t frame_mask;  /* (kind, eye) slots accepted in frame_index */
    /* defer_full: the FULL packet whose payload waits in staging */
    uint8_t staged_full; /* 1 from its acceptance until bytes are processed again */
    uint8_t staged_fmt;
    uint16_t staged_w, staged_h;
    uint32_t staged_base;
    uint8_t fov_valid;    /* bit e: fov[e] holds eye e's last accepted foveation header */
    tdc_fov_hdr_t fov[2];
    /* row bands (stream flag BANDS): per eye the picture in flight and the
     * header of its last accepted band; the FULL band waiting in staging
     * (defer_full) starts at row staged_row */
    uint8_t band_valid; /* bit e: band[e] holds eye e's last accepted band */
    uint16_t staged_row;
    tdc_band_seq_t band_seq[2];
    tdc_band_hdr_t band[2];
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

/* defer_full: unpacks the FULL packet just returned by tdc_link_feed()
 * (before the next feed call) as RGB888 into dst, rows stride bytes apart
 * (stride >= width * 3).  For a FULL row band dst is the picture's first
 * row: the band's rows go to dst + first_row * stride.  TDC_ERR_STATE if no accepted FULL payload is
 * waiting in staging (none was, or bytes were processed since), TDC_ERR_ARG
 * for a NULL dst or a short stride.  The payload stays valid: a second call
 * unpacks the same frame again. */
TDC_MUST_CHECK
tdc_status_t tdc_link_unpack_full(const tdc_link_decoder_t *dec, uint8_t *dst, uint32_t stride);

/* Drops any partly received packet and hunts for the next magic (e.g. after
 * a USB disconnect); stream, sequence, counters and buffers are kept.  The
 * dropped bytes count as garbage. */
void tdc_link_decoder_resync(tdc_link_decoder_t *dec);

/* Counters (live). */
const tdc_link_counters_t *tdc_link_counters(const tdc_link_decoder_t *dec);
uint32_t tdc_link_error_count(const tdc_link_decoder_t *dec, tdc_link_err_t e);

/* Active stream header, or NULL before the first accepted STREAM packet. */
const tdc_link_stream_info_t *tdc_link_stream(const tdc_link_decoder_t *dec);

/* The foveation header (stage parameters, geometry) of eye's last accepted
 * FOVEATED packet in the active stream, NULL if none: read it on that
 * packet's event, before feeding more bytes.  Its geometry is the slot's
 * grid: W x H, or rW x rH for a packet with TDC_LINK_PKT_FOV_REDUCED (the
 * event's flags say which). */
const tdc_fov_hdr_t *tdc_link_fov(const tdc_link_decoder_t *dec, uint32_t eye);

/* The header of eye's last accepted row band (index, count, rows) in the
 * active stream, NULL if none: read it on that band's event. */
const tdc_band_hdr_t *tdc_link_band(const tdc_link_decoder_t *dec, uint32_t eye);

/* Reduced-frame size of the active stream (0 x 0 without reduced frames). */
void tdc_link_reduced_size(const tdc_link_decoder_t *dec, uint32_t *rw, uint32_t *rh);

/* Which kind is due for (frame, eye) in a REDUCED stream: FULL or REDUCED.
 * Mono: even frames full, odd reduced.  Stereo: eye e of frame f is reduced
 * iff (f + e) is odd (one eye full, the other reduced, swapped every frame). */
static inline tdc_link_kind_t tdc_link_trm_kind(uint32_t frame, uint32_t eye)
{
    return ((frame + eye) & 1u) ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL;
}

#endif /* TDC_LINK_H */
