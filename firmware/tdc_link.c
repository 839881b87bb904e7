/*
 * tdc_link.c - streaming link decoder (docs/link-protocol.md).
 *
 * Receive state machine, fed any number of bytes at a time:
 *
 *   HUNT     search for the first magic byte; bytes passed over are garbage
 *   HEADER   collect the 32-byte header.  `synced` says whether it began
 *            where the previous packet ended (a mismatching magic there is
 *            ERR_MAGIC: sync lost) or where HUNT found a candidate.  A header
 *            with a bad CRC is rejected and its bytes 1..31 are rescanned
 *            (the true packet may start inside a false candidate).
 *   PAYLOAD  copy the payload into the staging buffer, CRC on the fly.  A
 *            payload whose CRC fails is rescanned for a packet start (a byte
 *            lost in transit puts the next packet's magic inside it), so the
 *            decoder resynchronises on the very next valid packet.  A packet
 *            found inside such a rescan is collected in place (payload_base).
 *   SKIP     pass over the payload of a packet whose (CRC-valid) header was
 *            rejected, so the next packet is found without hunting
 *
 * Nothing outside this struct is written before a packet is complete and
 * its payload CRC matched; then the payload is unpacked into the pipeline
 * buffer of its kind and eye, and the sequence state advances.
 */
#include "tdc_link.h"

/* check_header(): a valid packet of a kind this build skips (skip_motion). */
#define LINK_SKIP_UNUSED ((tdc_link_err_t)(TDC_LINK_ERR_COUNT + 1))

#include <string.h>

#include "tdc_crc32.h"

enum { ST_HUNT = 0, ST_HEADER = 1, ST_PAYLOAD = 2, ST_SKIP = 3 };
enum { RP_NONE = 0, RP_HEADER = 1, RP_STAGING = 2 };

/* Source offset meaning "these bytes are new input (or the header replay),
 * not part of the staging buffer". */
#define NOT_STAGING UINT32_MAX

static const uint8_t tdc_link_magic_bytes[4] = {'T', 'D', 'C', 'L'};

/* `synced` lives in the top bit of `state` so the struct stays small. */
#define ST_MASK 0x7Fu
#define ST_SYNCED 0x80u

/* Duplicate-detection slot of a packet within one frame index. */
static uint32_t slot_bit(uint32_t kind, uint32_t eye, uint32_t flags)
{
    if (kind == TDC_LINK_KIND_FOVEATED) {
        /* one picture per eye and frame: FULL or FOVEATED, or in a TRM
         * stream's reduced slot REDUCED or FOVEATED with FOV_REDUCED */
        kind = (flags & TDC_LINK_PKT_FOV_REDUCED) ? TDC_LINK_KIND_REDUCED : TDC_LINK_KIND_FULL;
    }
    if (kind == TDC_LINK_KIND_MOTION && (flags & TDC_LINK_PKT_MV_PER_SAMPLE)) {
        return 1u << (14u + eye);
    }
    return 1u << (kind * 2u + eye);
}

/* ------------------------------------------------------------------------
 * Events and counters.
 * ---------------------------------------------------------------------- */
static void push_event(tdc_link_decoder_t *dec, const tdc_link_event_t *ev)
{
    if (dec->ev_count >= TDC_LINK_EVENT_QUEUE) {
        dec->cnt.events_dropped++;
        return;
    }
    dec->ev[(dec->ev_head + dec->ev_count) % TDC_LINK_EVENT_QUEUE] = *ev;
    dec->ev_count++;
}

static void push_error(tdc_link_decoder_t *dec, tdc_link_err_t e, int with_header, uint32_t detail)
{
    tdc_link_event_t ev;
    if (with_header) {
        ev = dec->pkt;
    } else {
        memset(&ev, 0, sizeof ev);
    }
    ev.type = TDC_LINK_EV_ERROR;
    ev.error = (uint16_t)e;
    ev.detail = detail;
    dec->cnt.errors[e]++;
    push_event(dec, &ev);
}

static void set_state(tdc_link_decoder_t *dec, unsigned st, int synced)
{
    dec->state = (uint8_t)(st | (synced ? ST_SYNCED : 0u));
}

/* n bytes passed over while hunting: garbage between packets, or (inside a
 * staging rescan) the rest of a packet already rejected for its CRC. */
static void discard(tdc_link_decoder_t *dec, size_t n, uint32_t src_off)
{
    if (src_off == NOT_STAGING) {
        dec->garbage_run += (uint32_t)n;
        dec->cnt.garbage_bytes += n;
    } else {
        dec->cnt.skipped_bytes += n;
    }
}

/* ------------------------------------------------------------------------
 * Init and getters.
 * ---------------------------------------------------------------------- */
tdc_status_t tdc_link_decoder_init(tdc_link_decoder_t *dec, const tdc_link_config_t *cfg,
                                   const tdc_link_buffers_t *buffers)
{
    if (!dec || !cfg || !buffers || !buffers->staging) {
        return TDC_ERR_ARG;
    }
    if (cfg->eyes < 1 || cfg->eyes > 2 || cfg->width == 0 || cfg->height == 0) {
        return TDC_ERR_ARG;
    }
    if (cfg->width > TDC_LINK_MAX_WIDTH || cfg->height > TDC_LINK_MAX_HEIGHT ||
        (uint32_t)cfg->width * cfg->height > TDC_LINK_MAX_PIXELS) {
        return TDC_ERR_SIZE;
    }
    if (buffers->staging_bytes < TDC_LINK_STREAM_HEADER_BYTES) {
        return TDC_ERR_SIZE;
    }
    for (unsigned e = 0; e < cfg->eyes; e++) {
        if (buffers->full[e] && buffers->full_stride < (uint32_t)cfg->width * 3u) {
            return TDC_ERR_SIZE;
        }
    }
    memset(dec, 0, sizeof *dec);
    dec->cfg = *cfg;
    dec->buf = *buffers;
    set_state(dec, ST_HUNT, 0); /* joining a stream mid-way is normal: no sync to lose yet */
    return TDC_OK;
}

void tdc_link_decoder_resync(tdc_link_decoder_t *dec)
{
    const unsigned st = dec->state & ST_MASK;
    uint32_t dropped = 0;
    if (st == ST_HEADER) {
        dropped = dec->hdr_fill;
    } else if (st == ST_PAYLOAD) {
        dropped = TDC_LINK_HEADER_BYTES + dec->payload_fill;
    }
    dec->garbage_run += dropped;
    dec->cnt.garbage_bytes += dropped;
    dec->hdr_fill = 0;
    dec->replay_src = RP_NONE;
    dec->replay_len = 0;
    dec->replay_pos = 0;
    dec->replay_gen++;
    dec->hdr_in_staging = 0;
    dec->payload_base = 0;
    dec->skip_left = 0;
    dec->staged_full = 0;
    set_state(dec, ST_HUNT, 0);
}

const tdc_link_counters_t *tdc_link_counters(const tdc_link_decoder_t *dec)
{
    return &dec->cnt;
}

uint32_t tdc_link_error_count(const tdc_link_decoder_t *dec, tdc_link_err_t e)
{
    return (unsigned)e < (unsigned)TDC_LINK_ERR_COUNT ? dec->cnt.errors[e] : 0u;
}

const tdc_link_stream_info_t *tdc_link_stream(const tdc_link_decoder_t *dec)
{
    return dec->stream_active ? &dec->stream : NULL;
}

const tdc_fov_hdr_t *tdc_link_fov(const tdc_link_decoder_t *dec, uint32_t eye)
{
    return eye < 2u && ((dec->fov_valid >> eye) & 1u) ? &dec->fov[eye] : NULL;
}

const tdc_band_hdr_t *tdc_link_band(const tdc_link_decoder_t *dec, uint32_t eye)
{
    return eye < 2u && ((dec->band_valid >> eye) & 1u) ? &dec->band[eye] : NULL;
}

void tdc_link_reduced_size(const tdc_link_decoder_t *dec, uint32_t *rw, uint32_t *rh)
{
    *rw = dec->rw;
    *rh = dec->rh;
}

/* ------------------------------------------------------------------------
 * Header validation: everything that can be checked before the payload.
 * ---------------------------------------------------------------------- */
static tdc_link_err_t check_header(const tdc_link_decoder_t *dec, uint32_t version, uint32_t payload_len)
{
    const tdc_link_event_t *p = &dec->pkt;
    const uint32_t kind = p->kind, eye = p->eye, fmt = p->format, flags = p->flags;

    if (version != TDC_LINK_VERSION) {
        return TDC_LINK_ERR_VERSION;
    }
    const tdc_link_kind_info_t *ki = tdc_link_kind_info(kind);
    if (!ki) {
        return TDC_LINK_ERR_KIND;
    }
    if (kind == TDC_LINK_KIND_STREAM) {
        if (eye != 0) {
            return TDC_LINK_ERR_EYE;
        }
        if (fmt != TDC_PIXFMT_NONE || flags != 0) {
            return TDC_LINK_ERR_FORMAT;
        }
        if (p->width != dec->cfg.width || p->height != dec->cfg.height) {
            return TDC_LINK_ERR_DIMENSIONS;
        }
        if (payload_len != TDC_LINK_STREAM_HEADER_BYTES) {
            return TDC_LINK_ERR_LENGTH;
        }
        return TDC_LINK_OK;
    }
    if (!dec->stream_active || p->stream_id != dec->stream_id) {
        return TDC_LINK_ERR_STREAM;
    }
    if (eye >= dec->cfg.eyes) {
        return TDC_LINK_ERR_EYE;
    }
    if ((flags & ~(uint32_t)ki->pkt_flags) != 0 || (kind == TDC_LINK_KIND_LAYERS && !tdc_layer_flags_valid(flags))) {
        return TDC_LINK_ERR_FORMAT;
    }
    const int pixel_kind = ki->rule == TDC_LINK_PAYLOAD_PIXELS;
    if (kind == TDC_LINK_KIND_FOVEATED ? fmt != TDC_PIXFMT_RGB888 /* the samples: RGB8 only */
        : pixel_kind ? (!tdc_pixfmt_valid(fmt) || !((TDC_LINK_FORMAT_MASK >> fmt) & 1u))
                     : fmt != TDC_PIXFMT_NONE) {
        return TDC_LINK_ERR_FORMAT;
    }

    /* Is this kind part of the stream, supported by this build, and due now? */
    const uint32_t sflags = dec->stream.flags;
    const int trm = (sflags & TDC_LINK_STREAM_REDUCED) != 0;
    const tdc_link_buffers_t *b = &dec->buf;
    /* a BANDS stream sends every picture as row bands, any other none */
    const int band = (kind == TDC_LINK_KIND_FULL || kind == TDC_LINK_KIND_REDUCED) && (flags & TDC_LINK_PKT_BAND);
    const int banded = band == ((sflags & TDC_LINK_STREAM_BANDS) != 0);
    int ok;
    switch (kind) {
    case TDC_LINK_KIND_FULL:
        ok = banded && (b->full[eye] != NULL || b->defer_full) &&
             (!trm || tdc_link_trm_kind(p->frame_index, eye) == TDC_LINK_KIND_FULL);
        break;
    case TDC_LINK_KIND_REDUCED:
        ok = banded && trm && b->reduced[eye] != NULL &&
             tdc_link_trm_kind(p->frame_index, eye) == TDC_LINK_KIND_REDUCED;
        break;
    case TDC_LINK_KIND_SUBFRAME: ok = (sflags & TDC_LINK_STREAM_SUBFRAMES) && b->subframe[eye] != NULL; break;
    case TDC_LINK_KIND_MOTION:
        ok = (flags & TDC_LINK_PKT_MV_PER_SAMPLE)
                 ? ((sflags & TDC_LINK_STREAM_SAMPLE_MV) && b->sample_motion[eye])
                 : ((sflags & TDC_LINK_STREAM_MOTION) && (b->motion[eye] || b->skip_motion));
        break;
    case TDC_LINK_KIND_FOVEATED:
        /* the slot it states must be the one TRM's schedule has due */
        ok = (sflags & TDC_LINK_STREAM_FOVEATED) && b->fov_lp[eye] != NULL &&
             ((flags & TDC_LINK_PKT_FOV_REDUCED)
                  ? trm && b->reduced[eye] != NULL && tdc_link_trm_kind(p->frame_index, eye) == TDC_LINK_KIND_REDUCED
                  : b->full[eye] != NULL && (!trm || tdc_link_trm_kind(p->frame_index, eye) == TDC_LINK_KIND_FULL));
        break;
    case TDC_LINK_KIND_LAYERS:
        ok = (sflags & TDC_LINK_STREAM_LAYERS) && tdc_layer_frame_accepts(b->layers[eye], flags);
        break;
    default: /* PATTERN: with the first subframe of each 4-frame cycle */
        ok = (sflags & TDC_LINK_STREAM_SUBFRAMES) && b->pattern[eye] != NULL && (p->frame_index & 3u) == 0;
        break;
    }
    if (!ok) {
        return TDC_LINK_ERR_UNEXPECTED;
    }

    const int red_grid =
        kind == TDC_LINK_KIND_REDUCED || (kind == TDC_LINK_KIND_FOVEATED && (flags & TDC_LINK_PKT_FOV_REDUCED));
    const uint32_t want_w = red_grid ? dec->rw : dec->cfg.width;
    const uint32_t want_h = red_grid ? dec->rh : dec->cfg.height;
    if (p->width != want_w || p->height != want_h) {
        return TDC_LINK_ERR_DIMENSIONS;
    }
    /* Dimensions now equal the panel's (<= TDC_LINK_MAX_PIXELS), so the
     * expected length cannot wrap. */
    const uint32_t want_len =
        tdc_link_payload_bytes((tdc_link_kind_t)kind, (tdc_pixfmt_t)fmt, p->width, p->height, flags);
    /* STATED (FOVEATED): at least its kind header; the exact length is
     * checked against that header once the payload CRC vouches for it. */
    /* A band: its header and at least one row, at most the picture; the
     * exact length follows from the band header (tdc_band_hdr_parse). */
    if (band ? payload_len <= TDC_BAND_HDR_BYTES || payload_len - TDC_BAND_HDR_BYTES > want_len
        : ki->rule == TDC_LINK_PAYLOAD_STATED ? payload_len < TDC_FOV_HDR_BYTES
                                              : payload_len != want_len) {
        return TDC_LINK_ERR_LENGTH;
    }
    if (kind == TDC_LINK_KIND_MOTION && !(flags & TDC_LINK_PKT_MV_PER_SAMPLE) && !b->motion[eye]) {
        return LINK_SKIP_UNUSED; /* skip_motion: valid, but nothing here uses it */
    }
    if (payload_len > dec->buf.staging_bytes) {
        return TDC_LINK_ERR_LENGTH;
    }
    if (dec->have_frame) {
        if (p->frame_index < dec->frame_index) {
            return TDC_LINK_ERR_ORDER;
        }
        if (p->frame_index == dec->frame_index && (dec->frame_mask & slot_bit(kind, eye, flags))) {
            return TDC_LINK_ERR_DUPLICATE;
        }
    }
    return TDC_LINK_OK;
}

/* ------------------------------------------------------------------------
 * Row bands (tdc_band_link.h).
 * ---------------------------------------------------------------------- */
static int is_band(const tdc_link_decoder_t *dec)
{
    const tdc_link_event_t *p = &dec->pkt;
    return (p->kind == TDC_LINK_KIND_FULL || p->kind == TDC_LINK_KIND_REDUCED) && (p->flags & TDC_LINK_PKT_BAND) &&
           p->eye < dec->cfg.eyes && dec->stream_active && p->stream_id == dec->stream_id &&
           (dec->stream.flags & TDC_LINK_STREAM_BANDS);
}

/* Eye e's picture (kind, frame) is dropped whole: its event, counted once. */
static void band_drop_event(tdc_link_decoder_t *dec, uint32_t e, uint32_t kind, uint32_t frame, tdc_band_drop_t why)
{
    tdc_link_event_t ev;
    memset(&ev, 0, sizeof ev);
    ev.type = TDC_LINK_EV_ERROR;
    ev.error = TDC_LINK_ERR_BAND_DROPPED;
    ev.kind = (uint8_t)kind;
    ev.eye = (uint8_t)e;
    ev.stream_id = dec->stream_id;
    ev.flags = TDC_LINK_PKT_BAND;
    ev.frame_index = frame;
    ev.detail = (uint32_t)why;
    dec->cnt.errors[TDC_LINK_ERR_BAND_DROPPED]++;
    dec->cnt.band_drops[why]++;
    push_event(dec, &ev);
}

/* The current packet, a band (its header CRC vouches for kind, eye and
 * frame), was refused (CRC, a link check, a band reason other than FRAME
 * and DROPPED): the picture it names is dropped -- the one in flight, or,
 * if none is and may_start (not a band of a past frame or a complete
 * picture: ORDER, DUPLICATE), that picture from its start (its later
 * bands are DROPPED).  A
 * bad band naming another picture than the one in flight leaves that one
 * alone. */
static void band_bad(tdc_link_decoder_t *dec, tdc_band_drop_t why, int may_start)
{
    if (!is_band(dec)) {
        return;
    }
    const tdc_link_event_t *p = &dec->pkt;
    tdc_band_seq_t *s = &dec->band_seq[p->eye];
    if (s->state == TDC_BAND_OPEN && tdc_band_seq_is(s, p->kind, p->frame_index)) {
        s->state = TDC_BAND_DEAD;
    } else if (s->state == TDC_BAND_IDLE && may_start) {
        memset(s, 0, sizeof *s);
        s->state = TDC_BAND_DEAD;
        s->kind = p->kind;
        s->frame = p->frame_index;
    } else {
        return;
    }
    band_drop_event(dec, p->eye, p->kind, p->frame_index, why);
}

/* A new stream: pictures in flight never complete. */
static void band_reset(tdc_link_decoder_t *dec)
{
    for (uint32_t e = 0; e < dec->cfg.eyes; e++) {
        tdc_band_seq_t *s = &dec->band_seq[e];
        if (s->state == TDC_BAND_OPEN) {
            band_drop_event(dec, e, s->kind, s->frame, TDC_BAND_DROP_MISSING);
        }
        memset(s, 0, sizeof *s);
    }
    dec->band_valid = 0;
}

/* A band whose payload CRC matched: its header and its place in the eye's
 * picture.  Nothing is written; *h is the parsed header on TDC_BAND_OK. */
static tdc_band_err_t check_band(tdc_link_decoder_t *dec, tdc_band_hdr_t *h)
{
    const tdc_link_event_t *p = &dec->pkt;
    tdc_band_err_t r = tdc_band_hdr_parse(dec->buf.staging + dec->payload_base, (tdc_pixfmt_t)p->format, p->width,
                                          p->height, dec->payload_len, h);
    if (r == TDC_BAND_OK) {
        r = tdc_band_seq_check(&dec->band_seq[p->eye], p->kind, p->frame_index, p->format, h);
    }
    return r;
}

/* A complete header is in dec->hdr; its last byte was at staging offset
 * end_off - 1 if it came from a staging rescan (else end_off = NOT_STAGING). */
static void on_header(tdc_link_decoder_t *dec, uint32_t end_off)
{
    const uint8_t *h = dec->hdr;
    tdc_link_header_t ph;
    /* The magic matched byte by byte on the way in: only the CRC can fail. */
    if (tdc_link_header_unpack(h, &ph) != TDC_LINK_OK) {
        /* Corrupt header, or a false magic: rescan bytes 1..31 (the real
         * packet may begin there).  If the whole header came from the
         * staging rescan, just rewind it; otherwise replay a copy (any
         * staging rescan is used up then, so rescans never nest). */
        push_error(dec, TDC_LINK_ERR_HEADER_CRC, 0, 0);
        dec->replay_gen++;
        if (dec->hdr_in_staging && end_off != NOT_STAGING) {
            dec->replay_src = RP_STAGING;
            dec->replay_pos = dec->hdr_start + 1u;
            dec->cnt.skipped_bytes += 1u;
        } else {
            memcpy(dec->replay, h + 1, TDC_LINK_HEADER_BYTES - 1u);
            dec->replay_src = RP_HEADER;
            dec->replay_len = TDC_LINK_HEADER_BYTES - 1u;
            dec->replay_pos = 0;
            discard(dec, 1u, dec->hdr_in_staging ? 0u : NOT_STAGING);
        }
        dec->hdr_in_staging = 0;
        set_state(dec, ST_HUNT, 0);
        return;
    }
    dec->hdr_in_staging = 0;
    /* A valid header ends any run of garbage before it. */
    if (dec->garbage_run) {
        push_error(dec, TDC_LINK_ERR_GARBAGE, 0, dec->garbage_run);
        dec->garbage_run = 0;
    }
    tdc_link_event_t *p = &dec->pkt;
    memset(p, 0, sizeof *p);
    p->kind = ph.kind;
    p->eye = ph.eye;
    p->format = ph.format;
    p->stream_id = ph.stream_id;
    p->flags = ph.flags;
    p->frame_index = ph.frame_index;
    p->width = ph.width;
    p->height = ph.height;
    dec->payload_len = ph.payload_len;
    dec->payload_crc = ph.payload_crc;
    p->detail = dec->payload_len;

    const tdc_link_err_t e = check_header(dec, ph.version, dec->payload_len);
    if (e == LINK_SKIP_UNUSED) {
        /* intact header of a packet no stage uses: skip its payload, which
         * is not checked (nothing is written from it), no error */
        dec->cnt.packets_skipped++;
        dec->skip_left = dec->payload_len;
        set_state(dec, ST_SKIP, 0);
        dec->hdr_fill = 0;
        return;
    }
    if (e != TDC_LINK_OK) {
        push_error(dec, e, 1, dec->payload_len);
        if (e != TDC_LINK_ERR_STREAM && e != TDC_LINK_ERR_EYE) {
            /* a band of its picture refused */
            band_bad(dec, TDC_BAND_DROP_REFUSED, e != TDC_LINK_ERR_ORDER && e != TDC_LINK_ERR_DUPLICATE);
        }
        /* The header is intact (CRC), so its length is what was sent: skip
         * the payload.  A length beyond anything we could accept is not
         * trusted: hunt instead. */
        if (dec->payload_len == 0) {
            set_state(dec, ST_HEADER, 1);
        } else if (dec->payload_len <= dec->buf.staging_bytes) {
            dec->skip_left = dec->payload_len;
            set_state(dec, ST_SKIP, 0);
        } else {
            set_state(dec, ST_HUNT, 0);
        }
        dec->hdr_fill = 0;
        return;
    }
    dec->payload_fill = 0;
    dec->crc_state = TDC_CRC32_INIT;
    /* Found inside a staging rescan: the payload (or its start) is already
     * in place right after the header. */
    dec->payload_base = end_off == NOT_STAGING ? 0u : end_off;
    set_state(dec, ST_PAYLOAD, 0);
}

/* ------------------------------------------------------------------------
 * Commit of a packet whose payload CRC matched.
 * ---------------------------------------------------------------------- */
static tdc_link_err_t commit_stream(tdc_link_decoder_t *dec)
{
    const uint8_t *s = dec->buf.staging + dec->payload_base;
    tdc_link_stream_info_t in;
    tdc_link_stream_unpack(s, &in);

    const tdc_link_buffers_t *b = &dec->buf;
    if ((in.flags & ~(uint32_t)TDC_LINK_STREAM_KNOWN) != 0 || in.reserved != 0 || in.width != dec->cfg.width ||
        in.height != dec->cfg.height || in.eyes != dec->cfg.eyes || in.r_den == 0) {
        return TDC_LINK_ERR_STREAM_HEADER;
    }
    uint32_t rw = 0, rh = 0;
    if (in.flags & TDC_LINK_STREAM_REDUCED) {
        /* 1/4 <= r < 1 (docs/design.md §4.1, tdc_trm.h). */
        if ((uint32_t)in.r_num * 4u < in.r_den || in.r_num >= in.r_den) {
            return TDC_LINK_ERR_STREAM_HEADER;
        }
        rw = TDC_REDUCED_DIM(in.width, in.r_num, in.r_den);
        rh = TDC_REDUCED_DIM(in.height, in.r_num, in.r_den);
    } else if (in.r_num != in.r_den) {
        return TDC_LINK_ERR_STREAM_HEADER; /* r must be 1 without reduced frames */
    }
    if ((in.flags & (TDC_LINK_STREAM_SAMPLE_MV | TDC_LINK_STREAM_LAYERS)) && !(in.flags & TDC_LINK_STREAM_SUBFRAMES)) {
        return TDC_LINK_ERR_STREAM_HEADER;
    }
    if ((in.flags & TDC_LINK_STREAM_LAYER_HIST) && !(in.flags & TDC_LINK_STREAM_LAYERS)) {
        return TDC_LINK_ERR_STREAM_HEADER;
    }
    /* Foveated frames replace FULL ones, and in a TRM stream REDUCED ones
     * too (packet flag FOV_REDUCED); with subframes (which frame is
     * foveated) nothing is defined yet. */
    if ((in.flags & TDC_LINK_STREAM_FOVEATED) && (in.flags & TDC_LINK_STREAM_SUBFRAMES)) {
        return TDC_LINK_ERR_STREAM_HEADER;
    }
    /* The build must have a buffer for every stage the stream uses. */
    for (unsigned e = 0; e < in.eyes; e++) {
        if (((in.flags & TDC_LINK_STREAM_REDUCED) && (!b->reduced[e] || (size_t)rw * rh * 3u > b->reduced_bytes)) ||
            ((in.flags & TDC_LINK_STREAM_SUBFRAMES) && (!b->subframe[e] || !b->pattern[e])) ||
            ((in.flags & TDC_LINK_STREAM_MOTION) && !b->motion[e] && !b->skip_motion) ||
            ((in.flags & TDC_LINK_STREAM_SAMPLE_MV) && !b->sample_motion[e]) ||
            ((in.flags & TDC_LINK_STREAM_LAYERS) && !b->layers[e]) ||
            ((in.flags & TDC_LINK_STREAM_FOVEATED) && (!b->fov_lp[e] || !b->full[e]))) {
            return TDC_LINK_ERR_STREAM_HEADER;
        }
    }
    /* A repeated identical header (sent for late joiners) keeps the
     * sequence state; anything else starts a new stream. */
    if (!(dec->stream_active && dec->stream_id == dec->pkt.stream_id && !memcmp(&in, &dec->stream, sizeof in))) {
        dec->stream_active = 1;
        dec->stream_id = dec->pkt.stream_id;
        dec->stream = in;
        dec->rw = (uint16_t)rw;
        dec->rh = (uint16_t)rh;
        dec->have_frame = 0;
        dec->frame_mask = 0;
        dec->frame_index = 0;
        dec->fov_valid = 0;
        band_reset(dec);
    }
    return TDC_LINK_OK;
}

/* A FOVEATED payload whose CRC matched: its foveation header against the
 * configured panel, the length it states, this build's buffers.  Nothing
 * is written; *h is the parsed header on TDC_LINK_OK. */
static tdc_link_err_t check_foveated(tdc_link_decoder_t *dec, uint32_t eye, tdc_fov_hdr_t *h)
{
    const uint8_t *s = dec->buf.staging + dec->payload_base;
    /* against the slot's grid: the panel, or the reduced grid (check_header
     * matched the packet's width x height to it) */
    tdc_fov_hdr_err_t r = tdc_fov_hdr_parse(s, dec->pkt.width, dec->pkt.height, h);
    if (r == TDC_FOV_HDR_OK) {
        r = tdc_fov_payload_check(h, dec->payload_len - TDC_FOV_HDR_BYTES);
    }
    if (r != TDC_FOV_HDR_OK) {
        dec->cnt.fov_refused[r]++;
        return TDC_LINK_ERR_FOVEATION;
    }
    const tdc_link_buffers_t *b = &dec->buf;
    const size_t lp = (size_t)h->p.lp_w * h->p.lp_h;
    /* vectors for a build without the TAA buffer, or in a TRM stream: each
     * slot's stage sees every other frame of its eye, its history would be
     * two frames old and the vectors reach one (docs/link-protocol.md §2.2) */
    if ((h->flags & TDC_FOV_FLAG_MV) && (!b->fov_mv[eye] || (dec->stream.flags & TDC_LINK_STREAM_REDUCED))) {
        return TDC_LINK_ERR_UNEXPECTED;
    }
    if (lp * 3u > b->fov_lp_bytes || ((h->flags & TDC_FOV_FLAG_MV) && lp * 2u > b->fov_mv_count)) {
        return TDC_LINK_ERR_LENGTH; /* a larger delta than this build's buffers hold */
    }
    return TDC_LINK_OK;
}

/* Reduced frames due in frames [from, to) that were not received; frame
 * `from` is the current frame with slots `mask`. */
static uint32_t count_missing_reduced(const tdc_link_decoder_t *dec, uint32_t from, uint32_t to)
{
    uint64_t missing = 0;
    for (uint32_t e = 0; e < dec->cfg.eyes; e++) {
        if (tdc_link_trm_kind(from, e) == TDC_LINK_KIND_REDUCED &&
            !(dec->frame_mask & slot_bit(TDC_LINK_KIND_REDUCED, e, 0))) {
            missing++;
        }
    }
    if (to - from > 1u) {
        const uint64_t a = (uint64_t)from + 1u, b = (uint64_t)to - 1u;           /* frames never seen */
        missing += dec->cfg.eyes == 2 ? (b - a + 1u) : ((b + 1u) / 2u - a / 2u); /* odd frames */
    }
    return missing > UINT32_MAX ? UINT32_MAX : (uint32_t)missing;
}

/* Unpack dispatch limited to the compiled-in formats, so a board's mask
 * removes the other unpackers from its image. */
static void unpack_pixels(tdc_pixfmt_t fmt, const uint8_t *src, uint32_t w, uint32_t h, uint8_t *dst, uint32_t stride)
{
    (void)src; /* unused when the mask is empty */
    (void)w;
    (void)h;
    (void)dst;
    (void)stride;
    switch (fmt) {
#if (TDC_LINK_FORMAT_MASK >> 1) & 1u
    case TDC_PIXFMT_RGB888: tdc_pixfmt_unpack_rgb888(src, w, h, dst, stride); break;
#endif
#if (TDC_LINK_FORMAT_MASK >> 2) & 1u
    case TDC_PIXFMT_RGB565: tdc_pixfmt_unpack_rgb565(src, w, h, dst, stride); break;
#endif
#if (TDC_LINK_FORMAT_MASK >> 3) & 1u
    case TDC_PIXFMT_RGB30: tdc_pixfmt_unpack_rgb30(src, w, h, dst, stride); break;
#endif
#if (TDC_LINK_FORMAT_MASK >> 4) & 1u
    case TDC_PIXFMT_YCBCR420: tdc_pixfmt_unpack_ycbcr420(src, w, h, dst, stride); break;
#endif
    default: /* unreachable: check_header rejected it */ break;
    }
}

static void unpack_le16(const uint8_t *src, int16_t *dst, size_t count)
{
    for (size_t i = 0; i < count; i++) {
        dst[i] = tdc_get_le16s(src + 2u * i);
    }
}

/* The payload is complete; src_end = staging offset after its last byte if
 * it was collected inside a staging rescan, else NOT_STAGING. */
static void on_payload(tdc_link_decoder_t *dec, uint32_t src_end)
{
    tdc_link_event_t *p = &dec->pkt;
    set_state(dec, ST_HEADER, 1);
    dec->hdr_fill = 0;
    if (tdc_crc32_final(dec->crc_state) != dec->payload_crc) {
        push_error(dec, TDC_LINK_ERR_CRC, 1, dec->payload_len);
        band_bad(dec, TDC_BAND_DROP_CRC, 1);
        /* Rescan the payload for a packet start; inside a staging rescan
         * the rest of that rescan follows it contiguously. */
        dec->replay_gen++;
        dec->replay_src = RP_STAGING;
        dec->replay_pos = dec->payload_base;
        if (src_end == NOT_STAGING) {
            dec->replay_len = dec->payload_base + dec->payload_len;
        }
        set_state(dec, ST_HUNT, 0);
        return;
    }
    const uint32_t kind = p->kind, eye = p->eye;
    if (kind == TDC_LINK_KIND_STREAM) {
        const tdc_link_err_t e = commit_stream(dec);
        if (e != TDC_LINK_OK) {
            push_error(dec, e, 1, dec->payload_len);
            return;
        }
    } else {
        tdc_fov_hdr_t fh;
        memset(&fh, 0, sizeof fh);
        tdc_band_hdr_t bh;
        memset(&bh, 0, sizeof bh);
        /* check_header: a band is FULL or REDUCED of a BANDS stream */
        const int band = (kind == TDC_LINK_KIND_FULL || kind == TDC_LINK_KIND_REDUCED) && (p->flags & TDC_LINK_PKT_BAND);
        if (band) {
            const tdc_band_err_t be = check_band(dec, &bh);
            if (be != TDC_BAND_OK) {
                dec->cnt.band_errors[be]++;
                push_error(dec, TDC_LINK_ERR_BAND, 1, (uint32_t)be);
                if (be != TDC_BAND_ERR_FRAME && be != TDC_BAND_ERR_DROPPED) {
                    band_bad(dec, TDC_BAND_DROP_REFUSED, 1);
                }
                return;
            }
            tdc_band_seq_t *bs = &dec->band_seq[eye];
            if (bh.index == 0 && bs->state == TDC_BAND_OPEN) {
                /* the eye's next picture starts: the one in flight lost its last band */
                band_drop_event(dec, eye, bs->kind, bs->frame, TDC_BAND_DROP_MISSING);
            }
        }
        if (kind == TDC_LINK_KIND_FOVEATED) {
            const tdc_link_err_t e = check_foveated(dec, eye, &fh);
            if (e != TDC_LINK_OK) {
                push_error(dec, e, 1, dec->payload_len);
                return;
            }
        }
        if (kind == TDC_LINK_KIND_LAYERS) {
            /* contents the header cannot vouch for: refused before the
             * sequence advances or anything is written */
            const tdc_layer_err_t le = tdc_layer_payload_check(dec->buf.staging + dec->payload_base, dec->payload_len,
                                                               p->flags, p->width, p->height);
            if (le != TDC_LAYER_OK) {
                dec->cnt.layer_errors[le]++;
                push_error(dec, TDC_LINK_ERR_LAYERS, 1, (uint32_t)le);
                return;
            }
        }
        /* Sequence: advancing to a newer frame closes the current one. */
        if (!dec->have_frame || p->frame_index > dec->frame_index) {
            if (dec->have_frame && (dec->stream.flags & TDC_LINK_STREAM_REDUCED)) {
                const uint32_t miss = count_missing_reduced(dec, dec->frame_index, p->frame_index);
                if (miss) {
                    tdc_link_event_t ev;
                    memset(&ev, 0, sizeof ev);
                    ev.type = TDC_LINK_EV_ERROR;
                    ev.error = TDC_LINK_ERR_MISSING_REDUCED;
                    ev.kind = TDC_LINK_KIND_REDUCED;
                    ev.stream_id = dec->stream_id;
                    ev.frame_index = dec->frame_index;
                    ev.detail = miss;
                    dec->cnt.errors[TDC_LINK_ERR_MISSING_REDUCED]++;
                    dec->cnt.missing_reduced_frames += miss;
                    push_event(dec, &ev);
                }
            }
            dec->have_frame = 1;
            dec->frame_index = p->frame_index;
            dec->frame_mask = 0;
        }
        /* a banded picture fills its slot with its last band */
        if (!band || tdc_band_seq_accept(&dec->band_seq[eye], kind, p->frame_index, p->format, &bh)) {
            dec->frame_mask |= slot_bit(kind, eye, p->flags);
        }

        const uint8_t *s = dec->buf.staging + dec->payload_base;
        uint32_t rows = p->height, row0 = 0;
        if (band) {
            s += TDC_BAND_HDR_BYTES;
            rows = bh.rows;
            row0 = bh.first_row;
            dec->band[eye] = bh;
            dec->band_valid |= (uint8_t)(1u << eye);
            dec->cnt.bands_ok++;
        }
        const tdc_pixfmt_t fmt = (tdc_pixfmt_t)p->format;
        const tdc_link_buffers_t *b = &dec->buf;
        const uint32_t tx = TDC_TILES(p->width), ty = TDC_TILES(p->height);
        switch (kind) {
        case TDC_LINK_KIND_FULL:
            if (b->defer_full) {
                /* left in staging for tdc_link_unpack_full() */
                dec->staged_full = 1;
                dec->staged_fmt = (uint8_t)fmt;
                dec->staged_w = p->width;
                dec->staged_h = (uint16_t)rows;
                dec->staged_row = (uint16_t)row0;
                dec->staged_base = dec->payload_base + (band ? TDC_BAND_HDR_BYTES : 0u);
            } else {
                unpack_pixels(fmt, s, p->width, rows, b->full[eye] + (size_t)row0 * b->full_stride, b->full_stride);
            }
            break;
        case TDC_LINK_KIND_REDUCED:
            unpack_pixels(fmt, s, p->width, rows, b->reduced[eye] + (size_t)row0 * p->width * 3u,
                          (uint32_t)p->width * 3u);
            break;
        case TDC_LINK_KIND_SUBFRAME: unpack_pixels(fmt, s, tx, ty, b->subframe[eye], tx * 3u); break;
        case TDC_LINK_KIND_MOTION:
            if (p->flags & TDC_LINK_PKT_MV_PER_SAMPLE) {
                unpack_le16(s, b->sample_motion[eye], (size_t)tx * ty * 2u);
            } else {
                unpack_le16(s, b->motion[eye], (size_t)p->width * p->height * 2u);
            }
            break;
        case TDC_LINK_KIND_FOVEATED:
            /* the disk pixels into the slot's picture: the frame buffer, or the reduced buffer */
            tdc_fov_unpack(&fh, s + TDC_FOV_HDR_BYTES, b->fov_lp[eye], (size_t)fh.p.lp_w * 3u, b->fov_mv[eye],
                           (size_t)fh.p.lp_w * 2u,
                           (p->flags & TDC_LINK_PKT_FOV_REDUCED) ? b->reduced[eye] : b->full[eye],
                           (p->flags & TDC_LINK_PKT_FOV_REDUCED) ? (size_t)p->width * 3u : b->full_stride);
            dec->fov[eye] = fh;
            dec->fov_valid |= (uint8_t)(1u << eye);
            break;
        case TDC_LINK_KIND_LAYERS: tdc_layer_unpack(s, p->flags, p->width, p->height, b->layers[eye]); break;
        default: /* PATTERN */ memcpy(b->pattern[eye], s, dec->payload_len); break;
        }
    }
    dec->cnt.packets_ok++;
    dec->cnt.packets_by_kind[kind]++;
    tdc_link_event_t ev = *p;
    ev.type = TDC_LINK_EV_PACKET;
    ev.error = TDC_LINK_OK;
    push_event(dec, &ev);
}

/* ------------------------------------------------------------------------
 * Byte processing: consumes bytes until an event is queued or n is used up.
 * src_off = staging offset of p[0] when p points into a staging rescan,
 * else NOT_STAGING (new input or the header replay).
 * ---------------------------------------------------------------------- */
static size_t step(tdc_link_decoder_t *dec, const uint8_t *p, size_t n, uint32_t src_off)
{
    size_t i = 0;
    if (n) {
        /* bytes are processed: a deferred FULL payload may be overwritten
         * (step() runs only once every event was returned) */
        dec->staged_full = 0;
    }
    while (i < n && dec->ev_count == 0) {
        switch (dec->state & ST_MASK) {
        case ST_HUNT: {
            const uint8_t *t = (const uint8_t *)memchr(p + i, 'T', n - i);
            const size_t skip = t ? (size_t)(t - (p + i)) : n - i;
            discard(dec, skip, src_off);
            i += skip;
            if (t) {
                dec->hdr[0] = 'T';
                dec->hdr_fill = 1;
                dec->hdr_in_staging = src_off != NOT_STAGING;
                dec->hdr_start = src_off != NOT_STAGING ? src_off + (uint32_t)i : 0u;
                set_state(dec, ST_HEADER, 0);
                i++;
            }
            break;
        }
        case ST_HEADER: {
            if (dec->hdr_fill == 0) {
                /* A packet boundary: remember where, for a rewind. */
                dec->hdr_in_staging = src_off != NOT_STAGING;
                dec->hdr_start = src_off != NOT_STAGING ? src_off + (uint32_t)i : 0u;
            }
            if (dec->hdr_fill < 4u) {
                if (p[i] != tdc_link_magic_bytes[dec->hdr_fill]) {
                    /* Not a packet start.  At an expected boundary this
                     * is a loss of sync; the bytes matched so far are
                     * passed over; p[i] itself is rescanned by HUNT. */
                    if (dec->state & ST_SYNCED) {
                        push_error(dec, TDC_LINK_ERR_MAGIC, 0, 0);
                    }
                    discard(dec, dec->hdr_fill, dec->hdr_in_staging ? 0u : NOT_STAGING);
                    dec->hdr_fill = 0;
                    dec->hdr_in_staging = 0;
                    set_state(dec, ST_HUNT, 0);
                    break;
                }
                dec->hdr[dec->hdr_fill++] = p[i++];
                break;
            }
            size_t k = TDC_LINK_HEADER_BYTES - dec->hdr_fill;
            if (k > n - i) {
                k = n - i;
            }
            memcpy(dec->hdr + dec->hdr_fill, p + i, k);
            dec->hdr_fill = (uint8_t)(dec->hdr_fill + k);
            i += k;
            if (dec->hdr_fill == TDC_LINK_HEADER_BYTES) {
                dec->hdr_fill = 0;
                on_header(dec, src_off != NOT_STAGING ? src_off + (uint32_t)i : NOT_STAGING);
            }
            break;
        }
        case ST_PAYLOAD: {
            size_t k = dec->payload_len - dec->payload_fill;
            if (k > n - i) {
                k = n - i;
            }
            /* CRC first: when p points into staging the bytes are already
             * in place (src_off + i == payload_base + payload_fill). */
            dec->crc_state = tdc_crc32_update(dec->crc_state, p + i, k);
            if (src_off == NOT_STAGING) {
                if (dec->payload_base != 0) {
                    /* The rescan that held the start of this payload is
                     * used up: move what we have to the front. */
                    memmove(dec->buf.staging, dec->buf.staging + dec->payload_base, dec->payload_fill);
                    dec->payload_base = 0;
                }
                memcpy(dec->buf.staging + dec->payload_fill, p + i, k);
            }
            dec->payload_fill += (uint32_t)k;
            i += k;
            if (dec->payload_fill == dec->payload_len) {
                on_payload(dec, src_off != NOT_STAGING ? src_off + (uint32_t)i : NOT_STAGING);
            }
            break;
        }
        default: { /* ST_SKIP */
            size_t k = dec->skip_left;
            if (k > n - i) {
                k = n - i;
            }
            dec->skip_left -= (uint32_t)k;
            dec->cnt.skipped_bytes += k;
            i += k;
            if (dec->skip_left == 0) {
                dec->hdr_fill = 0;
                set_state(dec, ST_HEADER, 1);
            }
            break;
        }
        }
    }
    return i;
}

tdc_status_t tdc_link_unpack_full(const tdc_link_decoder_t *dec, uint8_t *dst, uint32_t stride)
{
    if (!dec || !dst) {
        return TDC_ERR_ARG;
    }
    if (!dec->staged_full) {
        return TDC_ERR_STATE;
    }
    if (stride < (uint32_t)dec->staged_w * 3u) {
        return TDC_ERR_ARG;
    }
    unpack_pixels((tdc_pixfmt_t)dec->staged_fmt, dec->buf.staging + dec->staged_base, dec->staged_w, dec->staged_h,
                  dst + (size_t)dec->staged_row * stride, stride);
    return TDC_OK;
}

static int pop_event(tdc_link_decoder_t *dec, tdc_link_event_t *ev)
{
    if (dec->ev_count == 0) {
        return 0;
    }
    *ev = dec->ev[dec->ev_head];
    dec->ev_head = (uint8_t)((dec->ev_head + 1u) % TDC_LINK_EVENT_QUEUE);
    dec->ev_count--;
    return 1;
}

size_t tdc_link_feed(tdc_link_decoder_t *dec, const uint8_t *bytes, size_t n, tdc_link_event_t *ev)
{
    size_t used = 0;
    for (;;) {
        if (pop_event(dec, ev)) {
            return used;
        }
        if (dec->replay_src != RP_NONE && dec->replay_pos < dec->replay_len) {
            /* Bytes of a rejected header or payload, rescanned before new
             * input.  If the step sets up a new rescan (generation bumped)
             * its position is already right. */
            const uint32_t gen = dec->replay_gen;
            const int staging = dec->replay_src == RP_STAGING;
            const uint8_t *src = staging ? dec->buf.staging : dec->replay;
            const size_t k = step(dec, src + dec->replay_pos, (size_t)(dec->replay_len - dec->replay_pos),
                                  staging ? dec->replay_pos : NOT_STAGING);
            if (dec->replay_gen == gen) {
                dec->replay_pos += (uint32_t)k;
                if (dec->replay_pos >= dec->replay_len) {
                    dec->replay_src = RP_NONE;
                }
            }
            continue;
        }
        if (used == n) {
            break;
        }
        const size_t k = step(dec, bytes + used, n - used, NOT_STAGING);
        used += k;
        dec->cnt.bytes_in += k;
    }
    memset(ev, 0, sizeof *ev);
    ev->type = TDC_LINK_EV_NONE;
    return used;
}
