/*
 * test_link_mask.c - a board build that compiles pixel formats out
 * (TDC_LINK_FORMAT_MASK): the decoder source is compiled here with only
 * RGB888 enabled; RGB888 frames decode, every other format is rejected with
 * TDC_LINK_ERR_FORMAT and leaves the frame buffer untouched.
 */
#define TDC_LINK_FORMAT_MASK (1u << 1) /* RGB888 only */
#include "../firmware/tdc_link.c"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_link_encode.h"
#include "link/tdc_link_gen.h"
#include "test_link_util.h"

#define W 17
#define H 9

static uint8_t staging[TDC_LINK_STAGING_BYTES(W, H)], frame[W * H * 3], src[W * H * 3], pkt[4096];

static void test_only_rgb888_compiled_in(void **state)
{
    (void)state;
    static tdc_link_decoder_t dec;
    tdc_link_config_t cfg = {W, H, 1};
    tdc_link_buffers_t b = lt_buffers(staging, sizeof staging);
    b.full[0] = frame;
    b.full_stride = W * 3;
    assert_int_equal(tdc_link_decoder_init(&dec, &cfg, &b), TDC_OK);
    tdc_link_stream_info_t in;
    memset(&in, 0, sizeof in);
    in.r_num = in.r_den = 1;
    in.width = W;
    in.height = H;
    in.eyes = 1;
    tdc_link_encoder_t enc;
    tdc_link_encoder_init(&enc, 1, &in);
    tdc_link_event_t ev;
    size_t n = tdc_link_encode_stream(&enc, pkt, sizeof pkt);
    assert_int_equal(tdc_link_feed(&dec, pkt, n, &ev), n);
    assert_int_equal(ev.type, TDC_LINK_EV_PACKET);
    tdc_link_gen_rgb(src, W, H, 0, 0, 3);
    n = tdc_link_encode_frame(&enc, pkt, sizeof pkt, TDC_LINK_KIND_FULL, 0, 0, TDC_PIXFMT_RGB888, src, W, H, W * 3);
    assert_int_equal(tdc_link_feed(&dec, pkt, n, &ev), n);
    assert_int_equal(ev.type, TDC_LINK_EV_PACKET);
    assert_memory_equal(frame, src, sizeof frame);
    for (uint32_t f = TDC_PIXFMT_RGB565; f < TDC_PIXFMT_COUNT; f++) {
        tdc_link_gen_rgb(src, W, H, f, 0, 4);
        n = tdc_link_encode_frame(&enc, pkt, sizeof pkt, TDC_LINK_KIND_FULL, 0, f, (tdc_pixfmt_t)f, src, W, H, W * 3);
        uint8_t before[sizeof frame];
        memcpy(before, frame, sizeof frame);
        size_t used = 0;
        ev.type = TDC_LINK_EV_NONE;
        while (used < n && ev.type == TDC_LINK_EV_NONE) {
            used += tdc_link_feed(&dec, pkt + used, n - used, &ev);
        }
        assert_int_equal(ev.type, TDC_LINK_EV_ERROR);
        assert_int_equal(ev.error, TDC_LINK_ERR_FORMAT);
        tdc_link_feed(&dec, pkt + used, n - used, &ev); /* the skipped payload */
        assert_memory_equal(frame, before, sizeof frame);
    }
    assert_int_equal(tdc_link_error_count(&dec, TDC_LINK_ERR_FORMAT), 3);
    assert_int_equal(tdc_link_counters(&dec)->packets_ok, 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_only_rgb888_compiled_in)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
