/*
 * test_wire.c - the wire-format module (firmware/tdc_wire.h): little-endian
 * fields, the packet header packer/unpacker, the STREAM payload, the kind
 * table and payload sizes.  Sizes are checked against the table of
 * docs/link-protocol.md §2, written out here independently of the kind
 * table.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "tdc_crc32.h"
#include "tdc_layer_link.h"
#include "tdc_wire.h"

static uint32_t rng(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return *s;
}

static void test_le_fields(void **state)
{
    (void)state;
    uint8_t b[4];
    tdc_put_le32(b, 0x11223344u);
    assert_int_equal(b[0], 0x44);
    assert_int_equal(b[1], 0x33);
    assert_int_equal(b[2], 0x22);
    assert_int_equal(b[3], 0x11);
    assert_int_equal(tdc_get_le32(b), 0x11223344u);
    assert_int_equal(tdc_get_le16(b), 0x3344u);
    assert_int_equal(tdc_get_le16(b + 2), 0x1122u);
    /* Every 16-bit value, unsigned and signed, round-trips with the
     * two's complement byte pattern. */
    for (int32_t v = -32768; v <= 32767; v++) {
        tdc_put_le16s(b, (int16_t)v);
        const uint32_t bits = (uint32_t)(v < 0 ? v + 65536 : v);
        assert_int_equal(b[0], bits & 0xFFu);
        assert_int_equal(b[1], bits >> 8);
        assert_int_equal(tdc_get_le16s(b), v);
        assert_int_equal(tdc_get_le16(b), bits);
        tdc_put_le16(b + 2, bits);
        assert_memory_equal(b, b + 2, 2);
    }
    uint32_t s = 12345u;
    for (int i = 0; i < 10000; i++) {
        const uint32_t v = rng(&s);
        tdc_put_le32(b, v);
        assert_int_equal(tdc_get_le32(b), v);
        assert_int_equal(tdc_get_le16(b) | ((uint32_t)tdc_get_le16(b + 2) << 16), v);
    }
}

static void random_header(tdc_link_header_t *h, uint32_t *s)
{
    h->version = (uint8_t)rng(s);
    h->kind = (uint8_t)rng(s);
    h->eye = (uint8_t)rng(s);
    h->format = (uint8_t)rng(s);
    h->stream_id = (uint16_t)rng(s);
    h->flags = (uint16_t)rng(s);
    h->frame_index = rng(s);
    h->width = (uint16_t)rng(s);
    h->height = (uint16_t)rng(s);
    h->payload_len = rng(s);
    h->payload_crc = rng(s);
}

static void test_header_pack_unpack(void **state)
{
    (void)state;
    /* Field positions of docs/link-protocol.md §1.1. */
    const tdc_link_header_t h = {1, 2, 1, 4, 0xBEEF, 0x0001, 0x01020304u, 1440, 1600, 0x00ABCDEFu, 0xCAFEF00Du};
    uint8_t b[TDC_LINK_HEADER_BYTES];
    memset(b, 0x55, sizeof b);
    tdc_link_header_pack(b, &h);
    const uint8_t want[28] = {'T',  'D',  'C',  'L',  1,    2,    1,    4,    0xEF, 0xBE, 0x01, 0x00, 0x04, 0x03,
                              0x02, 0x01, 0xA0, 0x05, 0x40, 0x06, 0xEF, 0xCD, 0xAB, 0x00, 0x0D, 0xF0, 0xFE, 0xCA};
    assert_memory_equal(b, want, sizeof want);
    assert_int_equal(tdc_get_le32(b + TDC_LINK_OFF_HEADER_CRC), tdc_crc32(b, 28));
    tdc_link_header_t u;
    assert_int_equal(tdc_link_header_unpack(b, &u), TDC_LINK_OK);
    assert_memory_equal(&u, &h, sizeof u);

    /* Random fields round-trip; every header byte is a field (no reserved
     * bytes), so unpack + pack reproduces the bytes exactly. */
    uint32_t s = 777u;
    for (int i = 0; i < 2000; i++) {
        tdc_link_header_t r, back;
        memset(&r, 0, sizeof r);
        memset(&back, 0xA5, sizeof back);
        random_header(&r, &s);
        tdc_link_header_pack(b, &r);
        assert_int_equal(tdc_link_header_unpack(b, &back), TDC_LINK_OK);
        assert_memory_equal(&back, &r, sizeof r);
        uint8_t b2[TDC_LINK_HEADER_BYTES];
        tdc_link_header_pack(b2, &back);
        assert_memory_equal(b2, b, sizeof b);
        /* Any single flipped bit is caught: in the magic as MAGIC, anywhere
         * else (fields or the CRC itself) as HEADER_CRC; fields are still
         * filled. */
        const unsigned bit = rng(&s) % (8u * TDC_LINK_HEADER_BYTES);
        b2[bit / 8u] ^= (uint8_t)(1u << (bit % 8u));
        const tdc_link_err_t e = tdc_link_header_unpack(b2, &back);
        assert_int_equal(e, bit < 32u ? TDC_LINK_ERR_MAGIC : TDC_LINK_ERR_HEADER_CRC);
        if (bit >= 32u && bit < 8u * TDC_LINK_OFF_HEADER_CRC) {
            assert_memory_not_equal(&back, &r, sizeof r);
        }
    }
}

static void test_stream_pack_unpack(void **state)
{
    (void)state;
    const tdc_link_stream_info_t in = {0x00000013u, 1, 2, 1440, 1600, 2, 0, 90};
    uint8_t b[TDC_LINK_STREAM_HEADER_BYTES];
    tdc_link_stream_pack(b, &in);
    const uint8_t want[16] = {0x13, 0, 0, 0, 1, 0, 2, 0, 0xA0, 0x05, 0x40, 0x06, 2, 0, 90, 0};
    assert_memory_equal(b, want, sizeof want);
    tdc_link_stream_info_t out;
    memset(&out, 0xFF, sizeof out);
    tdc_link_stream_unpack(b, &out);
    assert_memory_equal(&out, &in, sizeof in);
    assert_int_equal(sizeof(tdc_link_stream_info_t), TDC_LINK_STREAM_HEADER_BYTES); /* no padding: memcmp-able */
}

static void test_kind_table(void **state)
{
    (void)state;
    static const char *const names[] = {"stream",  "full",    "reduced", "subframe",
                                        "motion",  "pattern", "foveated", "layers"};
    for (uint32_t k = TDC_LINK_KIND_FIRST; k <= TDC_LINK_KIND_LAST; k++) {
        const tdc_link_kind_info_t *ki = tdc_link_kind_info(k);
        assert_non_null(ki);
        assert_string_equal(ki->name, names[k - TDC_LINK_KIND_FIRST]);
        assert_string_equal(tdc_link_kind_name(k), ki->name);
        assert_int_equal(ki->pkt_flags & ~(k == TDC_LINK_KIND_LAYERS ? TDC_LAYER_PKT_KNOWN : TDC_LINK_PKT_KNOWN), 0);
    }
    const uint32_t unknown[] = {0, TDC_LINK_KIND_LAST + 1u, 255u, 0xFFFFFFFFu};
    for (size_t i = 0; i < sizeof unknown / sizeof unknown[0]; i++) {
        assert_null(tdc_link_kind_info(unknown[i]));
        assert_string_equal(tdc_link_kind_name(unknown[i]), "?");
        assert_int_equal(tdc_link_payload_bytes((tdc_link_kind_t)unknown[i], TDC_PIXFMT_RGB888, 8, 8, 0), 0);
    }
    /* Only MOTION may carry MV_PER_SAMPLE. */
    assert_int_equal(tdc_link_kind_info(TDC_LINK_KIND_MOTION)->pkt_flags, TDC_LINK_PKT_MV_PER_SAMPLE);
    /* FULL and REDUCED may be row bands (tdc_band_link.h) */
    assert_int_equal(tdc_link_kind_info(TDC_LINK_KIND_FULL)->pkt_flags, TDC_LINK_PKT_BAND);
    assert_int_equal(tdc_link_kind_info(TDC_LINK_KIND_REDUCED)->pkt_flags, TDC_LINK_PKT_BAND);
}

/* Payload sizes = the table of docs/link-protocol.md §2, written out. */
static void test_payload_sizes(void **state)
{
    (void)state;
    static const uint32_t dims[] = {1, 2, 3, 7, 8, 9, 33, 64, 1080, 1439, 1440, 1600, 2160};
    for (size_t a = 0; a < sizeof dims / sizeof dims[0]; a++) {
        for (size_t c = 0; c < sizeof dims / sizeof dims[0]; c++) {
            const uint32_t w = dims[a], h = dims[c];
            const uint32_t tx = (w + 1u) / 2u, ty = (h + 1u) / 2u;
            assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_STREAM, TDC_PIXFMT_NONE, w, h, 0), 16);
            for (uint32_t f = TDC_PIXFMT_RGB888; f < TDC_PIXFMT_COUNT; f++) {
                assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_FULL, (tdc_pixfmt_t)f, w, h, 0),
                                 tdc_pixfmt_payload_bytes((tdc_pixfmt_t)f, w, h));
                assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_REDUCED, (tdc_pixfmt_t)f, w, h, 0),
                                 tdc_pixfmt_payload_bytes((tdc_pixfmt_t)f, w, h));
                assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_SUBFRAME, (tdc_pixfmt_t)f, w, h, 0),
                                 tdc_pixfmt_payload_bytes((tdc_pixfmt_t)f, tx, ty));
            }
            assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_FULL, TDC_PIXFMT_RGB888, w, h, 0), w * h * 3u);
            assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_FULL, TDC_PIXFMT_NONE, w, h, 0), 0);
            assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_MOTION, TDC_PIXFMT_NONE, w, h, 0), w * h * 4u);
            assert_int_equal(
                tdc_link_payload_bytes(TDC_LINK_KIND_MOTION, TDC_PIXFMT_NONE, w, h, TDC_LINK_PKT_MV_PER_SAMPLE),
                tx * ty * 4u);
            assert_int_equal(tdc_link_payload_bytes(TDC_LINK_KIND_PATTERN, TDC_PIXFMT_NONE, w, h, 0),
                             (tx * ty + 7u) / 8u);
            /* The buffer-size macros agree with the payload of their kind. */
            assert_int_equal(TDC_LINK_FRAME_BYTES(w, h),
                             tdc_link_payload_bytes(TDC_LINK_KIND_FULL, TDC_PIXFMT_RGB888, w, h, 0));
            assert_int_equal(TDC_LINK_SUBFRAME_BYTES(w, h),
                             tdc_link_payload_bytes(TDC_LINK_KIND_SUBFRAME, TDC_PIXFMT_RGB888, w, h, 0));
            assert_int_equal(TDC_LINK_MOTION_COUNT(w, h) * 2u,
                             tdc_link_payload_bytes(TDC_LINK_KIND_MOTION, TDC_PIXFMT_NONE, w, h, 0));
            assert_int_equal(
                TDC_LINK_SAMPLE_MOTION_COUNT(w, h) * 2u,
                tdc_link_payload_bytes(TDC_LINK_KIND_MOTION, TDC_PIXFMT_NONE, w, h, TDC_LINK_PKT_MV_PER_SAMPLE));
            assert_int_equal(TDC_PATTERN_BYTES(w, h),
                             tdc_link_payload_bytes(TDC_LINK_KIND_PATTERN, TDC_PIXFMT_NONE, w, h, 0));
            assert_int_equal(tdc_link_packet_bytes(TDC_LINK_KIND_PATTERN, TDC_PIXFMT_NONE, w, h, 0),
                             TDC_LINK_HEADER_BYTES + (tx * ty + 7u) / 8u);
        }
    }
    /* Packet sizes refuse what a 32-bit payload length cannot carry. */
    assert_int_equal(tdc_link_packet_bytes(TDC_LINK_KIND_FULL, TDC_PIXFMT_RGB888, 0, 8, 0), 0);
    assert_int_equal(tdc_link_packet_bytes(TDC_LINK_KIND_FULL, TDC_PIXFMT_RGB888, 65536, 1, 0), 0);
    assert_int_equal(tdc_link_packet_bytes(TDC_LINK_KIND_MOTION, TDC_PIXFMT_NONE, 16384, 16385, 0), 0);
    assert_int_equal(tdc_link_packet_bytes(TDC_LINK_KIND_MOTION, TDC_PIXFMT_NONE, 16384, 16384, 0),
                     TDC_LINK_HEADER_BYTES + 16384u * 16384u * 4u);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_le_fields),          cmocka_unit_test(test_header_pack_unpack),
    cmocka_unit_test(test_stream_pack_unpack), cmocka_unit_test(test_kind_table),
    cmocka_unit_test(test_payload_sizes),
)
