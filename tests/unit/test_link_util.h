/*
 * test_link_util.h - shared helpers of the link tests (tests/unit/test_link*.c):
 * a decoder over static buffers for a W x H panel, an event log, and
 * hashes of every pipeline buffer.  Header-only (static functions) so each
 * test stays a single-source program.
 */
#ifndef TEST_LINK_UTIL_H
#define TEST_LINK_UTIL_H

#include <stdint.h>
#include <string.h>

#include "link/tdc_link_gen.h"
#include "tdc_link.h"

#define LT_MAX_W 64
#define LT_MAX_H 48
#define LT_MAX_EVENTS 4096

typedef struct {
    uint8_t staging[TDC_LINK_STAGING_BYTES(LT_MAX_W, LT_MAX_H)];
    uint8_t full[2][TDC_LINK_FRAME_BYTES(LT_MAX_W, LT_MAX_H)];
    uint8_t reduced[2][TDC_LINK_FRAME_BYTES(LT_MAX_W, LT_MAX_H)];
    uint8_t subframe[2][TDC_LINK_SUBFRAME_BYTES(LT_MAX_W, LT_MAX_H)];
    int16_t motion[2][TDC_LINK_MOTION_COUNT(LT_MAX_W, LT_MAX_H)];
    int16_t sample_motion[2][TDC_LINK_SAMPLE_MOTION_COUNT(LT_MAX_W, LT_MAX_H)];
    uint8_t pattern[2][TDC_PATTERN_BYTES(LT_MAX_W, LT_MAX_H)];
    uint8_t fov_lp[2][TDC_LINK_FRAME_BYTES(LT_MAX_W, LT_MAX_H)]; /* delta <= 1: lp_w x lp_h <= W x H */
    int16_t fov_mv[2][TDC_LINK_MOTION_COUNT(LT_MAX_W, LT_MAX_H)];
    tdc_link_decoder_t dec;
    tdc_link_event_t ev[LT_MAX_EVENTS];
    uint32_t nev;
} lt_rig_t;

static inline uint64_t lt_fnv(uint64_t h, const void *p, size_t n)
{
    const uint8_t *b = (const uint8_t *)p;
    for (size_t i = 0; i < n; i++) {
        h = (h ^ b[i]) * 0x100000001b3ULL;
    }
    return h;
}

/* A decoder's buffers with only its staging: each test then wires the
 * buffers its streams need (and nothing else, so the decoder refuses the
 * rest). */
static inline tdc_link_buffers_t lt_buffers(uint8_t *staging, size_t staging_bytes)
{
    tdc_link_buffers_t b;
    memset(&b, 0, sizeof b);
    b.staging = staging;
    b.staging_bytes = staging_bytes;
    return b;
}

/* Fills buffers with a recognisable pattern so "unchanged" is meaningful. */
static inline int lt_init(lt_rig_t *r, uint16_t w, uint16_t h, uint8_t eyes)
{
    memset(r->full, 0xA5, sizeof r->full);
    memset(r->reduced, 0x5A, sizeof r->reduced);
    memset(r->subframe, 0x33, sizeof r->subframe);
    memset(r->motion, 0x44, sizeof r->motion);
    memset(r->sample_motion, 0x55, sizeof r->sample_motion);
    memset(r->pattern, 0x66, sizeof r->pattern);
    memset(r->fov_lp, 0x77, sizeof r->fov_lp);
    memset(r->fov_mv, 0x88, sizeof r->fov_mv);
    tdc_link_config_t cfg = {w, h, eyes};
    tdc_link_buffers_t b = lt_buffers(r->staging, sizeof r->staging);
    b.full_stride = (uint32_t)w * 3u;
    b.reduced_bytes = sizeof r->reduced[0];
    b.fov_lp_bytes = sizeof r->fov_lp[0];
    b.fov_mv_count = sizeof r->fov_mv[0] / sizeof r->fov_mv[0][0];
    for (int e = 0; e < 2; e++) {
        b.full[e] = r->full[e];
        b.reduced[e] = r->reduced[e];
        b.subframe[e] = r->subframe[e];
        b.motion[e] = r->motion[e];
        b.sample_motion[e] = r->sample_motion[e];
        b.pattern[e] = r->pattern[e];
        b.fov_lp[e] = r->fov_lp[e];
        b.fov_mv[e] = r->fov_mv[e];
    }
    r->nev = 0;
    return tdc_link_decoder_init(&r->dec, &cfg, &b);
}

/* A stream header for a w x h panel (the fields every test sets). */
static inline tdc_link_stream_info_t lt_info(uint32_t flags, uint16_t w, uint16_t h, uint8_t eyes, uint16_t r_num,
                                             uint16_t r_den, uint16_t hz)
{
    const tdc_link_stream_info_t in = {
        .flags = flags,
        .r_num = r_num,
        .r_den = r_den,
        .width = w,
        .height = h,
        .eyes = eyes,
        .refresh_hz = hz,
    };
    return in;
}

/* The samples of a foveated picture of geometry g in payload order (lp
 * samples, then the disk) and the lp samples' vectors, pseudo-random from
 * seed (an LCG: the same bytes on every run).  Returns the sample count;
 * samples holds 3 bytes, mvs 2 int16 per sample. */
static inline size_t lt_fov_samples(const tdc_fov_geom_t *g, uint32_t seed, uint8_t *samples, int16_t *mvs)
{
    const size_t nlp = (size_t)(g->lp_w - g->u0) * g->lp_h, n = nlp + tdc_fov_disk_pixels(g);
    uint32_t s = seed;
    for (size_t i = 0; i < n * 3u; i++) {
        s = s * 1664525u + 1013904223u;
        samples[i] = (uint8_t)(s >> 24);
    }
    for (size_t i = 0; i < nlp * 2u; i++) {
        s = s * 1664525u + 1013904223u;
        mvs[i] = (int16_t)((int32_t)(s >> 20) - 2048);
    }
    return n;
}

/* Hash of every pipeline buffer (what the display could show or use). */
static inline uint64_t lt_hash_all(const lt_rig_t *r)
{
    uint64_t h = 0xcbf29ce484222325ULL;
    h = lt_fnv(h, r->full, sizeof r->full);
    h = lt_fnv(h, r->reduced, sizeof r->reduced);
    h = lt_fnv(h, r->subframe, sizeof r->subframe);
    h = lt_fnv(h, r->motion, sizeof r->motion);
    h = lt_fnv(h, r->sample_motion, sizeof r->sample_motion);
    h = lt_fnv(h, r->pattern, sizeof r->pattern);
    h = lt_fnv(h, r->fov_lp, sizeof r->fov_lp);
    h = lt_fnv(h, r->fov_mv, sizeof r->fov_mv);
    return h;
}

/* Feeds n bytes in chunks: chunk = 0 whole, > 0 fixed size, < 0 random
 * sizes 1..-chunk from seed.  Logs every event.  Returns bytes consumed. */
static inline size_t lt_feed(lt_rig_t *r, const uint8_t *p, size_t n, int chunk, uint32_t seed)
{
    size_t pos = 0;
    uint32_t s = seed | 1u;
    while (pos < n || r->dec.ev_count) {
        size_t c = n - pos;
        if (chunk > 0 && (size_t)chunk < c) {
            c = (size_t)chunk;
        } else if (chunk < 0) {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            const size_t k = 1u + s % (uint32_t)(-chunk);
            c = k < c ? k : c;
        }
        tdc_link_event_t ev;
        pos += tdc_link_feed(&r->dec, p + pos, c, &ev);
        if (ev.type != TDC_LINK_EV_NONE && r->nev < LT_MAX_EVENTS) {
            r->ev[r->nev++] = ev;
        }
    }
    return pos;
}

static inline uint32_t lt_count(const lt_rig_t *r, uint32_t from, int type, int code)
{
    uint32_t n = 0;
    for (uint32_t i = from; i < r->nev; i++) {
        if (r->ev[i].type == type && (type != TDC_LINK_EV_ERROR || r->ev[i].error == code)) {
            n++;
        }
    }
    return n;
}

/* The packet header of a hand-built FOVEATED packet (stream 7; the tests
 * encode it with tdc_link_encode_raw, so CRCs stay valid). */
static inline tdc_link_header_t lt_fov_header(uint8_t eye, uint8_t fmt, uint16_t flags, uint32_t frame, uint16_t w,
                                              uint16_t h)
{
    const tdc_link_header_t f = {
        .version = TDC_LINK_VERSION,
        .kind = TDC_LINK_KIND_FOVEATED,
        .eye = eye,
        .format = fmt,
        .stream_id = 7,
        .flags = flags,
        .frame_index = frame,
        .width = w,
        .height = h,
    };
    return f;
}

/* A refused FOVEATED packet (cmocka tests; the caller includes cmocka.h):
 * since event ev0 exactly one error err and no packet, err counted once,
 * the foveation-header reason (0: none) counted alone, every buffer as
 * hashed before (h0) and the last good foveation header kept. */
#ifdef cmocka_unit_test
static inline void lt_expect_fov_refused(const lt_rig_t *r, uint32_t ev0, tdc_link_err_t err, int reason, uint64_t h0,
                                         const tdc_fov_hdr_t *kept)
{
    assert_int_equal(lt_count(r, ev0, TDC_LINK_EV_ERROR, err), 1);
    assert_int_equal(lt_count(r, ev0, TDC_LINK_EV_PACKET, 0), 0);
    assert_int_equal(tdc_link_error_count(&r->dec, err), 1);
    for (int k = 1; k < TDC_FOV_HDR_COUNT; k++) {
        assert_int_equal(tdc_link_counters(&r->dec)->fov_refused[k], k == reason ? 1u : 0u);
    }
    assert_true(lt_hash_all(r) == h0); /* the last good frame is kept, nothing written */
    assert_memory_equal(tdc_link_fov(&r->dec, 0), kept, sizeof *kept);
}
#endif

#endif