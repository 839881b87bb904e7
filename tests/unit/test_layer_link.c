/*
 * test_layer_link.c - the layered subframe kind (firmware/tdc_layer_link.h)
 * through the real encoder and decoder: sizes from the packet flags, a
 * layered stream decoded plane by plane, the one-layer stream's bytes, and
 * every refusal (a named reason, counted, nothing written, the next good
 * packet accepted).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "tdc_crc32.h"
#include "tdc_link.h"
#include "tdc_link_encode.h"
#include "test_link_util.h"
#include "golden/tdc_layer_content.h"

#define W 17 /* odd: partial tiles */
#define H 9
#define TX ((W + 1) / 2)
#define TY ((H + 1) / 2)
#define NT (TX * TY)

#define ALL_FLAGS 0x1Fu

static uint8_t staging[TDC_LINK_STAGING_LAYERS_BYTES(W, H)];
static uint8_t pattern[2][TDC_PATTERN_BYTES(W, H)];
static uint8_t subframe[2][NT * 3];
static int16_t sample_mv[2][NT * 2];
/* decoder planes per eye and a sender's planes */
static uint8_t d_val[2][TDC_LAYER_MAX][NT * 3];
static int16_t d_mv[2][TDC_LAYER_MAX][NT * 2];
static uint16_t d_w[2][NT];
static tdc_layer_frame_t d_frame[2];
static uint8_t s_val[TDC_LAYER_MAX][NT * 3];
static int16_t s_mv[TDC_LAYER_MAX][NT * 2];
static uint16_t s_w[NT];
static tdc_layer_frame_t s_frame;
static uint8_t pkt[64 + TDC_LINK_STAGING_LAYERS_BYTES(W, H)];
static const uint8_t kinds[TDC_LAYER_MAX] = {TDC_LAYER_MV_DUAL, TDC_LAYER_MV_SHADOW, TDC_LAYER_MV_GLOSSY,
                                             TDC_LAYER_MV_SURFACE};

static tdc_link_decoder_t dec;
static tdc_link_encoder_t enc;

static void fill_sender(uint32_t seed)
{
    for (int t = 0; t < TDC_LAYER_MAX; t++) {
        for (int k = 0; k < NT * 3; k++) {
            s_val[t][k] = (uint8_t)(seed * 31u + (uint32_t)(t * 7 + k) * 13u);
        }
        for (int k = 0; k < NT * 2; k++) {
            s_mv[t][k] = (int16_t)((int32_t)((seed + (uint32_t)t) * 977u + (uint32_t)k * 331u) % 4000 - 2000);
        }
        s_frame.value[t] = s_val[t];
        s_frame.mv[t] = s_mv[t];
    }
    for (int k = 0; k < NT; k++) {
        s_w[k] = (uint16_t)((seed * 1231u + (uint32_t)k * 977u) % 32769u);
    }
    s_frame.falloff = s_w;
}

static void setup_decoder(uint32_t sflags)
{
    tdc_link_config_t cfg = {W, H, 2};
    tdc_link_buffers_t b = lt_buffers(staging, sizeof staging);
    for (int e = 0; e < 2; e++) {
        TDC_LAYER_FRAME_WIRE(d_frame[e], d_val[e], d_mv[e], d_w[e]);
        b.layers[e] = &d_frame[e];
        b.pattern[e] = pattern[e];
        b.subframe[e] = subframe[e];
        b.sample_motion[e] = sample_mv[e];
    }
    assert_int_equal(tdc_link_decoder_init(&dec, &cfg, &b), TDC_OK);
    tdc_link_stream_info_t info = {sflags, 1, 1, W, H, 2, 0, 240};
    tdc_link_encoder_init(&enc, 7, &info);
    const size_t n = tdc_link_encode_stream(&enc, pkt, sizeof pkt);
    tdc_link_event_t ev;
    assert_int_equal(tdc_link_feed(&dec, pkt, n, &ev), n);
    assert_int_equal(ev.type, TDC_LINK_EV_PACKET);
}

/* Feeds n bytes; returns the event type of the first event (and *err). */
static int feed(size_t n, uint16_t *err)
{
    tdc_link_event_t ev;
    size_t used = 0;
    int type = TDC_LINK_EV_NONE;
    while (used < n || dec.ev_count) {
        used += tdc_link_feed(&dec, pkt + used, n - used, &ev);
        if (ev.type != TDC_LINK_EV_NONE && type == TDC_LINK_EV_NONE) {
            type = ev.type;
            *err = ev.error;
        }
        if (ev.type == TDC_LINK_EV_NONE) {
            break;
        }
    }
    return type;
}

static void test_sizes(void **state)
{
    (void)state;
    /* one layer: 7 bytes per tile + the layer header = SUBFRAME + MOTION payloads + 16 */
    const uint32_t one = TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING);
    assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_LAYERS, TDC_PIXFMT_NONE, W, H, one),
                     tdc_link_payload_bytes(TDC_LINK_KIND_SUBFRAME, TDC_PIXFMT_RGB888, W, H, 0) +
                         tdc_link_payload_bytes(TDC_LINK_KIND_MOTION, TDC_PIXFMT_NONE, W, H,
                                                TDC_LINK_PKT_MV_PER_SAMPLE) +
                         TDC_LAYER_HDR_BYTES);
    /* everything: 3+4, 1+4, 3+4, 3+4, 2 = 28 per tile */
    assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_LAYERS, TDC_PIXFMT_NONE, W, H, ALL_FLAGS), 16 + 28 * NT);
    assert_int_equal(TDC_LINK_STAGING_LAYERS_BYTES(W, H), 16 + 28 * NT);
    /* invalid sets: empty, falloff without visibility, visibility without shading, unknown bit */
    const uint32_t bad[] = {0u, TDC_LAYER_PKT_FALLOFF | 1u, TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY), 0x21u};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_false(tdc_layer_flags_valid(bad[i]));
        assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_LAYERS, TDC_PIXFMT_NONE, W, H, bad[i]), 0);
    }
}

/* Every layer set is decoded plane by plane, equal to what was sent. */
static void test_roundtrip(void **state)
{
    (void)state;
    setup_decoder(TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_LAYERS);
    uint32_t frame = 0;
    for (uint32_t flags = 1; flags <= ALL_FLAGS; flags++) {
        if (!tdc_layer_flags_valid(flags)) {
            continue;
        }
        for (uint32_t eye = 0; eye < 2; eye++) {
            fill_sender(flags * 2u + eye);
            memset(d_val, 0, sizeof d_val);
            const size_t n = tdc_link_encode_layers(&enc, pkt, sizeof pkt, eye, frame, &s_frame, flags, kinds, W, H);
            assert_int_equal(n, TDC_LINK_HEADER_BYTES + tdc_layer_payload_bytes(flags, NT));
            uint16_t err = 0;
            assert_int_equal(feed(n, &err), TDC_LINK_EV_PACKET);
            assert_int_equal(d_frame[eye].present, flags);
            for (uint32_t t = 1; t <= TDC_LAYER_MAX; t++) {
                if (flags & TDC_LAYER_PKT_TYPE(t)) {
                    assert_memory_equal(d_val[eye][t - 1], s_val[t - 1], NT * tdc_layer_value_bytes(t));
                    assert_memory_equal(d_mv[eye][t - 1], s_mv[t - 1], NT * 4);
                }
            }
            if (flags & TDC_LAYER_PKT_FALLOFF) {
                assert_memory_equal(d_w[eye], s_w, NT * 2);
            }
            assert_int_equal(d_frame[eye].hdr.tiles_x, TX);
            assert_int_equal(d_frame[eye].hdr.tiles_y, TY);
        }
        frame++;
    }
    assert_int_equal(tdc_link_counters(&dec)->packets_by_kind[TDC_LINK_KIND_LAYERS], 2u * (frame));
}

/* A stream that does not announce layers refuses LAYERS packets; a build
 * without layer planes refuses a stream that announces them. */
static void test_not_announced(void **state)
{
    (void)state;
    setup_decoder(TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_SAMPLE_MV);
    fill_sender(1);
    size_t n = tdc_link_encode_layers(&enc, pkt, sizeof pkt, 0, 0, &s_frame, 1u, kinds, W, H);
    uint16_t err = 0;
    assert_int_equal(feed(n, &err), TDC_LINK_EV_ERROR);
    assert_int_equal(err, TDC_LINK_ERR_UNEXPECTED);
    /* LAYERS without SUBFRAMES: stream header refused */
    tdc_link_stream_info_t info = {TDC_LINK_STREAM_LAYERS, 1, 1, W, H, 2, 0, 240};
    tdc_link_encoder_init(&enc, 9, &info);
    n = tdc_link_encode_stream(&enc, pkt, sizeof pkt);
    assert_int_equal(feed(n, &err), TDC_LINK_EV_ERROR);
    assert_int_equal(err, TDC_LINK_ERR_STREAM_HEADER);
}

/* Refusals: (what to damage, expected decoder code, expected layer reason). */
typedef struct {
    const char *what;
    uint16_t code;
    tdc_layer_err_t reason;
} bad_t;

/* Builds a damaged packet: payload byte `off` of a valid ALL_FLAGS packet
 * set to `val` (or header flags changed), CRCs made valid again. */
static size_t make_bad(int which)
{
    fill_sender(5);
    uint32_t flags = ALL_FLAGS;
    if (which == 9) {
        s_mv[TDC_LAYER_GLOSSY - 1][7] = TDC_LAYER_MV_SENTINEL;
    }
    if (which == 10) {
        s_w[NT - 1] = TDC_LAYER_W_ONE + 1u;
    }
    size_t n = tdc_link_encode_layers(&enc, pkt, sizeof pkt, 1, 100, &s_frame, flags, kinds, W, H);
    uint8_t *pl = pkt + TDC_LINK_HEADER_BYTES;
    switch (which) {
    case 0: pl[0] = 2; break;                          /* version */
    case 1: pl[1] = 3; break;                          /* count */
    case 2: pl[3] = TDC_LAYER_GLOSSY; break;           /* type order */
    case 3: pl[6 + 1] = TDC_LAYER_MV_GLOSSY; break;    /* visibility with a glossy vector */
    case 4: tdc_put_le16(pl + 12, TX + 1); break;      /* tiles_x */
    case 5: pl[11] = 1; break;                         /* reserved */
    case 6: pl[10] = 0; break;                         /* falloff flag disagrees with the packet's */
    case 7: pl[6 + 0] = 0; break;                      /* vector kind 0 for a present layer */
    case 8: pl[1] = 0; break;                          /* count 0 */
    default: break;                                    /* 9, 10: built above */
    }
    if (which <= 8) {
        /* payload CRC over the damaged payload, header CRC anew */
        tdc_link_header_t h;
        assert_int_equal(tdc_link_header_unpack(pkt, &h), TDC_LINK_OK);
        h.payload_crc = tdc_crc32(pl, h.payload_len);
        tdc_link_header_pack(pkt, &h);
    }
    return n;
}

static void test_refusals(void **state)
{
    (void)state;
    static const tdc_layer_err_t want[] = {
        TDC_LAYER_ERR_VERSION, TDC_LAYER_ERR_COUNT,    TDC_LAYER_ERR_TYPE,   TDC_LAYER_ERR_VECTOR,
        TDC_LAYER_ERR_SIZE,    TDC_LAYER_ERR_RESERVED, TDC_LAYER_ERR_RESERVED, TDC_LAYER_ERR_VECTOR,
        TDC_LAYER_ERR_COUNT,   TDC_LAYER_ERR_SENTINEL, TDC_LAYER_ERR_WEIGHT};
    uint32_t seen = 0;
    for (int which = 0; which < (int)(sizeof want / sizeof want[0]); which++) {
        setup_decoder(TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_LAYERS);
        /* a good frame first: what must be kept */
        fill_sender(3);
        size_t n = tdc_link_encode_layers(&enc, pkt, sizeof pkt, 1, 99, &s_frame, ALL_FLAGS, kinds, W, H);
        uint16_t err = 0;
        assert_int_equal(feed(n, &err), TDC_LINK_EV_PACKET);
        uint8_t keep_val[sizeof d_val];
        int16_t keep_mv[sizeof d_mv / 2];
        uint16_t keep_w[sizeof d_w / 2];
        memcpy(keep_val, d_val, sizeof d_val);
        memcpy(keep_mv, d_mv, sizeof d_mv);
        memcpy(keep_w, d_w, sizeof d_w);
        n = make_bad(which);
        assert_true(n > 0);
        err = 0;
        assert_int_equal(feed(n, &err), TDC_LINK_EV_ERROR);
        assert_int_equal(err, TDC_LINK_ERR_LAYERS);
        assert_int_equal(tdc_link_error_count(&dec, TDC_LINK_ERR_LAYERS), 1);
        assert_int_equal(tdc_link_counters(&dec)->layer_errors[want[which]], 1);
        assert_memory_equal(keep_val, d_val, sizeof d_val);
        assert_memory_equal(keep_mv, d_mv, sizeof d_mv);
        assert_memory_equal(keep_w, d_w, sizeof d_w);
        assert_string_not_equal(tdc_layer_err_name(want[which]), "TDC_LAYER_ERR_?");
        seen |= 1u << want[which];
        /* the same frame, sent right, is still accepted (nothing advanced) */
        fill_sender(4);
        n = tdc_link_encode_layers(&enc, pkt, sizeof pkt, 1, 100, &s_frame, ALL_FLAGS, kinds, W, H);
        assert_int_equal(feed(n, &err), TDC_LINK_EV_PACKET);
        assert_memory_equal(d_mv[1][1], s_mv[1], NT * 4);
    }
    assert_int_equal(seen, ((1u << TDC_LAYER_ERR_N) - 1u) & ~1u); /* every reason */
    assert_string_equal(tdc_layer_err_name(TDC_LAYER_ERR_N), "TDC_LAYER_ERR_?");
    assert_string_equal(tdc_link_err_name(TDC_LINK_ERR_LAYERS), "layers");
}

/* Header-level refusals: invalid flag sets (format), a length that is not
 * the flags' (length), a build missing a plane (unexpected). */
static void test_header_refusals(void **state)
{
    (void)state;
    setup_decoder(TDC_LINK_STREAM_SUBFRAMES | TDC_LINK_STREAM_LAYERS);
    fill_sender(2);
    size_t n = tdc_link_encode_layers(&enc, pkt, sizeof pkt, 0, 1, &s_frame, 3u, kinds, W, H);
    tdc_link_header_t h;
    assert_int_equal(tdc_link_header_unpack(pkt, &h), TDC_LINK_OK);
    uint16_t err;
    /* visibility without shading */
    h.flags = TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY);
    tdc_link_header_pack(pkt, &h);
    assert_int_equal(feed(n, &err), TDC_LINK_EV_ERROR);
    assert_int_equal(err, TDC_LINK_ERR_FORMAT);
    /* glossy only: valid flags, but the payload length is the 3-flag one */
    h.flags = TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY) | TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING);
    tdc_link_header_pack(pkt, &h);
    assert_int_equal(feed(n, &err), TDC_LINK_EV_ERROR);
    assert_int_equal(err, TDC_LINK_ERR_LENGTH);
    /* a build without the falloff plane */
    d_frame[0].falloff = NULL;
    n = tdc_link_encode_layers(&enc, pkt, sizeof pkt, 0, 2, &s_frame, ALL_FLAGS, kinds, W, H);
    assert_int_equal(feed(n, &err), TDC_LINK_EV_ERROR);
    assert_int_equal(err, TDC_LINK_ERR_UNEXPECTED);
    /* ... takes the same stream without falloff */
    n = tdc_link_encode_layers(&enc, pkt, sizeof pkt, 0, 2, &s_frame, 0xFu, kinds, W, H);
    assert_int_equal(feed(n, &err), TDC_LINK_EV_PACKET);
    /* the encoder refuses what it cannot describe */
    const uint8_t badk[TDC_LAYER_MAX] = {TDC_LAYER_MV_SHADOW, 0, 0, 0};
    assert_int_equal(tdc_link_encode_layers(&enc, pkt, sizeof pkt, 0, 3, &s_frame, 1u, badk, W, H), 0);
    assert_int_equal(tdc_link_encode_layers(&enc, pkt, 100, 0, 3, &s_frame, 1u, kinds, W, H), 0);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_sizes),           cmocka_unit_test(test_roundtrip),
    cmocka_unit_test(test_not_announced),   cmocka_unit_test(test_refusals),
    cmocka_unit_test(test_header_refusals),
)
