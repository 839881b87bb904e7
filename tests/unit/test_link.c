/*
 * test_link.c - link protocol: encoder -> decoder round trips for every
 * pixel format and packet kind at odd sizes, one malformed packet per error
 * code (error event, counter, buffers unchanged, resynchronisation),
 * chunking invariance, and sequencing (order, duplicates, missing reduced
 * frames, stream headers).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include <stdio.h>
#include <stdlib.h>

#include "tdc_crc32.h"
#include "tdc_link_encode.h"
#include "link/tdc_link_gen.h"
#include "tdc_link.h"
#include "tdc_trm.h"
#include "test_link_util.h"

static lt_rig_t rig, rig2;
static uint8_t stream[1 << 20], stream2[1 << 20], pkt[1 << 16], pkt2[1 << 16];
static uint32_t scratch[LT_MAX_W * LT_MAX_H];
static uint8_t src[LT_MAX_W * LT_MAX_H * 3], expect[LT_MAX_W * LT_MAX_H * 3];

static const tdc_pixfmt_t all_fmts[] = {TDC_PIXFMT_RGB888, TDC_PIXFMT_RGB565, TDC_PIXFMT_RGB30, TDC_PIXFMT_YCBCR420};

/* What the decoder must produce from an RGB888 source packed in fmt:
 * derived from the format definitions, not from the decoder code. */
static void expected_rgb(tdc_pixfmt_t fmt, const uint8_t *s, uint32_t w, uint32_t h, uint8_t *out)
{
    static uint8_t packed[LT_MAX_W * LT_MAX_H * 4];
    tdc_pixfmt_pack(fmt, s, w, h, w * 3u, packed);
    const uint32_t cw = (w + 1u) / 2u, ch = (h + 1u) / 2u;
    for (uint32_t y = 0; y < h; y++) {
        for (uint32_t x = 0; x < w; x++) {
            const uint8_t *p = s + 3u * (w * y + x);
            uint8_t *o = out + 3u * (w * y + x);
            switch (fmt) {
            case TDC_PIXFMT_RGB888: memcpy(o, p, 3); break;
            case TDC_PIXFMT_RGB565: { /* 5/6/5-bit round, then bit replication */
                const unsigned r5 = (p[0] * 31u + 127u) / 255u, g6 = (p[1] * 63u + 127u) / 255u,
                               b5 = (p[2] * 31u + 127u) / 255u;
                o[0] = (uint8_t)(r5 << 3 | r5 >> 2);
                o[1] = (uint8_t)(g6 << 2 | g6 >> 4);
                o[2] = (uint8_t)(b5 << 3 | b5 >> 2);
                break;
            }
            case TDC_PIXFMT_RGB30: /* 8 -> 10 -> 8 bits is lossless */ memcpy(o, p, 3); break;
            default: { /* nearest chroma of the pixel's 2x2 block */
                const uint8_t yv = packed[w * y + x];
                const uint8_t cb = packed[w * h + cw * (y / 2u) + x / 2u];
                const uint8_t cr = packed[w * h + cw * ch + cw * (y / 2u) + x / 2u];
                tdc_pixfmt_ycbcr_to_rgb(yv, cb, cr, o);
                break;
            }
            }
        }
    }
}

static tdc_link_stream_info_t info_of(uint32_t flags, uint16_t w, uint16_t h, uint8_t eyes, uint16_t rn, uint16_t rd)
{
    return lt_info(flags, w, h, eyes, rn, rd, 120);
}

/* ------------------------------------------------------------------------
 * Round trips.
 * ---------------------------------------------------------------------- */
static void round_trip_frames(uint16_t w, uint16_t h, uint8_t eyes, uint16_t rn, uint16_t rd)
{
    for (size_t fi = 0; fi < sizeof all_fmts / sizeof all_fmts[0]; fi++) {
        const tdc_pixfmt_t fmt = all_fmts[fi];
        tdc_link_gen_opts_t o;
        memset(&o, 0, sizeof o);
        o.stream_id = 3;
        o.info = info_of(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_MOTION, w, h, eyes, rn, rd);
        o.fmt = fmt;
        o.frames = 4;
        o.seed = 77u + (uint32_t)fi;
        o.with_stream_header = 1;
        tdc_link_gen_packet_t pk[64];
        uint32_t npk = 0;
        const size_t n =
            tdc_link_gen_stream(stream, sizeof stream, &o, (uint8_t *)scratch, sizeof scratch, pk, 64, &npk);
        assert_true(n > 0);
        assert_int_equal(lt_init(&rig, w, h, eyes), TDC_OK);
        const uint32_t rw = TDC_REDUCED_DIM(w, rn, rd), rh = TDC_REDUCED_DIM(h, rn, rd);
        /* Packet by packet: check each buffer right after its event. */
        for (uint32_t i = 0; i < npk; i++) {
            const uint32_t before = rig.nev;
            assert_int_equal(lt_feed(&rig, stream + pk[i].offset, pk[i].size, 0, 0), pk[i].size);
            assert_int_equal(rig.nev, before + 1);
            const tdc_link_event_t *ev = &rig.ev[before];
            assert_int_equal(ev->type, TDC_LINK_EV_PACKET);
            assert_int_equal(ev->kind, pk[i].kind);
            assert_int_equal(ev->eye, pk[i].eye);
            assert_int_equal(ev->frame_index, pk[i].frame);
            const uint32_t e = ev->eye, f = ev->frame_index;
            if (ev->kind == TDC_LINK_KIND_FULL) {
                tdc_link_gen_rgb(src, w, h, f, e, o.seed);
                expected_rgb(fmt, src, w, h, expect);
                assert_memory_equal(rig.full[e], expect, (size_t)w * h * 3u);
            } else if (ev->kind == TDC_LINK_KIND_REDUCED) {
                assert_int_equal(ev->width, rw);
                assert_int_equal(ev->height, rh);
                tdc_link_gen_rgb(src, rw, rh, f, e, o.seed);
                expected_rgb(fmt, src, rw, rh, expect);
                assert_memory_equal(rig.reduced[e], expect, (size_t)rw * rh * 3u);
            } else if (ev->kind == TDC_LINK_KIND_MOTION) {
                static int16_t mv[LT_MAX_W * LT_MAX_H * 2];
                tdc_link_gen_mv(mv, (size_t)w * h * 2u, f, e, o.seed);
                assert_memory_equal(rig.motion[e], mv, (size_t)w * h * 4u);
            }
        }
        for (int k = 1; k < TDC_LINK_ERR_COUNT; k++) {
            assert_int_equal(tdc_link_error_count(&rig.dec, (tdc_link_err_t)k), 0);
        }
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, npk);
    }
}

static void test_round_trip_trm_odd_sizes(void **state)
{
    (void)state;
    round_trip_frames(37, 23, 2, 1, 2);
    round_trip_frames(37, 23, 1, 3, 4);
    round_trip_frames(1, 1, 1, 1, 2);
    round_trip_frames(3, 5, 2, 1, 4);
    round_trip_frames(LT_MAX_W - 1, LT_MAX_H - 1, 2, 2, 3);
}

static void round_trip_subframes(uint16_t w, uint16_t h, uint8_t eyes)
{
    const uint32_t tx = TDC_TILES(w), ty = TDC_TILES(h);
    for (size_t fi = 0; fi < sizeof all_fmts / sizeof all_fmts[0]; fi++) {
        const tdc_pixfmt_t fmt = all_fmts[fi];
        tdc_link_gen_opts_t o;
        memset(&o, 0, sizeof o);
        o.stream_id = 9;
        o.info = info_of(TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_SAMPLE_MV | TDC_LINK_STREAM_MOTION |
                             TDC_LINK_STREAM_MIRRORS,
                         w, h, eyes, 1, 1);
        o.fmt = fmt;
        o.frames = 6;
        o.seed = 1234u + (uint32_t)fi;
        o.with_stream_header = 1;
        tdc_link_gen_packet_t pk[128];
        uint32_t npk = 0;
        const size_t n =
            tdc_link_gen_stream(stream, sizeof stream, &o, (uint8_t *)scratch, sizeof scratch, pk, 128, &npk);
        assert_true(n > 0);
        assert_int_equal(lt_init(&rig, w, h, eyes), TDC_OK);
        uint32_t seen[TDC_LINK_KIND_LAST + 1] = {0};
        for (uint32_t i = 0; i < npk; i++) {
            const uint32_t before = rig.nev;
            lt_feed(&rig, stream + pk[i].offset, pk[i].size, 0, 0);
            assert_int_equal(rig.nev, before + 1);
            const tdc_link_event_t *ev = &rig.ev[before];
            assert_int_equal(ev->type, TDC_LINK_EV_PACKET);
            seen[ev->kind]++;
            const uint32_t e = ev->eye, f = ev->frame_index;
            if (ev->kind == TDC_LINK_KIND_SUBFRAME) {
                tdc_link_gen_rgb(src, tx, ty, f, e, o.seed);
                expected_rgb(fmt, src, tx, ty, expect);
                assert_memory_equal(rig.subframe[e], expect, (size_t)tx * ty * 3u);
            } else if (ev->kind == TDC_LINK_KIND_PATTERN) {
                uint8_t bits[TDC_PATTERN_BYTES(LT_MAX_W, LT_MAX_H)];
                const size_t nb = TDC_PATTERN_BYTES(w, h);
                tdc_link_gen_pattern(bits, nb, tx * ty, f, e, o.seed);
                assert_memory_equal(rig.pattern[e], bits, nb);
                assert_int_equal(f % 4u, 0);
            } else if (ev->kind == TDC_LINK_KIND_MOTION) {
                static int16_t mv[LT_MAX_W * LT_MAX_H * 2];
                if (ev->flags & TDC_LINK_PKT_MV_PER_SAMPLE) {
                    tdc_link_gen_mv(mv, (size_t)tx * ty * 2u, f, e, o.seed ^ 0x5A5Au);
                    assert_memory_equal(rig.sample_motion[e], mv, (size_t)tx * ty * 4u);
                } else {
                    tdc_link_gen_mv(mv, (size_t)w * h * 2u, f, e, o.seed);
                    assert_memory_equal(rig.motion[e], mv, (size_t)w * h * 4u);
                }
            }
        }
        assert_int_equal(seen[TDC_LINK_KIND_STREAM], 1);
        assert_int_equal(seen[TDC_LINK_KIND_SUBFRAME], 6u * eyes);
        assert_int_equal(seen[TDC_LINK_KIND_PATTERN], 2u * eyes); /* frames 0 and 4 */
        assert_int_equal(seen[TDC_LINK_KIND_MOTION], 12u * eyes);
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, npk);
        const tdc_link_stream_info_t *si = tdc_link_stream(&rig.dec);
        assert_non_null(si);
        assert_int_equal(si->flags, o.info.flags);
    }
}

static void test_round_trip_subframes_odd_sizes(void **state)
{
    (void)state;
    round_trip_subframes(37, 23, 2);
    round_trip_subframes(1, 1, 1);
    round_trip_subframes(5, 2, 1);
    round_trip_subframes(2, 7, 2);
}

/* Full frames at r = 1 (no TRM), every format; stride wider than the eye. */
static void test_round_trip_full_only_and_stride(void **state)
{
    (void)state;
    const uint16_t w = 13, h = 9;
    for (size_t fi = 0; fi < 4; fi++) {
        tdc_link_encoder_t enc;
        tdc_link_stream_info_t in = info_of(0, w, h, 1, 1, 1);
        tdc_link_encoder_init(&enc, 1, &in);
        static uint8_t panel[2 * 13 * 3 * 9]; /* side-by-side: eye 0 of a 26-wide panel */
        memset(panel, 0xEE, sizeof panel);
        tdc_link_config_t cfg = {w, h, 1};
        tdc_link_buffers_t b;
        memset(&b, 0, sizeof b);
        b.staging = rig.staging;
        b.staging_bytes = sizeof rig.staging;
        b.full[0] = panel;
        b.full_stride = 2u * w * 3u;
        assert_int_equal(tdc_link_decoder_init(&rig.dec, &cfg, &b), TDC_OK);
        rig.nev = 0;
        size_t n = tdc_link_encode_stream(&enc, stream, sizeof stream);
        tdc_link_gen_rgb(src, w, h, 5, 0, 1);
        n += tdc_link_encode_frame(&enc, stream + n, sizeof stream - n, TDC_LINK_KIND_FULL, 0, 5, all_fmts[fi], src, w,
                                   h, w * 3u);
        lt_feed(&rig, stream, n, 0, 0);
        assert_int_equal(lt_count(&rig, 0, TDC_LINK_EV_PACKET, 0), 2);
        expected_rgb(all_fmts[fi], src, w, h, expect);
        for (uint32_t y = 0; y < h; y++) {
            assert_memory_equal(panel + (size_t)y * 2u * w * 3u, expect + (size_t)y * w * 3u, (size_t)w * 3u);
            for (uint32_t x = 0; x < (uint32_t)w * 3u; x++) {
                assert_int_equal(panel[(size_t)y * 2u * w * 3u + w * 3u + x], 0xEE); /* other eye untouched */
            }
        }
        /* A REDUCED packet in a stream without reduced frames: unexpected. */
        n = tdc_link_encode_frame(&enc, stream, sizeof stream, TDC_LINK_KIND_REDUCED, 0, 6, all_fmts[fi], src, 7, 5,
                                  21);
        lt_feed(&rig, stream, n, 0, 0);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_UNEXPECTED), 1);
    }
}

/* defer_full (the board loop, fuzz finding F1): a FULL packet is accepted
 * without touching any pipeline buffer; tdc_link_unpack_full() unpacks it
 * exactly as the direct path would, until bytes are processed again. */
static void test_defer_full(void **state)
{
    (void)state;
    const uint16_t w = 13, h = 9;
    for (size_t fi = 0; fi < 4; fi++) {
        tdc_link_encoder_t enc;
        tdc_link_stream_info_t in = info_of(0, w, h, 2, 1, 1);
        tdc_link_encoder_init(&enc, 1, &in);
        static uint8_t panel[2 * 13 * 3 * 9];
        memset(panel, 0xEE, sizeof panel);
        tdc_link_config_t cfg = {w, h, 2};
        tdc_link_buffers_t b;
        memset(&b, 0, sizeof b);
        b.staging = rig.staging;
        b.staging_bytes = sizeof rig.staging;
        b.defer_full = 1; /* full[] NULL: allowed */
        assert_int_equal(tdc_link_decoder_init(&rig.dec, &cfg, &b), TDC_OK);
        assert_int_equal(tdc_link_unpack_full(&rig.dec, panel, 2u * w * 3u), TDC_ERR_STATE); /* nothing yet */
        size_t n = tdc_link_encode_stream(&enc, stream, sizeof stream);
        const size_t first = n;
        tdc_link_gen_rgb(src, w, h, 5, 1, 1);
        n += tdc_link_encode_frame(&enc, stream + n, sizeof stream - n, TDC_LINK_KIND_FULL, 1, 5, all_fmts[fi], src, w,
                                   h, w * 3u);
        tdc_link_event_t ev;
        assert_int_equal(tdc_link_feed(&rig.dec, stream, first, &ev), first); /* stream header */
        assert_int_equal(ev.type, TDC_LINK_EV_PACKET);
        assert_int_equal(tdc_link_feed(&rig.dec, stream + first, n - first, &ev), n - first);
        assert_int_equal(ev.type, TDC_LINK_EV_PACKET);
        assert_int_equal(ev.kind, TDC_LINK_KIND_FULL);
        for (size_t i = 0; i < sizeof panel; i++) {
            assert_int_equal(panel[i], 0xEE); /* accepted, nothing written */
        }
        assert_int_equal(tdc_link_unpack_full(&rig.dec, panel + w * 3u, w * 3u - 1u), TDC_ERR_ARG); /* short stride */
        assert_int_equal(tdc_link_unpack_full(&rig.dec, NULL, 2u * w * 3u), TDC_ERR_ARG);
        for (int twice = 0; twice < 2; twice++) {
            assert_int_equal(tdc_link_unpack_full(&rig.dec, panel + w * 3u, 2u * w * 3u), TDC_OK);
        }
        expected_rgb(all_fmts[fi], src, w, h, expect);
        for (uint32_t y = 0; y < h; y++) {
            assert_memory_equal(panel + (size_t)y * 2u * w * 3u + w * 3u, expect + (size_t)y * w * 3u, (size_t)w * 3u);
            for (uint32_t x = 0; x < (uint32_t)w * 3u; x++) {
                assert_int_equal(panel[(size_t)y * 2u * w * 3u + x], 0xEE); /* eye 0 untouched */
            }
        }
        /* a feed with no bytes (returns nothing queued) keeps it; bytes end it */
        assert_int_equal(tdc_link_feed(&rig.dec, stream, 0, &ev), 0);
        assert_int_equal(tdc_link_unpack_full(&rig.dec, panel + w * 3u, 2u * w * 3u), TDC_OK);
        assert_int_equal(tdc_link_feed(&rig.dec, stream, 3, &ev), 3);
        assert_int_equal(tdc_link_unpack_full(&rig.dec, panel + w * 3u, 2u * w * 3u), TDC_ERR_STATE);
        tdc_link_decoder_resync(&rig.dec);
        /* a rejected FULL packet (bad payload CRC) leaves nothing to unpack */
        n = tdc_link_encode_frame(&enc, stream, sizeof stream, TDC_LINK_KIND_FULL, 0, 6, all_fmts[fi], src, w, h,
                                  w * 3u);
        stream[TDC_LINK_HEADER_BYTES + 5u] ^= 0x10u;
        size_t used = 0;
        int rejected = 0;
        while (used < n) {
            used += tdc_link_feed(&rig.dec, stream + used, n - used, &ev);
            rejected |= ev.type == TDC_LINK_EV_ERROR && ev.error == TDC_LINK_ERR_CRC;
            assert_int_not_equal(ev.type, TDC_LINK_EV_PACKET);
        }
        assert_true(rejected);
        assert_int_equal(tdc_link_unpack_full(&rig.dec, panel, 2u * w * 3u), TDC_ERR_STATE);
    }
}

/* ------------------------------------------------------------------------
 * Malformed packets: one per error code.
 * Baseline: stereo 37x23 TRM stream (r = 1/2, motion), frames 0 and 1
 * complete.  The trailing good packet P is frame 2, eye 0, FULL, RGB888.
 * ---------------------------------------------------------------------- */
#define MW 37
#define MH 23

typedef struct {
    tdc_link_err_t code;
    const char *what;
    int accepts_packet;                       /* the packet itself is valid (missing reduced) */
    uint32_t allowed_extra;                   /* bitmask of other codes that may accompany it */
    size_t (*make)(uint8_t *out, size_t cap); /* NULL: good_with_field(off, bytes, value) */
    uint8_t off, bytes;                       /* a header field: wire offset, width */
    uint32_t value;
} bad_case_t;

static tdc_link_encoder_t menc;
static size_t base_len, good_len;

static void build_baseline(void)
{
    tdc_link_gen_opts_t o;
    memset(&o, 0, sizeof o);
    o.stream_id = 42;
    o.info = info_of(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_MOTION, MW, MH, 2, 1, 2);
    o.fmt = TDC_PIXFMT_RGB888;
    o.frames = 2;
    o.seed = 5;
    o.with_stream_header = 1;
    base_len = tdc_link_gen_stream(stream, sizeof stream, &o, (uint8_t *)scratch, sizeof scratch, NULL, 0, NULL);
    assert_true(base_len > 0);
    tdc_link_encoder_init(&menc, 42, &o.info);
    tdc_link_gen_rgb(src, MW, MH, 2, 0, 99);
    good_len = tdc_link_encode_frame(&menc, pkt2, sizeof pkt2, TDC_LINK_KIND_FULL, 0, 2, TDC_PIXFMT_RGB888, src, MW, MH,
                                     MW * 3u);
    assert_true(good_len > 0);
}

/* The good packet with header fields changed (CRCs recomputed). */
static size_t good_with(uint8_t *out, size_t cap, void (*edit)(tdc_link_header_t *f))
{
    tdc_link_header_t f;
    assert_int_equal(tdc_link_header_unpack(pkt2, &f), TDC_LINK_OK);
    edit(&f);
    return tdc_link_encode_raw(out, cap, &f, pkt2 + TDC_LINK_HEADER_BYTES, f.payload_len);
}

/* The good packet with one header field (wire offset off, 1, 2 or 4
 * bytes little-endian) set to v and the header CRC recomputed: a
 * well-formed header that says what the decoder must refuse. */
static size_t good_with_field(uint8_t *out, unsigned off, unsigned bytes, uint32_t v)
{
    memcpy(out, pkt2, good_len);
    if (bytes == 1u) {
        out[off] = (uint8_t)v;
    } else if (bytes == 2u) {
        tdc_put_le16(out + off, v);
    } else {
        tdc_put_le32(out + off, v);
    }
    tdc_put_le32(out + TDC_LINK_OFF_HEADER_CRC, tdc_crc32(out, TDC_LINK_OFF_HEADER_CRC));
    return good_len;
}

static void ed_dup(tdc_link_header_t *f)
{
    f->frame_index = 1;
    f->eye = 1;
}

static size_t mk_magic(uint8_t *out, size_t cap)
{
    (void)cap;
    memcpy(out, pkt2, good_len);
    out[0] = 'X';
    return good_len;
}
static size_t mk_garbage(uint8_t *out, size_t cap)
{
    (void)cap;
    for (size_t i = 0; i < 50; i++) {
        out[i] = (uint8_t)('a' + i % 19u); /* no 'T' */
    }
    return 50;
}
static size_t mk_header_crc(uint8_t *out, size_t cap)
{
    (void)cap;
    memcpy(out, pkt2, good_len);
    out[TDC_LINK_OFF_WIDTH] ^= 1; /* header CRC not updated */
    return good_len;
}
static size_t mk_length(uint8_t *out, size_t cap)
{
    tdc_link_header_t f;
    assert_int_equal(tdc_link_header_unpack(pkt2, &f), TDC_LINK_OK);
    return tdc_link_encode_raw(out, cap, &f, pkt2 + TDC_LINK_HEADER_BYTES, f.payload_len - 3u);
}
static size_t mk_crc(uint8_t *out, size_t cap)
{
    (void)cap;
    memcpy(out, pkt2, good_len);
    out[TDC_LINK_HEADER_BYTES + 100] ^= 0x40; /* payload corrupted in transit */
    return good_len;
}
static size_t mk_dup(uint8_t *out, size_t cap)
{
    return good_with(out, cap, ed_dup);
}
static size_t mk_missing(uint8_t *out, size_t cap)
{
    /* Frame 3 eye 1 (a full slot) arrives after frame 1: frame 2, whose
     * eye 1 was due a reduced frame, never came. */
    tdc_link_gen_rgb(src, MW, MH, 3, 1, 7);
    return tdc_link_encode_frame(&menc, out, cap, TDC_LINK_KIND_FULL, 1, 3, TDC_PIXFMT_RGB888, src, MW, MH, MW * 3u);
}
static size_t mk_unexpected(uint8_t *out, size_t cap)
{
    /* A reduced frame for frame 2, eye 0: that slot is due a full frame. */
    const uint32_t rw = TDC_REDUCED_DIM(MW, 1, 2), rh = TDC_REDUCED_DIM(MH, 1, 2);
    tdc_link_gen_rgb(src, rw, rh, 2, 0, 7);
    return tdc_link_encode_frame(&menc, out, cap, TDC_LINK_KIND_REDUCED, 0, 2, TDC_PIXFMT_RGB888, src, rw, rh, rw * 3u);
}
static size_t mk_stream_header(uint8_t *out, size_t cap)
{
    tdc_link_encoder_t e2 = menc;
    e2.info.r_num = 1;
    e2.info.r_den = 8; /* r = 1/8 < 1/4 */
    return tdc_link_encode_stream(&e2, out, cap);
}

#define B(e) (1u << (e))
static const bad_case_t bad_cases[] = {
    {TDC_LINK_ERR_MAGIC, "magic", 0, B(TDC_LINK_ERR_GARBAGE), mk_magic, 0, 0, 0},
    {TDC_LINK_ERR_GARBAGE, "garbage", 0, B(TDC_LINK_ERR_MAGIC), mk_garbage, 0, 0, 0},
    {TDC_LINK_ERR_HEADER_CRC, "header-crc", 0, B(TDC_LINK_ERR_GARBAGE), mk_header_crc, 0, 0, 0},
    {TDC_LINK_ERR_VERSION, "version", 0, 0, NULL, TDC_LINK_OFF_VERSION, 1, 2},
    {TDC_LINK_ERR_KIND, "kind", 0, 0, NULL, TDC_LINK_OFF_KIND, 1, 9},
    {TDC_LINK_ERR_EYE, "eye", 0, 0, NULL, TDC_LINK_OFF_EYE, 1, 2},
    {TDC_LINK_ERR_FORMAT, "format", 0, 0, NULL, TDC_LINK_OFF_FORMAT, 1, 7},
    {TDC_LINK_ERR_DIMENSIONS, "dimensions", 0, 0, NULL, TDC_LINK_OFF_WIDTH, 2, MW + 2},
    {TDC_LINK_ERR_LENGTH, "length", 0, 0, mk_length, 0, 0, 0},
    {TDC_LINK_ERR_CRC, "crc", 0, 0, mk_crc, 0, 0, 0},
    {TDC_LINK_ERR_STREAM, "stream", 0, 0, NULL, TDC_LINK_OFF_STREAM_ID, 2, 43},
    {TDC_LINK_ERR_ORDER, "order", 0, 0, NULL, TDC_LINK_OFF_FRAME, 4, 0},
    {TDC_LINK_ERR_DUPLICATE, "duplicate", 0, 0, mk_dup, 0, 0, 0},
    {TDC_LINK_ERR_MISSING_REDUCED, "missing-reduced", 1, 0, mk_missing, 0, 0, 0},
    {TDC_LINK_ERR_UNEXPECTED, "unexpected", 0, 0, mk_unexpected, 0, 0, 0},
    {TDC_LINK_ERR_STREAM_HEADER, "stream-header", 0, 0, mk_stream_header, 0, 0, 0},
};

static void run_bad_case(const bad_case_t *c, int chunk)
{
    assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
    assert_int_equal(lt_feed(&rig, stream, base_len, chunk, 11), base_len);
    assert_int_equal(lt_count(&rig, 0, TDC_LINK_EV_PACKET, 0),
                     1 + 2 * 2 * 2); /* header + 2 frames x 2 eyes x (pix + mv) */
    const uint32_t base_ok = tdc_link_counters(&rig.dec)->packets_ok;
    const uint64_t shown = lt_fnv(0xcbf29ce484222325ULL, rig.full, sizeof rig.full);
    const uint64_t all = lt_hash_all(&rig);
    const uint64_t shown0 = lt_fnv(0xcbf29ce484222325ULL, rig.full[0], sizeof rig.full[0]);
    const uint64_t red = lt_fnv(0xcbf29ce484222325ULL, rig.reduced, sizeof rig.reduced);
    const size_t n = c->make ? c->make(pkt, sizeof pkt) : good_with_field(pkt, c->off, c->bytes, c->value);
    assert_true(n > 0);
    const uint32_t ev0 = rig.nev;
    assert_int_equal(lt_feed(&rig, pkt, n, chunk, 12), n);
    if (c->accepts_packet) {
        /* The packet itself is good and shown (full eye 1); nothing else
         * changed: no reduced frame is invented for the missing one. */
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, base_ok + 1);
        assert_memory_equal(rig.full[1], pkt + TDC_LINK_HEADER_BYTES, (size_t)MW * MH * 3u);
        assert_true(lt_fnv(0xcbf29ce484222325ULL, rig.full[0], sizeof rig.full[0]) == shown0);
        assert_true(lt_fnv(0xcbf29ce484222325ULL, rig.reduced, sizeof rig.reduced) == red);
    } else {
        /* Nothing at all changed: the displayed frame is the last good one. */
        assert_true(lt_hash_all(&rig) == all);
        assert_true(lt_fnv(0xcbf29ce484222325ULL, rig.full, sizeof rig.full) == shown);
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, base_ok);
    }
    /* Then a good packet: accepted (resynchronised), shown.  After the
     * missing-reduced case the decoder is at frame 3: send frame 3's
     * reduced eye 0 instead. */
    const uint32_t ok_before = tdc_link_counters(&rig.dec)->packets_ok;
    if (c->code != TDC_LINK_ERR_MISSING_REDUCED) {
        assert_int_equal(lt_feed(&rig, pkt2, good_len, chunk, 13), good_len);
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, ok_before + 1);
        assert_memory_equal(rig.full[0], pkt2 + TDC_LINK_HEADER_BYTES, (size_t)MW * MH * 3u);
    } else {
        const uint32_t rw = TDC_REDUCED_DIM(MW, 1, 2), rh = TDC_REDUCED_DIM(MH, 1, 2);
        tdc_link_gen_rgb(src, rw, rh, 3, 0, 7);
        const size_t m = tdc_link_encode_frame(&menc, pkt, sizeof pkt, TDC_LINK_KIND_REDUCED, 0, 3, TDC_PIXFMT_RGB888,
                                               src, rw, rh, rw * 3u);
        assert_int_equal(lt_feed(&rig, pkt, m, chunk, 13), m);
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, ok_before + 1);
        assert_memory_equal(rig.reduced[0], src, (size_t)rw * rh * 3u);
        assert_int_equal(tdc_link_counters(&rig.dec)->missing_reduced_frames, 1);
    }
    /* The error: its event and its counter, exactly once; nothing else
     * besides the allowed companions. */
    if (lt_count(&rig, ev0, TDC_LINK_EV_ERROR, c->code) != 1) {
        print_error("case %s: %u events of its code\n", c->what, lt_count(&rig, ev0, TDC_LINK_EV_ERROR, c->code));
    }
    assert_int_equal(lt_count(&rig, ev0, TDC_LINK_EV_ERROR, c->code), 1);
    assert_int_equal(tdc_link_error_count(&rig.dec, c->code), 1);
    for (int k = 1; k < TDC_LINK_ERR_COUNT; k++) {
        if (k != (int)c->code && !(c->allowed_extra & B(k))) {
            if (tdc_link_error_count(&rig.dec, (tdc_link_err_t)k)) {
                print_error("case %s: unexpected %s\n", c->what, tdc_link_err_name((tdc_link_err_t)k));
            }
            assert_int_equal(tdc_link_error_count(&rig.dec, (tdc_link_err_t)k), 0);
        }
    }
}

static void test_malformed_table(void **state)
{
    (void)state;
    build_baseline();
    /* Every code except OK is in the table exactly once; FOVEATION needs a
     * foveated stream, which this TRM baseline cannot be: every reason of
     * it is in tests/unit/test_link_fov.c. */
    uint32_t covered = 0;
    for (size_t i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++) {
        assert_false(covered & B(bad_cases[i].code));
        covered |= B(bad_cases[i].code);
        assert_string_equal(tdc_link_err_name(bad_cases[i].code), bad_cases[i].what);
    }
    /* LAYERS needs a layered stream: its cases are tests/unit/test_layer_link.c;
     * BAND and BAND_DROPPED a banded one: tests/unit/test_band_link.c */
    assert_int_equal(covered, ((1u << TDC_LINK_ERR_COUNT) - 1u) & ~1u & ~B(TDC_LINK_ERR_FOVEATION) &
                                  ~B(TDC_LINK_ERR_LAYERS) & ~B(TDC_LINK_ERR_BAND) & ~B(TDC_LINK_ERR_BAND_DROPPED));
    const int chunks[] = {0, 1, 7, -40};
    for (size_t ci = 0; ci < 4; ci++) {
        for (size_t i = 0; i < sizeof bad_cases / sizeof bad_cases[0]; i++) {
            run_bad_case(&bad_cases[i], chunks[ci]);
        }
    }
}

/* Garbage details: exact byte count; a stream joined mid-way is garbage
 * but no loss of sync; a false magic inside garbage and a real packet that
 * starts inside a rejected header are both recovered. */
static void test_garbage_and_resync(void **state)
{
    (void)state;
    build_baseline();
    /* Joined mid-packet: the tail of a packet, then the baseline. */
    memcpy(stream2, pkt2 + 100, good_len - 100);
    memcpy(stream2 + good_len - 100, stream, base_len);
    for (int chunk = 0; chunk < 3; chunk++) {
        assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
        lt_feed(&rig, stream2, good_len - 100 + base_len, chunk == 2 ? -9 : chunk, 3);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_GARBAGE), 1);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_MAGIC), 0);
        assert_int_equal(tdc_link_counters(&rig.dec)->garbage_bytes, good_len - 100);
        assert_int_equal(rig.ev[0].detail, good_len - 100);
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, 9);
    }
    /* Garbage with false magics ("TDCL" + junk) between packets. */
    size_t n = 0;
    memcpy(stream2, stream, base_len);
    n = base_len;
    /* "TTDTDCTDCL" + 40 x + "TDC": the false header completes inside it. */
    char junk[64];
    size_t jn = 0;
    memcpy(junk, "TTDTDCTDCL", 10);
    jn = 10;
    memset(junk + jn, 'x', 40);
    jn += 40;
    memcpy(junk + jn, "TDC", 3);
    jn += 3;
    memcpy(stream2 + n, junk, jn);
    n += jn;
    memcpy(stream2 + n, pkt2, good_len);
    n += good_len;
    assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
    lt_feed(&rig, stream2, n, 1, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_MAGIC), 1);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_HEADER_CRC), 1);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_GARBAGE), 1);
    assert_int_equal(tdc_link_counters(&rig.dec)->garbage_bytes, jn);
    assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, 10);
    /* A packet starting 5 bytes into a truncated header ("TDCL" + 1 byte,
     * then the real packet): found by rescanning the rejected header. */
    memcpy(stream2, stream, base_len);
    n = base_len;
    memcpy(stream2 + n, pkt2, 5);
    n += 5;
    memcpy(stream2 + n, pkt2, good_len);
    n += good_len;
    for (int chunk = 0; chunk < 3; chunk++) {
        assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
        lt_feed(&rig, stream2, n, chunk == 2 ? -5 : chunk, 9);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_HEADER_CRC), 1);
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, 10);
        assert_memory_equal(rig.full[0], pkt2 + TDC_LINK_HEADER_BYTES, (size_t)MW * MH * 3u);
    }
    /* A dropped byte inside a payload: that packet fails its CRC and its
     * payload now holds the first byte of the next packet.  The decoder
     * rescans the failed payload and resynchronises on that very next
     * packet (here a duplicate, recognised as such), losing nothing else. */
    memcpy(stream2, stream, base_len);
    n = base_len;
    memcpy(stream2 + n, pkt2, 200);
    memcpy(stream2 + n + 200, pkt2 + 201, good_len - 201);
    n += good_len - 1;
    n += good_with(stream2 + n, sizeof stream2 - n, ed_dup);
    tdc_link_gen_rgb(src, MW, MH, 2, 1, 4);
    const uint32_t rw = TDC_REDUCED_DIM(MW, 1, 2), rh = TDC_REDUCED_DIM(MH, 1, 2);
    n += tdc_link_encode_frame(&menc, stream2 + n, sizeof stream2 - n, TDC_LINK_KIND_REDUCED, 1, 2, TDC_PIXFMT_RGB888,
                               src, rw, rh, rw * 3u);
    n += tdc_link_encode_frame(&menc, stream2 + n, sizeof stream2 - n, TDC_LINK_KIND_REDUCED, 1, 2, TDC_PIXFMT_RGB888,
                               src, rw, rh, rw * 3u);
    for (int chunk = 0; chunk < 3; chunk++) {
        assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
        lt_feed(&rig, stream2, n, chunk == 2 ? -7 : chunk, 5);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_CRC), 1);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_DUPLICATE), 2); /* the next packet, found */
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_MAGIC), 0);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_GARBAGE), 0);
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, 10);
        assert_int_equal(tdc_link_counters(&rig.dec)->packets_by_kind[TDC_LINK_KIND_REDUCED], 2 + 1);
        assert_memory_equal(rig.reduced[1], src, (size_t)rw * rh * 3u);
    }
    /* A packet hidden entirely inside a failed payload (a short packet
     * spliced into a long one that then fails its CRC) is found too, and
     * the stream after it continues in sync. */
    {
        uint8_t pat[TDC_PATTERN_BYTES(MW, MH)];
        memset(pat, 0, sizeof pat);
        tdc_link_stream_info_t in = info_of(TDC_LINK_STREAM_SUBFRAMES, MW, MH, 1, 1, 1);
        tdc_link_encoder_t e1;
        tdc_link_encoder_init(&e1, 4, &in);
        size_t q = tdc_link_encode_stream(&e1, stream2, sizeof stream2);
        tdc_link_gen_rgb(src, MW, MH, 0, 0, 1);
        const size_t a = tdc_link_encode_frame(&e1, stream2 + q, sizeof stream2 - q, TDC_LINK_KIND_FULL, 0, 0,
                                               TDC_PIXFMT_RGB888, src, MW, MH, MW * 3u);
        /* Cut the full frame at byte 300 and append a pattern packet and the
         * rest: the frame's CRC fails (its payload swallowed the pattern). */
        static uint8_t tmp[1 << 16];
        memcpy(tmp, stream2 + q, a);
        size_t r = q;
        memcpy(stream2 + r, tmp, 300);
        r += 300;
        pat[0] = 0x5A;
        const size_t pl = tdc_link_encode_pattern(&e1, stream2 + r, sizeof stream2 - r, 0, 0, pat, MW, MH);
        r += pl;
        memcpy(stream2 + r, tmp + 300, a - 300 - pl); /* keep the total = a: the frame's length still matches */
        r += a - 300 - pl;
        const size_t sub =
            tdc_link_encode_subframe(&e1, stream2 + r, sizeof stream2 - r, 0, 0, TDC_PIXFMT_RGB565, src, MW, MH);
        r += sub;
        for (int chunk = 0; chunk < 3; chunk++) {
            assert_int_equal(lt_init(&rig, MW, MH, 1), TDC_OK);
            lt_feed(&rig, stream2, r, chunk == 2 ? -11 : chunk, 8);
            assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_CRC), 1);
            assert_int_equal(tdc_link_counters(&rig.dec)->packets_by_kind[TDC_LINK_KIND_PATTERN], 1);
            assert_int_equal(rig.pattern[0][0], 0x5A);
            assert_int_equal(tdc_link_counters(&rig.dec)->packets_by_kind[TDC_LINK_KIND_SUBFRAME], 1);
            assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, 3);
        }
    }
}

/* A transfer cut off mid-packet (USB unplugged): resync drops the partial
 * packet, keeps the stream, and the next packet is decoded. */
static void test_resync_after_cut(void **state)
{
    (void)state;
    build_baseline();
    assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
    lt_feed(&rig, stream, base_len, 0, 0);
    const uint64_t before = lt_hash_all(&rig);
    lt_feed(&rig, pkt2, 500, 0, 0); /* header + part of the payload */
    tdc_link_decoder_resync(&rig.dec);
    assert_true(lt_hash_all(&rig) == before);
    lt_feed(&rig, pkt2, good_len, 3, 0);
    assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, 10);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_GARBAGE), 1);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_MAGIC), 0);
    assert_int_equal(tdc_link_counters(&rig.dec)->garbage_bytes, 500);
    assert_memory_equal(rig.full[0], pkt2 + TDC_LINK_HEADER_BYTES, (size_t)MW * MH * 3u);
}

/* ------------------------------------------------------------------------
 * Chunking: 1-byte, random and whole-packet pieces give identical events,
 * counters and buffers, on a stream with errors mixed in.
 * ---------------------------------------------------------------------- */
static size_t build_messy_stream(uint8_t *out, size_t cap, tdc_link_gen_packet_t *pk, uint32_t *npk)
{
    tdc_link_gen_opts_t o;
    memset(&o, 0, sizeof o);
    o.stream_id = 5;
    o.info = info_of(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_MOTION, 29, 17, 2, 1, 2);
    o.fmt = TDC_PIXFMT_YCBCR420;
    o.frames = 8;
    o.seed = 21;
    o.with_stream_header = 1;
    size_t n = tdc_link_gen_stream(stream2, sizeof stream2, &o, (uint8_t *)scratch, sizeof scratch, pk, 256, npk);
    assert_true(n > 0 && *npk > 20);
    /* Copy with damage: garbage before packet 3, packet 6 CRC-corrupted,
     * packet 9 dropped, packet 12 duplicated, header of 15 corrupted. */
    size_t m = 0;
    for (uint32_t i = 0; i < *npk; i++) {
        if (i == 9) {
            continue;
        }
        if (i == 3) {
            memcpy(out + m, "noise-noise-TDC-noise", 21);
            m += 21;
        }
        memcpy(out + m, stream2 + pk[i].offset, pk[i].size);
        if (i == 6) {
            out[m + pk[i].size - 1] ^= 0xFF;
        }
        if (i == 15) {
            out[m + 9] ^= 0x01;
        }
        m += pk[i].size;
        if (i == 12) {
            memcpy(out + m, stream2 + pk[i].offset, pk[i].size);
            m += pk[i].size;
        }
    }
    assert_true(m <= cap);
    return m;
}

static void test_chunking_identical(void **state)
{
    (void)state;
    static tdc_link_gen_packet_t pk[256];
    uint32_t npk = 0;
    const size_t n = build_messy_stream(stream, sizeof stream, pk, &npk);
    /* Whole-packet pieces: the clean packet table does not apply to the
     * damaged copy, so use the whole buffer, then 1 byte, then random. */
    static tdc_link_event_t ref_ev[LT_MAX_EVENTS];
    uint32_t ref_n = 0;
    uint64_t ref_hash = 0;
    tdc_link_counters_t ref_cnt;
    const int chunks[] = {0, 1, -3, -100, -5000, 4096, 33};
    for (size_t ci = 0; ci < sizeof chunks / sizeof chunks[0]; ci++) {
        assert_int_equal(lt_init(&rig, 29, 17, 2), TDC_OK);
        assert_int_equal(lt_feed(&rig, stream, n, chunks[ci], (uint32_t)ci * 7919u), n);
        if (ci == 0) {
            memcpy(ref_ev, rig.ev, sizeof(tdc_link_event_t) * rig.nev);
            ref_n = rig.nev;
            ref_hash = lt_hash_all(&rig);
            ref_cnt = *tdc_link_counters(&rig.dec);
            /* The damage shows up as expected. */
            assert_int_equal(ref_cnt.errors[TDC_LINK_ERR_MAGIC], 1);   /* noise at a boundary */
            assert_int_equal(ref_cnt.errors[TDC_LINK_ERR_GARBAGE], 2); /* noise; body of the bad header */
            assert_int_equal(ref_cnt.errors[TDC_LINK_ERR_CRC], 1);
            assert_int_equal(ref_cnt.errors[TDC_LINK_ERR_DUPLICATE], 1);
            assert_int_equal(ref_cnt.errors[TDC_LINK_ERR_HEADER_CRC], 1);
            assert_true(ref_cnt.packets_ok >= npk - 4);
            continue;
        }
        assert_int_equal(rig.nev, ref_n);
        assert_memory_equal(rig.ev, ref_ev, sizeof(tdc_link_event_t) * ref_n);
        assert_true(lt_hash_all(&rig) == ref_hash);
        assert_memory_equal(tdc_link_counters(&rig.dec), &ref_cnt, sizeof ref_cnt);
    }
    /* Whole-packet pieces on the clean stream equal one whole buffer. */
    assert_int_equal(lt_init(&rig, 29, 17, 2), TDC_OK);
    for (uint32_t i = 0; i < npk; i++) {
        lt_feed(&rig, stream2 + pk[i].offset, pk[i].size, 0, 0);
    }
    assert_int_equal(lt_init(&rig2, 29, 17, 2), TDC_OK);
    lt_feed(&rig2, stream2, pk[npk - 1].offset + pk[npk - 1].size, 1, 0);
    assert_int_equal(rig.nev, rig2.nev);
    assert_memory_equal(rig.ev, rig2.ev, sizeof(tdc_link_event_t) * rig.nev);
    assert_true(lt_hash_all(&rig) == lt_hash_all(&rig2));
}

/* ------------------------------------------------------------------------
 * Sequencing.
 * ---------------------------------------------------------------------- */
static size_t frame_pkt(uint8_t *out, size_t cap, tdc_link_kind_t k, uint32_t eye, uint32_t f)
{
    const uint32_t w = k == TDC_LINK_KIND_REDUCED ? TDC_REDUCED_DIM(MW, 1, 2) : MW;
    const uint32_t h = k == TDC_LINK_KIND_REDUCED ? TDC_REDUCED_DIM(MH, 1, 2) : MH;
    tdc_link_gen_rgb(src, w, h, f, eye, 1);
    return tdc_link_encode_frame(&menc, out, cap, k, eye, f, TDC_PIXFMT_RGB565, src, w, h, w * 3u);
}

static void test_missing_reduced_counts(void **state)
{
    (void)state;
    build_baseline(); /* frames 0, 1 complete */
    /* Stereo: frame 2 eye 0 full only, then frame 5: missing = frame 2's
     * eye 1 + frames 3, 4 (one reduced eye each) = 3. */
    assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
    lt_feed(&rig, stream, base_len, 0, 0);
    size_t n = frame_pkt(pkt, sizeof pkt, TDC_LINK_KIND_FULL, 0, 2);
    lt_feed(&rig, pkt, n, 0, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_MISSING_REDUCED), 0);
    n = frame_pkt(pkt, sizeof pkt, TDC_LINK_KIND_FULL, 1, 5);
    const uint32_t ev0 = rig.nev;
    lt_feed(&rig, pkt, n, 0, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_MISSING_REDUCED), 1);
    assert_int_equal(tdc_link_counters(&rig.dec)->missing_reduced_frames, 3);
    assert_int_equal(rig.ev[ev0].error, TDC_LINK_ERR_MISSING_REDUCED); /* before the packet event */
    assert_int_equal(rig.ev[ev0].frame_index, 2);
    assert_int_equal(rig.ev[ev0].detail, 3);
    assert_int_equal(rig.ev[ev0 + 1].type, TDC_LINK_EV_PACKET);
    /* Reduced frame due in a full slot is unexpected; a full one in a
     * reduced slot too. */
    n = frame_pkt(pkt, sizeof pkt, TDC_LINK_KIND_FULL, 0, 5);
    lt_feed(&rig, pkt, n, 0, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_UNEXPECTED), 1);
    n = frame_pkt(pkt, sizeof pkt, TDC_LINK_KIND_REDUCED, 0, 5);
    lt_feed(&rig, pkt, n, 0, 0);
    assert_int_equal(tdc_link_counters(&rig.dec)->packets_by_kind[TDC_LINK_KIND_REDUCED], 3);

    /* Mono, r = 3/4: frames 0 (full), 1 missing, 2 full, then 8: missing
     * = frame 1, then frames 3, 5, 7 = 4 reduced frames in 2 events. */
    tdc_link_stream_info_t in = info_of(TDC_LINK_STREAM_REDUCED, MW, MH, 1, 3, 4);
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 8, &in);
    assert_int_equal(lt_init(&rig, MW, MH, 1), TDC_OK);
    n = tdc_link_encode_stream(&enc, stream2, sizeof stream2);
    tdc_link_gen_rgb(src, MW, MH, 0, 0, 1);
    const uint32_t fr[] = {0, 2, 8};
    for (int i = 0; i < 3; i++) {
        n += tdc_link_encode_frame(&enc, stream2 + n, sizeof stream2 - n, TDC_LINK_KIND_FULL, 0, fr[i],
                                   TDC_PIXFMT_RGB888, src, MW, MH, MW * 3u);
    }
    lt_feed(&rig, stream2, n, 0, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_MISSING_REDUCED), 2);
    assert_int_equal(tdc_link_counters(&rig.dec)->missing_reduced_frames, 4);
    assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, 4);
}

static void test_stream_headers(void **state)
{
    (void)state;
    build_baseline();
    /* Repeating the same header (late joiners) keeps the frame sequence:
     * frame 1 is still a duplicate afterwards. */
    assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
    lt_feed(&rig, stream, base_len, 0, 0);
    size_t n = tdc_link_encode_stream(&menc, pkt, sizeof pkt);
    lt_feed(&rig, pkt, n, 0, 0);
    n = good_with(pkt, sizeof pkt, ed_dup);
    lt_feed(&rig, pkt, n, 0, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_DUPLICATE), 1);
    /* A new stream id resets it: frame 0 is fine again, old id rejected. */
    tdc_link_encoder_t e2 = menc;
    e2.stream_id = 77;
    n = tdc_link_encode_stream(&e2, pkt, sizeof pkt);
    lt_feed(&rig, pkt, n, 0, 0);
    tdc_link_gen_rgb(src, MW, MH, 0, 0, 1);
    n = tdc_link_encode_frame(&e2, pkt, sizeof pkt, TDC_LINK_KIND_FULL, 0, 0, TDC_PIXFMT_RGB888, src, MW, MH, MW * 3u);
    const uint32_t ok = tdc_link_counters(&rig.dec)->packets_ok;
    lt_feed(&rig, pkt, n, 0, 0);
    assert_int_equal(tdc_link_counters(&rig.dec)->packets_ok, ok + 1);
    lt_feed(&rig, pkt2, good_len, 0, 0); /* stream 42 */
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_STREAM), 1);
    /* Before any stream header, frames are rejected. */
    assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
    lt_feed(&rig, pkt2, good_len, 0, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_STREAM), 1);
    assert_null(tdc_link_stream(&rig.dec));
    /* Invalid stream headers: unknown flag, eyes, r = 1 with REDUCED, r != 1
     * without, sample MV without subframes, reduced size over capacity,
     * layer history without layers. */
    struct {
        uint32_t flags;
        uint16_t w;
        uint8_t eyes;
        uint16_t rn, rd;
    } bad[] = {{0x200, MW, 2, 1, 1},
               {TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_LAYER_HIST, MW, 2, 1, 1},
               {0, MW, 1, 1, 1},
               {TDC_LINK_STREAM_REDUCED, MW, 2, 1, 1},
               {0, MW, 2, 1, 2},
               {TDC_LINK_STREAM_SAMPLE_MV, MW, 2, 1, 1},
               {TDC_LINK_STREAM_REDUCED, MW, 2, 1, 0},
               {TDC_LINK_STREAM_REDUCED, MW, 2, 1, 5}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        tdc_link_stream_info_t in = info_of(bad[i].flags, bad[i].w, MH, bad[i].eyes, bad[i].rn, bad[i].rd);
        tdc_link_encoder_t e3;
        tdc_link_encoder_init(&e3, 1, &in);
        assert_int_equal(lt_init(&rig, MW, MH, 2), TDC_OK);
        n = tdc_link_encode_stream(&e3, pkt, sizeof pkt);
        lt_feed(&rig, pkt, n, 0, 0);
        assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_STREAM_HEADER), 1);
        assert_null(tdc_link_stream(&rig.dec));
    }
    /* A build without reduced buffers refuses a TRM stream. */
    tdc_link_config_t cfg = {MW, MH, 2};
    tdc_link_buffers_t b;
    memset(&b, 0, sizeof b);
    b.staging = rig.staging;
    b.staging_bytes = sizeof rig.staging;
    b.full[0] = rig.full[0];
    b.full[1] = rig.full[1];
    b.full_stride = MW * 3u;
    assert_int_equal(tdc_link_decoder_init(&rig.dec, &cfg, &b), TDC_OK);
    rig.nev = 0;
    lt_feed(&rig, stream, base_len, 0, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_STREAM_HEADER), 1);
    /* Reduced size is round(n r), at least 1 (tdc_geom.h, shared with TRM). */
    for (uint32_t d = 1; d < 5000; d += 7) {
        for (uint32_t num = 1; num <= 8; num++) {
            const uint32_t den = 8u;
            const uint32_t want = (uint32_t)((double)d * num / den + 0.5);
            assert_int_equal(TDC_REDUCED_DIM(d, num, den), want < 1u ? 1u : want);
            assert_int_equal(tdc_reduced_dim(d, num, den), TDC_REDUCED_DIM(d, num, den));
        }
    }
    assert_int_equal(TDC_REDUCED_DIM(1, 1, 4), 1); /* never 0 */
}

static void test_pattern_only_at_cycle_start(void **state)
{
    (void)state;
    tdc_link_stream_info_t in = info_of(TDC_LINK_STREAM_SUBFRAMES, 9, 7, 1, 1, 1);
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 2, &in);
    assert_int_equal(lt_init(&rig, 9, 7, 1), TDC_OK);
    size_t n = tdc_link_encode_stream(&enc, stream, sizeof stream);
    uint8_t bits[4] = {0xFF, 0xFF, 0xFF, 0xFF};
    n +=
        tdc_link_encode_pattern(&enc, stream + n, sizeof stream - n, 0, 1, bits, 9, 7); /* frame 1: not a cycle start */
    n += tdc_link_encode_pattern(&enc, stream + n, sizeof stream - n, 0, 4, bits, 9, 7);
    lt_feed(&rig, stream, n, 0, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_UNEXPECTED), 1);
    assert_int_equal(tdc_link_counters(&rig.dec)->packets_by_kind[TDC_LINK_KIND_PATTERN], 1);
    /* 5 x 4 = 20 tiles: 3 bytes, bits past tile 20 cleared on the wire. */
    assert_int_equal(rig.pattern[0][0], 0xFF);
    assert_int_equal(rig.pattern[0][2], 0x0F);
    /* Motion vectors are not part of this stream. */
    int16_t mv[9 * 7 * 2] = {0};
    n = tdc_link_encode_motion(&enc, stream, sizeof stream, 0, 4, mv, 9, 7, 0);
    lt_feed(&rig, stream, n, 0, 0);
    assert_int_equal(tdc_link_error_count(&rig.dec, TDC_LINK_ERR_UNEXPECTED), 2);
}

static void test_init_errors(void **state)
{
    (void)state;
    tdc_link_config_t cfg = {MW, MH, 2};
    tdc_link_buffers_t b;
    memset(&b, 0, sizeof b);
    assert_int_equal(tdc_link_decoder_init(&rig.dec, &cfg, &b), TDC_ERR_ARG); /* no staging */
    b.staging = rig.staging;
    b.staging_bytes = 8;
    assert_int_equal(tdc_link_decoder_init(&rig.dec, &cfg, &b), TDC_ERR_SIZE);
    b.staging_bytes = sizeof rig.staging;
    cfg.eyes = 3;
    assert_int_equal(tdc_link_decoder_init(&rig.dec, &cfg, &b), TDC_ERR_ARG);
    cfg.eyes = 1;
    cfg.width = TDC_LINK_MAX_WIDTH + 1;
    assert_int_equal(tdc_link_decoder_init(&rig.dec, &cfg, &b), TDC_ERR_SIZE);
    cfg.width = MW;
    b.full[0] = rig.full[0];
    b.full_stride = MW * 3u - 1u;
    assert_int_equal(tdc_link_decoder_init(&rig.dec, &cfg, &b), TDC_ERR_SIZE);
    b.full_stride = MW * 3u;
    assert_int_equal(tdc_link_decoder_init(&rig.dec, &cfg, &b), TDC_OK);
    assert_int_equal(tdc_link_decoder_init(NULL, &cfg, &b), TDC_ERR_ARG);
    /* Host default holds 1920x1080 and 1440x1600. */
    assert_true(1920u * 1080u <= TDC_LINK_MAX_PIXELS && 1440u * 1600u <= TDC_LINK_MAX_PIXELS);
    assert_true(TDC_LINK_MAX_WIDTH >= 1920 && TDC_LINK_MAX_HEIGHT >= 1600);
    /* Encoder refuses what does not fit. */
    tdc_link_gen_rgb(src, 8, 8, 0, 0, 0);
    assert_int_equal(tdc_link_encode_frame(&menc, pkt, 100, TDC_LINK_KIND_FULL, 0, 0, TDC_PIXFMT_RGB888, src, 8, 8, 24),
                     0);
    assert_int_equal(
        tdc_link_encode_frame(&menc, pkt, sizeof pkt, TDC_LINK_KIND_FULL, 0, 0, (tdc_pixfmt_t)9, src, 8, 8, 24), 0);
    assert_int_equal(tdc_link_packet_bytes(TDC_LINK_KIND_FULL, TDC_PIXFMT_YCBCR420, 3, 3, 0), 32u + 9u + 2u * 4u);
    /* Sizes whose payload would not fit 32 bits are refused, not wrapped. */
    assert_int_equal(tdc_link_packet_bytes(TDC_LINK_KIND_FULL, TDC_PIXFMT_RGB30, 65535, 65535, 0), 0);
    assert_int_equal(tdc_link_encode_frame(&menc, pkt, sizeof pkt, TDC_LINK_KIND_FULL, 0, 0, TDC_PIXFMT_RGB30, src,
                                           65535, 65535, 65535u * 3u),
                     0);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_round_trip_trm_odd_sizes),
    cmocka_unit_test(test_round_trip_subframes_odd_sizes),
    cmocka_unit_test(test_round_trip_full_only_and_stride),
    cmocka_unit_test(test_defer_full),
    cmocka_unit_test(test_malformed_table),
    cmocka_unit_test(test_garbage_and_resync),
    cmocka_unit_test(test_resync_after_cut),
    cmocka_unit_test(test_chunking_identical),
    cmocka_unit_test(test_missing_reduced_counts),
    cmocka_unit_test(test_stream_headers),
    cmocka_unit_test(test_pattern_only_at_cycle_start),
    cmocka_unit_test(test_init_errors),
)
