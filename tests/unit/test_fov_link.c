/*
 * test_fov_link.c - the foveation header of the foveated link kind
 * (firmware/tdc_fov_link.c): pack/parse round trip on every panel size,
 * the payload length from the geometry, each rule refused with its named
 * reason (alpha, delta, disk above 1, gaze far outside, buffer size against
 * the panel, stated u0 / disk count, reserved bits), and every single-bit
 * flip of a valid header either refused or parsed to a self-consistent
 * header (never a crash, never a payload length that disagrees with it).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "tdc_fov_link.h"

static void le16(uint8_t *b, uint16_t v)
{
    b[0] = (uint8_t)v;
    b[1] = (uint8_t)(v >> 8);
}

static void test_round_trip(void **state)
{
    (void)state;
    static const uint16_t sizes[][2] = {{1080, 1200}, {1920, 1080}, {2560, 1440}, {37, 29}};
    for (unsigned s = 0; s < 4; s++) {
        const uint16_t W = sizes[s][0], H = sizes[s][1];
        for (int k = 0; k < 3; k++) {
            const uint16_t delta = k == 2 ? 32768 : 18187; /* 0.555, quantised up */
            tdc_fov_params_t p = {W * 128 + 77 * k,          H * 100,
                                  (uint16_t)(256 + 700 * k), (uint16_t)(4077 * k),
                                  tdc_fov_lp_size(delta, W), tdc_fov_lp_size(delta, H), {0, 0}, 0, 0};
            uint8_t hdr[TDC_FOV_HDR_BYTES];
            assert_int_equal(tdc_fov_hdr_pack(hdr, W, H, &p, delta, (uint8_t)(k & 1)), TDC_OK);
            tdc_fov_hdr_t h;
            assert_int_equal(tdc_fov_hdr_parse(hdr, W, H, &h), TDC_FOV_HDR_OK);
            assert_memory_equal(&h.p, &p, sizeof p);
            assert_int_equal(h.delta_q15, delta);
            if (delta == 18187) { /* the quantised-up 0.555 gives floor(0.555 n) */
                assert_int_equal(p.lp_w, W * 555 / 1000);
                assert_int_equal(p.lp_h, H * 555 / 1000);
            }
            assert_int_equal(h.flags, k & 1);
            const uint32_t lp = (uint32_t)(h.g.lp_w - h.g.u0) * h.g.lp_h;
            assert_int_equal(h.payload_bytes, 3 * lp + 3 * tdc_fov_disk_pixels(&h.g) + ((k & 1) ? 4 * lp : 0));
            assert_int_equal(tdc_fov_payload_check(&h, h.payload_bytes), TDC_FOV_HDR_OK);
            assert_int_equal(tdc_fov_payload_check(&h, h.payload_bytes - 1), TDC_FOV_HDR_PAYLOAD); /* truncated */
            assert_int_equal(tdc_fov_payload_check(&h, h.payload_bytes + 3), TDC_FOV_HDR_PAYLOAD);
            /* the same header does not fit another panel */
            assert_int_equal(tdc_fov_hdr_parse(hdr, (uint16_t)(W + 2), H, &h), TDC_FOV_HDR_BUFFER);
        }
    }
}

/* One header field overwritten (little-endian, len bytes at off) and the reason it must be refused for. */
typedef struct {
    unsigned off, len;
    uint32_t v;
    tdc_fov_hdr_err_t want;
} hdr_case_t;

static void check_cases(const char *kind, const uint8_t good[TDC_FOV_HDR_BYTES], const hdr_case_t *cases, unsigned n,
                        uint16_t W, uint16_t H)
{
    for (unsigned c = 0; c < n; c++) {
        uint8_t b[TDC_FOV_HDR_BYTES];
        memcpy(b, good, sizeof b);
        for (unsigned i = 0; i < cases[c].len; i++) b[cases[c].off + i] = (uint8_t)(cases[c].v >> (8 * i));
        tdc_fov_hdr_t h;
        const tdc_fov_hdr_err_t e = tdc_fov_hdr_parse(b, W, H, &h);
        if (e != cases[c].want)
            fail_msg("%s case %u: got %s want %s", kind, c, tdc_fov_hdr_err_name(e),
                     tdc_fov_hdr_err_name(cases[c].want));
    }
}

static void test_named_rejections(void **state)
{
    (void)state;
    const uint16_t W = 1080, H = 1200;
    const tdc_fov_params_t p = {W * 128, H * 128, 1024, 4077, 599, 666, {0, 0}, 0, 0};
    uint8_t good[TDC_FOV_HDR_BYTES], b[TDC_FOV_HDR_BYTES];
    assert_int_equal(tdc_fov_hdr_pack(good, W, H, &p, 18187, 1), TDC_OK);
    tdc_fov_hdr_t h;
    static const hdr_case_t cases[] = {
        {8, 2, 255, TDC_FOV_HDR_ALPHA},
        {8, 2, 2049, TDC_FOV_HDR_ALPHA},
        {10, 2, 0, TDC_FOV_HDR_DELTA},
        {10, 2, 32769, TDC_FOV_HDR_DELTA},
        {12, 2, 32769, TDC_FOV_HDR_DISK},
        {0, 4, 2 * 1080 * 256 + 1, TDC_FOV_HDR_GAZE},
        {4, 4, 0xFFFFFFFFu - 1200 * 256, TDC_FOV_HDR_GAZE}, /* -1200 px - 1 Q8 */
        {14, 2, 600, TDC_FOV_HDR_BUFFER},
        {16, 2, 665, TDC_FOV_HDR_BUFFER},
        {18, 2, 0, TDC_FOV_HDR_GEOMETRY},
        {20, 4, 1, TDC_FOV_HDR_GEOMETRY},
        {24, 1, 2, TDC_FOV_HDR_RESERVED},
        {31, 1, 1, TDC_FOV_HDR_RESERVED},
        {30, 1, 1, TDC_FOV_HDR_RESERVED},
        {26, 2, 300, TDC_FOV_HDR_RESERVED}, /* k on a kernel log-polar header */
        {25, 1, 2, TDC_FOV_HDR_TRANSFORM},
        {25, 1, 1, TDC_FOV_HDR_ALPHA}, /* log-rectilinear with alpha 4 */
    };
    check_cases("kernel log-polar", good, cases, sizeof cases / sizeof cases[0], W, H);
    /* gaze exactly one screen outside: accepted */
    memcpy(b, good, sizeof b);
    tdc_fov_params_t q = p;
    q.gaze_x_q8 = -W * 256;
    q.gaze_y_q8 = 2 * H * 256;
    assert_int_equal(tdc_fov_hdr_pack(b, W, H, &q, 18187, 0), TDC_OK);
    assert_int_equal(tdc_fov_hdr_parse(b, W, H, &h), TDC_FOV_HDR_OK);
    assert_int_equal(h.p.gaze_x_q8, -W * 256);
    le16(b + 8, 1024);
    assert_string_equal(tdc_fov_hdr_err_name(TDC_FOV_HDR_GEOMETRY), "TDC_FOV_HDR_GEOMETRY");
    assert_string_equal(tdc_fov_hdr_err_name((tdc_fov_hdr_err_t)99), "TDC_FOV_HDR_?");
    assert_int_equal(tdc_fov_hdr_pack(b, W, H, &q, 18187, 2), TDC_ERR_ARG);
    /* log-rectilinear: packed and parsed back, each of its own refusals */
    tdc_fov_params_t r = p;
    r.alpha_q8 = 256;
    r.transform = TDC_FOV_LOG_RECT;
    r.lr_k_q4[0] = 4600;
    r.lr_k_q4[1] = 65535;
    assert_int_equal(tdc_fov_hdr_pack(b, W, H, &r, 18187, 1), TDC_OK);
    assert_int_equal(b[25], 1);
    assert_int_equal(tdc_fov_hdr_parse(b, W, H, &h), TDC_FOV_HDR_OK);
    assert_memory_equal(&h.p, &r, sizeof r);
    assert_int_equal(h.g.u0, 0);
    assert_int_equal(h.payload_bytes, 7u * 599u * 666u + 3u * tdc_fov_disk_pixels(&h.g));
    uint8_t lr[TDC_FOV_HDR_BYTES];
    memcpy(lr, b, sizeof lr);
    static const hdr_case_t lcases[] = {
        {26, 2, 0, TDC_FOV_HDR_SCALE},    {26, 2, 15, TDC_FOV_HDR_SCALE}, {28, 2, 0, TDC_FOV_HDR_SCALE},
        {8, 2, 257, TDC_FOV_HDR_ALPHA},   {25, 1, 9, TDC_FOV_HDR_TRANSFORM}, {18, 2, 3, TDC_FOV_HDR_GEOMETRY},
        {14, 2, 598, TDC_FOV_HDR_BUFFER}, {30, 2, 1, TDC_FOV_HDR_RESERVED},
    };
    check_cases("log-rectilinear", lr, lcases, sizeof lcases / sizeof lcases[0], W, H);
    r.lr_k_q4[1] = 15; /* the sender cannot pack what the receiver refuses */
    assert_int_equal(tdc_fov_hdr_pack(b, W, H, &r, 18187, 0), TDC_ERR_ARG);
    assert_string_equal(tdc_fov_hdr_err_name(TDC_FOV_HDR_SCALE), "TDC_FOV_HDR_SCALE");
}

static void test_bit_flips(void **state)
{
    (void)state;
    const uint16_t W = 640, H = 360;
    const tdc_fov_params_t p = {W * 110, H * 140, 1024, 4077, 355, 199, {0, 0}, 0, 0};
    uint8_t good[TDC_FOV_HDR_BYTES];
    assert_int_equal(tdc_fov_hdr_pack(good, W, H, &p, 18187, 1), TDC_OK);
    int refused = 0, accepted = 0;
    for (unsigned bit = 0; bit < 8 * TDC_FOV_HDR_BYTES; bit++) {
        uint8_t b[TDC_FOV_HDR_BYTES];
        memcpy(b, good, sizeof b);
        b[bit / 8] ^= (uint8_t)(1u << (bit % 8));
        tdc_fov_hdr_t h;
        if (tdc_fov_hdr_parse(b, W, H, &h) != TDC_FOV_HDR_OK) {
            refused++;
            continue;
        }
        accepted++; /* a different but valid header (e.g. a gaze moved by a fraction of a pixel) */
        assert_int_equal(h.payload_bytes, tdc_fov_payload_bytes(&h.g, h.flags & 1));
    }
    printf("single-bit flips of a header: %d refused, %d accepted as another valid header (the packet CRC "
           "catches those)\n",
           refused, accepted);
    assert_true(refused > accepted);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_round_trip), cmocka_unit_test(test_named_rejections),
                                       cmocka_unit_test(test_bit_flips)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
