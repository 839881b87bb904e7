/*
 * test_band_link.c - row bands of FULL and REDUCED pictures through the
 * real decoder (firmware/tdc_band_link.h, docs/link-protocol.md §2.3), on a
 * 37 x 23 stereo TRM stream (r = 1/2: 19 x 12 reduced) with a staging
 * buffer of one band:
 *   - round trips: every format x band height (1, 4, 6, whole picture),
 *     written straight into the buffers and with defer_full, equal to the
 *     whole picture unpacked; the slot completes on the last band only;
 *     identical for whole, 1-byte and odd chunks;
 *   - the bad input of issue 17: a band with a bad CRC, bands out of order,
 *     a band for another frame, a missing last band, a frame that changes
 *     size (band geometry, format) mid-stream, plus malformed band headers,
 *     a whole picture in a banded stream and a band in an unbanded one, a
 *     band larger than staging: each with its named error and reason,
 *     counted once; a refused band writes nothing; a dropped picture never
 *     completes its slot (the frame loop never swaps it in) and is
 *     reported once with its reason.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "tdc_link.h"
#include "tdc_link_encode.h"
#include "test_link_util.h"

#define W 37
#define H 23
#define RW TDC_REDUCED_DIM(W, 1u, 2u)
#define RH TDC_REDUCED_DIM(H, 1u, 2u)
#define BR_MAX 6 /* the largest band this build stages */

static uint8_t staging[TDC_LINK_STAGING_BAND_BYTES(W, BR_MAX, 4u)];
static uint8_t full[2][W * H * 3];
static uint8_t reduced[2][RW * RH * 3];
static uint8_t src[2][W * H * 3];  /* what the sender sends, per eye */
static uint8_t want[W * H * 3];    /* whole-picture decode of src */
static uint8_t pkt[64 + W * H * 4];
static uint8_t stream[1u << 16];
static size_t stream_n;

static tdc_link_decoder_t dec;
static tdc_link_encoder_t enc;

#define EV_MAX 256
static tdc_link_event_t evs[EV_MAX];
static int n_ev;

static void setup(uint32_t sflags, int defer)
{
    tdc_link_config_t cfg = {W, H, 2};
    tdc_link_buffers_t b = lt_buffers(staging, sizeof staging);
    b.defer_full = (uint8_t)defer;
    for (int e = 0; e < 2; e++) {
        b.full[e] = defer ? NULL : full[e];
        b.reduced[e] = reduced[e];
    }
    b.full_stride = W * 3;
    b.reduced_bytes = sizeof reduced[0];
    memset(full, 0xA5, sizeof full);
    memset(reduced, 0x5A, sizeof reduced);
    assert_int_equal(tdc_link_decoder_init(&dec, &cfg, &b), TDC_OK);
    const uint16_t den = (sflags & TDC_LINK_STREAM_REDUCED) ? 2u : 1u;
    tdc_link_stream_info_t info = {sflags, 1, den, W, H, 2, 0, 90};
    tdc_link_encoder_init(&enc, 3, &info);
    stream_n = tdc_link_encode_stream(&enc, stream, sizeof stream);
    n_ev = 0;
}

static void fill_src(uint32_t seed)
{
    for (int e = 0; e < 2; e++) {
        for (size_t i = 0; i < sizeof src[e]; i++) {
            src[e][i] = (uint8_t)((seed + (uint32_t)e) * 29u + (uint32_t)i * 7u + (uint32_t)(i >> 5));
        }
    }
}

static void put(const uint8_t *p, size_t n)
{
    assert_true(n > 0 && stream_n + n <= sizeof stream);
    memcpy(stream + stream_n, p, n);
    stream_n += n;
}

/* Band `index` of eye e's picture of frame f (its TRM kind) in bands of br. */
static size_t band(uint32_t e, uint32_t f, tdc_pixfmt_t fmt, uint32_t br, uint32_t index)
{
    const tdc_link_kind_t k = tdc_link_trm_kind(f, e);
    const uint32_t w = k == TDC_LINK_KIND_FULL ? W : RW, h = k == TDC_LINK_KIND_FULL ? H : RH;
    return tdc_link_encode_band(&enc, pkt, sizeof pkt, k, e, f, fmt, src[e], w, h, W * 3u, br, index);
}

static void put_band(uint32_t e, uint32_t f, tdc_pixfmt_t fmt, uint32_t br, uint32_t index)
{
    put(pkt, band(e, f, fmt, br, index));
}

/* Feeds the collected stream in chunks (0 = whole), logging every event;
 * with defer_full each FULL band is unpacked into full[eye] on its event. */
static void run(int chunk)
{
    size_t used = 0;
    for (;;) {
        size_t n = stream_n - used;
        if (chunk > 0 && n > (size_t)chunk) {
            n = (size_t)chunk;
        }
        tdc_link_event_t ev;
        used += tdc_link_feed(&dec, stream + used, n, &ev);
        if (ev.type == TDC_LINK_EV_NONE) {
            if (used == stream_n) {
                break;
            }
            continue;
        }
        assert_true(n_ev < EV_MAX);
        evs[n_ev++] = ev;
        if (ev.type == TDC_LINK_EV_PACKET && ev.kind == TDC_LINK_KIND_FULL && dec.buf.defer_full) {
            assert_int_equal(tdc_link_unpack_full(&dec, full[ev.eye], W * 3u), TDC_OK);
        }
    }
    stream_n = 0;
}

static int count(int type, uint16_t error)
{
    int c = 0;
    for (int i = 0; i < n_ev; i++) {
        c += evs[i].type == type && (type != TDC_LINK_EV_ERROR || evs[i].error == error);
    }
    return c;
}

/* Exactly these error counts and nothing else. */
static void expect_errors(uint32_t band_err, uint32_t drop, uint32_t link_err)
{
    const tdc_link_counters_t *c = tdc_link_counters(&dec);
    for (int k = 1; k < TDC_LINK_ERR_COUNT; k++) {
        const uint32_t want_n = (k == TDC_LINK_ERR_BAND && band_err) + (k == TDC_LINK_ERR_BAND_DROPPED && drop) +
                                (link_err && k == (int)link_err);
        if (c->errors[k] != want_n) {
            print_error("code %s: %u, want %u\n", tdc_link_err_name((tdc_link_err_t)k), c->errors[k], want_n);
        }
        assert_int_equal(c->errors[k], want_n);
    }
    for (int r = 1; r < TDC_BAND_ERR_N; r++) {
        assert_int_equal(c->band_errors[r], (uint32_t)(r == (int)band_err));
    }
    for (int r = 1; r < TDC_BAND_DROP_N; r++) {
        assert_int_equal(c->band_drops[r], (uint32_t)(r == (int)drop));
    }
    if (band_err) {
        assert_int_equal(count(TDC_LINK_EV_ERROR, TDC_LINK_ERR_BAND), 1);
    }
}

static void test_geometry(void **state)
{
    (void)state;
    uint8_t h[TDC_BAND_HDR_BYTES];
    tdc_band_hdr_t p;
    assert_int_equal(tdc_band_count(23, 4), 6);
    assert_int_equal(tdc_band_count(23, 23), 1);
    assert_int_equal(tdc_band_hdr_pack(h, 5, 4, 23, TDC_PIXFMT_RGB888), 0);
    assert_int_equal(tdc_band_hdr_parse(h, TDC_PIXFMT_RGB888, W, 23, tdc_band_payload_bytes(TDC_PIXFMT_RGB888, W, 3), &p),
                     TDC_BAND_OK);
    assert_int_equal(p.first_row, 20);
    assert_int_equal(p.rows, 3);
    assert_int_equal(p.count, 6);
    assert_int_equal(tdc_band_hdr_pack(h, 6, 4, 23, TDC_PIXFMT_RGB888), -1); /* index >= count */
    assert_int_equal(tdc_band_hdr_pack(h, 0, 0, 23, TDC_PIXFMT_RGB888), -1);
    assert_int_equal(tdc_band_hdr_pack(h, 0, 3, 23, TDC_PIXFMT_YCBCR420), -1); /* would split chroma rows */
    assert_int_equal(tdc_band_hdr_pack(h, 0, 23, 23, TDC_PIXFMT_YCBCR420), 0); /* one band: any height */
    assert_string_equal(tdc_band_err_name(TDC_BAND_ERR_ORDER), "TDC_BAND_ERR_ORDER");
    assert_string_equal(tdc_band_err_name(TDC_BAND_ERR_N), "TDC_BAND_ERR_?");
    assert_string_equal(tdc_band_drop_name(TDC_BAND_DROP_MISSING), "TDC_BAND_DROP_MISSING");
    assert_string_equal(tdc_link_err_name(TDC_LINK_ERR_BAND), "band");
    assert_string_equal(tdc_link_err_name(TDC_LINK_ERR_BAND_DROPPED), "band-dropped");
}

/* Every format x band height x delivery: the bands rebuild the picture
 * exactly; the slot completes on the last band. */
static void test_roundtrip(void **state)
{
    (void)state;
    const tdc_pixfmt_t fmts[] = {TDC_PIXFMT_RGB888, TDC_PIXFMT_RGB565, TDC_PIXFMT_RGB30, TDC_PIXFMT_YCBCR420};
    const uint32_t brs[] = {1, 4, 6};
    const int chunks[] = {0, 1, 13};
    for (int defer = 0; defer < 2; defer++) {
        for (size_t fi = 0; fi < 4; fi++) {
            for (size_t bi = 0; bi < 3; bi++) {
                for (size_t ci = 0; ci < 3; ci++) {
                    const tdc_pixfmt_t fmt = fmts[fi];
                    const uint32_t br = (fmt == TDC_PIXFMT_YCBCR420 && (brs[bi] & 1u)) ? 2u : brs[bi];
                    setup(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_BANDS, defer);
                    fill_src((uint32_t)(fi * 9 + bi * 3 + ci));
                    uint32_t bands = 0;
                    for (uint32_t f = 0; f < 2; f++) {
                        for (uint32_t e = 0; e < 2; e++) {
                            const uint32_t h = tdc_link_trm_kind(f, e) == TDC_LINK_KIND_FULL ? H : RH;
                            for (uint32_t i = 0; i < tdc_band_count(h, br); i++, bands++) {
                                put_band(e, f, fmt, br, i);
                            }
                        }
                    }
                    run(chunks[ci]);
                    expect_errors(0, 0, 0);
                    assert_int_equal(count(TDC_LINK_EV_PACKET, 0), (int)bands + 1);
                    assert_int_equal(tdc_link_counters(&dec)->bands_ok, bands);
                    /* frame 1: eye 1 full, eye 0 reduced */
                    tdc_pixfmt_pack(fmt, src[1], W, H, W * 3u, pkt);
                    tdc_pixfmt_unpack(fmt, pkt, W, H, want, W * 3u);
                    assert_memory_equal(full[1], want, sizeof want);
                    tdc_pixfmt_pack(fmt, src[0], RW, RH, W * 3u, pkt);
                    tdc_pixfmt_unpack(fmt, pkt, RW, RH, want, RW * 3u);
                    assert_memory_equal(reduced[0], want, (size_t)RW * RH * 3u);
                    /* every slot of frame 1 complete: a band again is a duplicate */
                    put_band(1, 1, fmt, br, 0);
                    run(0);
                    expect_errors(0, 0, TDC_LINK_ERR_DUPLICATE);
                }
            }
        }
    }
}

/* The whole picture as one band needs a staging buffer of a picture: here
 * it is LENGTH (the build stages one band); a band of the build's height
 * is accepted. */
static void test_staging(void **state)
{
    (void)state;
    setup(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_BANDS, 0);
    fill_src(1);
    put_band(0, 0, TDC_PIXFMT_RGB30, H, 0);
    run(0);
    expect_errors(0, TDC_BAND_DROP_REFUSED, TDC_LINK_ERR_LENGTH);
    assert_int_equal(evs[n_ev - 1].detail, TDC_BAND_DROP_REFUSED);
    uint8_t before[sizeof full];
    memcpy(before, full, sizeof full);
    /* its later bands: DROPPED, nothing written; the next frame is fine */
    put_band(0, 0, TDC_PIXFMT_RGB30, BR_MAX, 1);
    run(0);
    assert_memory_equal(before, full, sizeof full);
    assert_int_equal(tdc_link_counters(&dec)->band_errors[TDC_BAND_ERR_DROPPED], 1);
}

/* Whole pictures in a banded stream and bands in an unbanded one. */
static void test_mode_mismatch(void **state)
{
    (void)state;
    setup(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_BANDS, 0);
    fill_src(2);
    put(pkt, tdc_link_encode_frame(&enc, pkt, sizeof pkt, TDC_LINK_KIND_REDUCED, 1, 0, TDC_PIXFMT_RGB888, src[1], RW,
                                   RH, W * 3u));
    run(0);
    expect_errors(0, 0, TDC_LINK_ERR_UNEXPECTED);
    setup(TDC_LINK_STREAM_REDUCED, 0);
    put_band(0, 0, TDC_PIXFMT_RGB888, 4, 0);
    run(0);
    expect_errors(0, 0, TDC_LINK_ERR_UNEXPECTED);
    /* bands without TRM */
    setup(TDC_LINK_STREAM_BANDS, 0);
    put_band(0, 0, TDC_PIXFMT_RGB888, 4, 0);
    run(0);
    expect_errors(0, 0, 0);
}

/* Frame 0, eye 0 (FULL, 6 bands of 4) with band 3 damaged in `how`, then
 * eye 1 (REDUCED) intact, then frame 1 both eyes intact. */
enum { BAD_CRC, BAD_ORDER, BAD_SIZE, BAD_FORMAT, BAD_VERSION, BAD_GEOMETRY, BAD_REPEAT };

static void bad_band_case(int how, uint32_t want_band_err, uint32_t want_link_err, uint32_t want_drop_reason)
{
    for (int chunk = 0; chunk < 2; chunk++) {
        setup(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_BANDS, 0);
        fill_src(3);
        uint8_t before[H * W * 3];
        for (uint32_t i = 0; i < 3; i++) {
            put_band(0, 0, TDC_PIXFMT_RGB888, 4, i);
        }
        {
            const uint32_t i = 3;
            size_t n = band(0, 0, TDC_PIXFMT_RGB888, 4, i);
            switch (how) {
            case BAD_CRC: pkt[TDC_LINK_HEADER_BYTES + 40] ^= 0x10u; break;
            case BAD_ORDER: n = band(0, 0, TDC_PIXFMT_RGB888, 4, 4); break; /* 4 before 3 */
            case BAD_SIZE: n = band(0, 0, TDC_PIXFMT_RGB888, 2, 6); break;  /* rows 12..13 in bands of 2 */
            case BAD_FORMAT: n = band(0, 0, TDC_PIXFMT_RGB565, 4, 3); break;
            case BAD_REPEAT: n = band(0, 0, TDC_PIXFMT_RGB888, 4, 2); break;
            case BAD_VERSION:
            case BAD_GEOMETRY: {
                uint8_t pay[TDC_BAND_HDR_BYTES + W * 4 * 3];
                const uint32_t len = (uint32_t)(n - TDC_LINK_HEADER_BYTES);
                memcpy(pay, pkt + TDC_LINK_HEADER_BYTES, len);
                if (how == BAD_VERSION) {
                    pay[0] = 2;
                } else {
                    pay[10] = 3; /* rows: 3, not 4 */
                }
                tdc_link_header_t hh;
                assert_int_equal(tdc_link_header_unpack(pkt, &hh), TDC_LINK_OK);
                n = tdc_link_encode_raw(pkt, sizeof pkt, &hh, pay, len);
                break;
            }
            default: fail();
            }
            put(pkt, n);
            if (how == BAD_ORDER) {
                put_band(0, 0, TDC_PIXFMT_RGB888, 4, 3); /* the late band 3: its picture is gone */
            }
            if (how != BAD_ORDER) {
                put_band(0, 0, TDC_PIXFMT_RGB888, 4, 4);
            }
            put_band(0, 0, TDC_PIXFMT_RGB888, 4, 5);
        }
        for (uint32_t i = 0; i < 3; i++) {
            put_band(1, 0, TDC_PIXFMT_RGB888, 4, i);
        }
        run(chunk ? 1 : 0);
        /* rows 12.. of eye 0 never written: the refused band and the ones after it */
        memset(before, 0xA5, sizeof before);
        assert_memory_equal(full[0] + 12 * W * 3, before, (size_t)(H - 12) * W * 3u);
        const tdc_link_counters_t *c = tdc_link_counters(&dec);
        assert_int_equal(c->errors[TDC_LINK_ERR_BAND_DROPPED], 1);
        assert_int_equal(c->band_drops[want_drop_reason], 1);
        if (want_link_err) {
            assert_int_equal(c->errors[want_link_err], 1);
        }
        if (want_band_err) {
            assert_int_equal(c->band_errors[want_band_err], 1);
        }
        /* the two later bands of the dropped picture: DROPPED, each counted there */
        assert_int_equal(c->band_errors[TDC_BAND_ERR_DROPPED], 2);
        assert_int_equal(c->errors[TDC_LINK_ERR_BAND], 2u + (want_band_err != 0));
        /* the drop event names the picture */
        int seen = 0;
        for (int k = 0; k < n_ev; k++) {
            if (evs[k].type == TDC_LINK_EV_ERROR && evs[k].error == TDC_LINK_ERR_BAND_DROPPED) {
                assert_int_equal(evs[k].eye, 0);
                assert_int_equal(evs[k].frame_index, 0);
                assert_int_equal(evs[k].kind, TDC_LINK_KIND_FULL);
                assert_int_equal(evs[k].detail, want_drop_reason);
                seen++;
            }
        }
        assert_int_equal(seen, 1);
        /* eye 0's slot never completed; eye 1's did; frame 1 comes through */
        assert_int_equal(dec.frame_mask & (1u << (TDC_LINK_KIND_FULL * 2u)), 0);
        put_band(0, 1, TDC_PIXFMT_RGB888, 4, 0); /* frame 1, eye 0: reduced */
        put_band(0, 1, TDC_PIXFMT_RGB888, 4, 1);
        put_band(0, 1, TDC_PIXFMT_RGB888, 4, 2);
        const int before_ok = count(TDC_LINK_EV_PACKET, 0);
        run(0);
        assert_int_equal(count(TDC_LINK_EV_PACKET, 0) - before_ok, 3);
    }
}

static void test_bad_crc(void **state)
{
    (void)state;
    bad_band_case(BAD_CRC, 0, TDC_LINK_ERR_CRC, TDC_BAND_DROP_CRC);
}
static void test_out_of_order(void **state)
{
    (void)state;
    bad_band_case(BAD_ORDER, TDC_BAND_ERR_ORDER, 0, TDC_BAND_DROP_REFUSED);
}
static void test_repeated(void **state)
{
    (void)state;
    bad_band_case(BAD_REPEAT, TDC_BAND_ERR_ORDER, 0, TDC_BAND_DROP_REFUSED);
}
static void test_size_change(void **state)
{
    (void)state;
    bad_band_case(BAD_SIZE, TDC_BAND_ERR_SIZE, 0, TDC_BAND_DROP_REFUSED);
    bad_band_case(BAD_FORMAT, TDC_BAND_ERR_SIZE, 0, TDC_BAND_DROP_REFUSED);
}
static void test_bad_header(void **state)
{
    (void)state;
    bad_band_case(BAD_VERSION, TDC_BAND_ERR_HEADER, 0, TDC_BAND_DROP_REFUSED);
    bad_band_case(BAD_GEOMETRY, TDC_BAND_ERR_GEOMETRY, 0, TDC_BAND_DROP_REFUSED);
}

/* A band for another frame (index > 0, no picture of it in flight): refused
 * as FRAME, writes nothing, and the picture in flight completes. */
static void test_other_frame(void **state)
{
    (void)state;
    setup(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_BANDS, 0);
    fill_src(4);
    put_band(0, 0, TDC_PIXFMT_RGB888, 4, 0);
    put_band(0, 0, TDC_PIXFMT_RGB888, 4, 1);
    put_band(0, 2, TDC_PIXFMT_RGB888, 4, 3); /* frame 2's band 3 */
    for (uint32_t i = 2; i < 6; i++) {
        put_band(0, 0, TDC_PIXFMT_RGB888, 4, i);
    }
    run(0);
    expect_errors(TDC_BAND_ERR_FRAME, 0, 0);
    assert_memory_equal(full[0], src[0], sizeof full[0]);
    assert_int_equal(dec.frame_index, 0); /* the refused band did not move the sequence */
    assert_true(dec.frame_mask & (1u << (TDC_LINK_KIND_FULL * 2u)));
}

/* The last band never comes: the eye's next picture reports the drop
 * (MISSING, naming the old picture) and is accepted itself; a REDUCED
 * picture left incomplete also counts as a missing reduced frame. */
static void test_missing_last(void **state)
{
    (void)state;
    setup(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_BANDS, 0);
    fill_src(5);
    for (uint32_t i = 0; i < 5; i++) {
        put_band(0, 0, TDC_PIXFMT_RGB888, 4, i); /* 5 of 6 */
    }
    for (uint32_t i = 0; i < 3; i++) {
        put_band(1, 0, TDC_PIXFMT_RGB888, 4, i);
    }
    put_band(0, 2, TDC_PIXFMT_RGB888, 4, 0); /* eye 0's next full picture */
    run(0);
    /* the drop (frame 1 was never sent: MISSING_REDUCED besides) */
    const tdc_link_counters_t *c = tdc_link_counters(&dec);
    assert_int_equal(c->errors[TDC_LINK_ERR_BAND_DROPPED], 1);
    assert_int_equal(c->band_drops[TDC_BAND_DROP_MISSING], 1);
    int k = 0;
    while (k < n_ev && !(evs[k].type == TDC_LINK_EV_ERROR && evs[k].error == TDC_LINK_ERR_BAND_DROPPED)) {
        k++;
    }
    assert_true(k < n_ev);
    assert_int_equal(evs[k].frame_index, 0);
    assert_int_equal(evs[k].eye, 0);
    assert_int_equal(evs[k].detail, TDC_BAND_DROP_MISSING);
    assert_int_equal(evs[n_ev - 1].type, TDC_LINK_EV_PACKET);
    assert_int_equal(evs[n_ev - 1].frame_index, 2);
    assert_int_equal(c->errors[TDC_LINK_ERR_BAND], 0);
    /* a reduced picture left without its last band is a missing reduced frame */
    setup(TDC_LINK_STREAM_REDUCED | TDC_LINK_STREAM_BANDS, 0);
    put_band(1, 0, TDC_PIXFMT_RGB888, 4, 0);
    put_band(1, 0, TDC_PIXFMT_RGB888, 4, 1);
    put_band(0, 1, TDC_PIXFMT_RGB888, 4, 0); /* frame 1 (eye 0 reduced) */
    run(0);
    c = tdc_link_counters(&dec);
    assert_int_equal(c->missing_reduced_frames, 1);
    assert_int_equal(c->band_drops[TDC_BAND_DROP_MISSING], 0); /* eye 1's picture is still in flight */
    /* a new stream ends it */
    tdc_link_stream_info_t info = {TDC_LINK_STREAM_BANDS, 1, 1, W, H, 2, 0, 90};
    tdc_link_encoder_init(&enc, 4, &info);
    put(pkt, tdc_link_encode_stream(&enc, pkt, sizeof pkt));
    run(0);
    assert_int_equal(tdc_link_counters(&dec)->band_drops[TDC_BAND_DROP_MISSING], 2);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_geometry),      cmocka_unit_test(test_roundtrip),   cmocka_unit_test(test_staging),
    cmocka_unit_test(test_mode_mismatch), cmocka_unit_test(test_bad_crc),     cmocka_unit_test(test_out_of_order),
    cmocka_unit_test(test_repeated),      cmocka_unit_test(test_size_change), cmocka_unit_test(test_bad_header),
    cmocka_unit_test(test_other_frame),   cmocka_unit_test(test_missing_last),
)
