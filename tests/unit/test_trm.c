/*
 * test_trm.c - TRM API contract: configuration errors, refusal below the
 * minimum refresh, call order, arena bounds, pass-through elision, stereo
 * eye alternation and per-stage counters.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include "golden/tdc_content.h"
#include "tdc_math.h"
#include "tdc_trm_kernels.h"
#include "trm_fixture.h"

static void test_config_errors(void **state)
{
    (void)state;
    tdc_trm_config_t cfg;
    trm_fix_t f;
    tdc_trm_default_config(&cfg, 40, 30, 90);
    cfg.r_num = 1;
    cfg.r_den = 5; /* r = 0.2 < 1/4 */
    assert_int_equal(tdc_trm_get_size(&cfg), 0);
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_ERR_RATIO);
    trm_fix_close(&f);
    cfg.r_num = 3;
    cfg.r_den = 2; /* r > 1 */
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_ERR_RATIO);
    trm_fix_close(&f);
    tdc_trm_default_config(&cfg, 40, 30, 90);
    cfg.sigma_q8 = 2000; /* beyond the kernel tables */
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_ERR_ARG);
    trm_fix_close(&f);
    /* arena one byte short */
    tdc_trm_default_config(&cfg, 40, 30, 90);
    size_t n = tdc_trm_get_size(&cfg);
    static uint64_t arena[65536];
    tdc_trm_t trm;
    assert_true(n <= sizeof arena);
    assert_int_equal(tdc_trm_init(&trm, &cfg, &tdc_panel_htc_vive, arena, n - 1), TDC_ERR_SIZE);
    assert_int_equal(tdc_trm_init(&trm, &cfg, &tdc_panel_htc_vive, arena, n), TDC_OK);
    assert_int_equal(tdc_trm_init(NULL, &cfg, &tdc_panel_htc_vive, arena, n), TDC_ERR_ARG);
}

static void test_refuses_low_refresh(void **state)
{
    (void)state;
    tdc_trm_config_t cfg;
    trm_fix_t f;
    tdc_trm_default_config(&cfg, 40, 30, 60);
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_ERR_REFRESH_LOW);
    trm_fix_close(&f);
    tdc_trm_default_config(&cfg, 40, 30, 89);
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_ERR_REFRESH_LOW);
    trm_fix_close(&f);
    tdc_trm_default_config(&cfg, 40, 30, 90);
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_OK);
    trm_fix_close(&f);
    /* r = 1 is no TRM at all: allowed at any refresh */
    tdc_trm_default_config(&cfg, 40, 30, 60);
    cfg.r_num = cfg.r_den = 1;
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_OK);
    trm_fix_close(&f);
}

static void test_call_order_keeps_last_frame(void **state)
{
    (void)state;
    tdc_trm_config_t cfg;
    trm_fix_t f;
    tdc_trm_default_config(&cfg, 41, 29, 90);
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_OK);
    memset(f.out, 0x5a, (size_t)f.w * f.h * 3);
    memset(f.red, 100, (size_t)f.w * f.h * 3);
    /* a reduced frame with no full frame before it is refused, out untouched */
    assert_int_equal(tdc_trm_reduced(&f.trm, f.red, f.trm.rw * 3u, f.out, (uint32_t)f.w * 3u), TDC_ERR_STATE);
    for (size_t i = 0; i < (size_t)f.w * f.h * 3; i++) {
        assert_int_equal(f.out[i], 0x5a);
    }
    tdc_content_frame(TDC_CONTENT_TEXT, 0, 1, f.in, f.w, f.h, f.w * 3);
    assert_int_equal(trm_fix_full(&f), TDC_OK);
    assert_int_equal(trm_fix_reduced_of_in(&f), TDC_OK);
    /* after a reset the history is gone again */
    tdc_trm_reset(&f.trm);
    assert_int_equal(tdc_trm_reduced(&f.trm, f.red, f.trm.rw * 3u, f.out, (uint32_t)f.w * 3u), TDC_ERR_STATE);
    /* bad strides */
    assert_int_equal(tdc_trm_full(&f.trm, f.in, 3u, f.out, (uint32_t)f.w * 3u), TDC_ERR_ARG);
    trm_fix_close(&f);
}

static void test_arena_bound(void **state)
{
    (void)state;
    static const uint16_t sizes[][2] = {{1, 1}, {2, 3}, {97, 67}, {1080, 1200}, {1440, 1600}, {1919, 1081}};
    static const uint16_t ratios[][2] = {{1, 4}, {2, 5}, {1, 2}, {3, 4}, {1, 1}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        for (size_t r = 0; r < sizeof ratios / sizeof ratios[0]; r++) {
            tdc_trm_config_t cfg;
            tdc_trm_default_config(&cfg, sizes[i][0], sizes[i][1], 90);
            cfg.r_num = ratios[r][0];
            cfg.r_den = ratios[r][1];
            cfg.sigma_q8 = TDC_TRM_MAX_SIGMA_Q8;
            size_t n = tdc_trm_get_size(&cfg);
            assert_true(n > 0);
            /* the compile-time bound at the board's largest ratio (r=1) holds */
            assert_true(n <= TDC_TRM_MEM_BYTES(sizes[i][0], sizes[i][1], 1, 1));
        }
    }
}

static void test_passthrough_elision(void **state)
{
    (void)state;
    tdc_trm_config_t cfg;
    trm_fix_t f;
    /* r = 1: the stream carries no reduced frames, TRM does no work */
    tdc_trm_default_config(&cfg, 33, 17, 120);
    cfg.r_num = cfg.r_den = 1;
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_rift_cv1), TDC_OK);
    for (uint32_t t = 0; t < 5; t++) {
        tdc_content_frame(TDC_CONTENT_NOISE, t, 3, f.in, f.w, f.h, f.w * 3);
        assert_int_equal(trm_fix_full(&f), TDC_OK);
        assert_memory_equal(f.in, f.out, (size_t)f.w * f.h * 3);
    }
    assert_int_equal(f.trm.stats.passthrough_frames, 5);
    assert_true(tdc_trm_get_size(&cfg) <= 8u); /* no arena: any board takes an r = 1 stream */
    assert_int_equal(f.trm.stats.full_frames, 0);
    assert_int_equal(f.trm.stats.weight_computed, 0);
    trm_fix_close(&f);
    /* r = 1/2 but the stream header says no reduced frames */
    tdc_trm_default_config(&cfg, 33, 17, 90);
    cfg.reduced_in_stream = 0;
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_rift_cv1), TDC_OK);
    tdc_content_frame(TDC_CONTENT_EDGE, 0, 3, f.in, f.w, f.h, f.w * 3);
    assert_int_equal(trm_fix_full(&f), TDC_OK);
    assert_memory_equal(f.in, f.out, (size_t)f.w * f.h * 3);
    assert_int_equal(tdc_trm_reduced(&f.trm, f.red, f.trm.rw * 3u, f.out, (uint32_t)f.w * 3u), TDC_ERR_STATE);
    trm_fix_close(&f);
}

static void test_static_pair_skips_weight(void **state)
{
    (void)state;
    tdc_trm_config_t cfg;
    trm_fix_t f;
    tdc_trm_default_config(&cfg, 64, 48, 90);
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_OK);
    /* static text: renderer's reduced frame is D(I) itself, rounded; where
     * U(D(I)) equals U(i) exactly the weight is known to be 1 */
    tdc_content_frame(TDC_CONTENT_CHECKER, 0, 1, f.in, f.w, f.h, f.w * 3);
    assert_int_equal(trm_fix_full(&f), TDC_OK);
    assert_int_equal(trm_fix_reduced_of_in(&f), TDC_OK);
    const tdc_trm_stats_t *s = &f.trm.stats;
    printf("static checker pair: weight computed %llu, skipped (c = 0 known) %llu, no residual %llu\n",
           (unsigned long long)s->weight_computed, (unsigned long long)s->weight_skipped,
           (unsigned long long)s->residual_skipped);
    assert_true(s->weight_skipped > 0);
    assert_int_equal(s->weight_computed + s->weight_skipped + s->residual_skipped, (uint64_t)f.w * f.h * 3);
    /* a flat frame has no residual at all: nothing computed */
    tdc_content_frame(TDC_CONTENT_WHITE, 0, 1, f.in, f.w, f.h, f.w * 3);
    uint64_t before = s->weight_computed + s->weight_skipped;
    assert_int_equal(trm_fix_full(&f), TDC_OK);
    assert_int_equal(trm_fix_reduced_of_in(&f), TDC_OK);
    assert_int_equal(s->weight_computed + s->weight_skipped, before);
    trm_fix_close(&f);
}

/* Stereo: eye 0 full on even frames, eye 1 on odd; each eye's output must be
 * exactly what that eye's own mono sequence gives. */
static void test_stereo_alternation(void **state)
{
    (void)state;
    assert_true(tdc_trm_stereo_eye_is_full(0, 0));
    assert_false(tdc_trm_stereo_eye_is_full(0, 1));
    assert_false(tdc_trm_stereo_eye_is_full(1, 0));
    assert_true(tdc_trm_stereo_eye_is_full(1, 1));
    tdc_trm_config_t cfg;
    tdc_trm_default_config(&cfg, 30, 20, 90);
    trm_fix_t eye[2], mono;
    for (int e = 0; e < 2; e++) {
        assert_int_equal(trm_fix_open(&eye[e], &cfg, &tdc_panel_htc_vive), TDC_OK);
    }
    assert_int_equal(trm_fix_open(&mono, &cfg, &tdc_panel_htc_vive), TDC_OK);
    for (uint32_t t = 0; t < 9; t++) {
        for (int e = 0; e < 2; e++) {
            tdc_content_frame(TDC_CONTENT_EDGE, t, (uint32_t)e, eye[e].in, 30, 20, 90);
            if (tdc_trm_stereo_eye_is_full(t, e)) {
                assert_int_equal(trm_fix_full(&eye[e]), TDC_OK);
            } else if (t > 0) {
                assert_int_equal(trm_fix_reduced_of_in(&eye[e]), TDC_OK);
            }
        }
        /* mono replay of eye 1 (full on odd frames) */
        tdc_content_frame(TDC_CONTENT_EDGE, t, 1, mono.in, 30, 20, 90);
        if (t & 1u) {
            assert_int_equal(trm_fix_full(&mono), TDC_OK);
        } else if (t > 0) {
            assert_int_equal(trm_fix_reduced_of_in(&mono), TDC_OK);
        }
        if (t > 0) {
            assert_memory_equal(mono.out, eye[1].out, 30 * 20 * 3);
        }
    }
    assert_int_equal(eye[0].trm.stats.full_frames, 5);
    assert_int_equal(eye[1].trm.stats.full_frames, 4);
    trm_fix_close(&eye[0]);
    trm_fix_close(&eye[1]);
    trm_fix_close(&mono);
}

/* A whole frame through tdc_trm_split/_d_band/_band/_join with nb bands,
 * run last band first (each band on its own buffers, as on the row
 * workers); pic: the full frame (in place) or the reduced frame. */
static tdc_status_t banded_frame(trm_fix_t *f, int full, uint32_t seq, uint32_t nb, tdc_trm_rowbuf_t *bufs)
{
    const uint32_t w3 = (uint32_t)f->w * 3u;
    tdc_status_t st = full ? tdc_trm_full_begin(&f->trm, f->out, w3, f->out, w3)
                           : tdc_trm_reduced_begin(&f->trm, f->red, (uint32_t)f->trm.rw * 3u, f->out, w3, seq);
    uint32_t d_rows = 99;
    st = st == TDC_OK ? tdc_trm_split(&f->trm, &d_rows) : st;
    if (st != TDC_OK) {
        return st;
    }
    assert_int_equal(d_rows, full ? f->trm.rh : 0u);
    for (uint32_t i = nb; i-- > 0;) {
        tdc_trm_d_band(&f->trm, d_rows * i / nb, d_rows * (i + 1u) / nb, &bufs[i]);
    }
    uint64_t n[3] = {0, 0, 0};
    for (uint32_t i = nb; i-- > 0;) {
        tdc_trm_band(&f->trm, (uint32_t)f->h * i / nb, (uint32_t)f->h * (i + 1u) / nb, &bufs[i], n);
    }
    tdc_trm_join(&f->trm, n);
    return full ? tdc_trm_full_end(&f->trm, seq) : tdc_trm_reduced_end(&f->trm);
}

/* Row bands (the Linux board's row workers): the same bytes and counters
 * as whole frames for 1-4 bands (band boundaries inside D's kernel reach
 * at this size), full frames in place, paired and unpaired reduced ones;
 * the buffers' checks. */
static void test_row_bands(void **state)
{
    (void)state;
    tdc_trm_config_t cfg;
    tdc_trm_default_config(&cfg, 61, 47, 90);
    trm_fix_t whole, band;
    assert_int_equal(trm_fix_open(&whole, &cfg, &tdc_panel_htc_vive), TDC_OK);
    assert_int_equal(trm_fix_open(&band, &cfg, &tdc_panel_htc_vive), TDC_OK);
    const size_t bytes = TDC_TRM_ROWBUF_BYTES(61u, band.trm.rw);
    uint64_t *mem = malloc(4u * bytes + 8u);
    tdc_trm_rowbuf_t bufs[4];
    bufs[0] = tdc_trm_rowbuf_own(&band.trm);
    assert_int_equal(tdc_trm_rowbuf_init(&band.trm, &bufs[1], mem, bytes - 8u), TDC_ERR_SIZE);
    assert_int_equal(tdc_trm_rowbuf_init(&band.trm, &bufs[1], (uint8_t *)mem + 4, bytes), TDC_ERR_ARG);
    for (uint32_t i = 1; i < 4; i++) {
        assert_int_equal(tdc_trm_rowbuf_init(&band.trm, &bufs[i], (uint8_t *)mem + (i - 1u) * bytes, bytes), TDC_OK);
    }
    uint32_t d = 0;
    assert_int_equal(tdc_trm_split(&band.trm, &d), TDC_ERR_STATE); /* no frame open */
    const uint32_t w3 = 61u * 3u, rw3 = (uint32_t)whole.trm.rw * 3u;
    /* frame 0 reduced (unpaired: no full frame yet), then full / reduced */
    for (uint32_t t = 0; t < 7; t++) {
        const int full = t % 2u == 1u;
        tdc_content_frame(TDC_CONTENT_EDGE, t, 0, whole.in, 61, 47, 90);
        if (full) {
            memcpy(whole.out, whole.in, (size_t)w3 * 47u);
            memcpy(band.out, whole.in, (size_t)w3 * 47u);
            assert_int_equal(tdc_trm_full_seq(&whole.trm, whole.out, w3, whole.out, w3, t), TDC_OK);
        } else {
            assert_int_equal(tdc_trm_downsample(&whole.trm, whole.in, w3, whole.red, rw3), TDC_OK);
            memcpy(band.red, whole.red, (size_t)rw3 * whole.trm.rh);
            assert_int_equal(tdc_trm_reduced_seq(&whole.trm, whole.red, rw3, whole.out, w3, t), TDC_OK);
        }
        assert_int_equal(banded_frame(&band, full, t, 1u + t % 4u, bufs), TDC_OK);
        assert_memory_equal(band.out, whole.out, (size_t)w3 * 47u);
    }
    assert_int_equal(band.trm.stats.reduced_unpaired, 1);
    assert_memory_equal(&band.trm.stats, &whole.trm.stats, sizeof whole.trm.stats);
    free(mem);
    trm_fix_close(&whole);
    trm_fix_close(&band);
}

/* The reduced path's weight table against double exp(-x). */
static void test_weight_accuracy(void **state)
{
    (void)state;
    tdc_trm_config_t cfg;
    trm_fix_t f;
    tdc_trm_default_config(&cfg, 8, 8, 90);
    assert_int_equal(trm_fix_open(&f, &cfg, &tdc_panel_htc_vive), TDC_OK);
    double max_err = 0.0;
    int32_t prev = 32768;
    for (uint32_t x = 0; x < (20u << 16); x += 7u) {
        int32_t got = tdc_trm_weight(&f.trm, x);
        double err = fabs(got - 32768.0 * exp(-(double)x / 65536.0));
        max_err = err > max_err ? err : max_err;
        assert_true(got <= prev && got >= 0);
        prev = got;
    }
    assert_int_equal(tdc_trm_weight(&f.trm, 0), 32768);
    printf("motion weight table: max error %.3f LSB (Q15), bound 0.6\n", max_err);
    assert_true(max_err <= 0.6);
    trm_fix_close(&f);
}

/* The generated weight table (tdc-tablegen --trm) holds exactly the values
 * of the firmware's exact helper, which the stage computed at init before
 * the table was generated (so every TRM golden vector is unchanged). */
static void test_weight_table_generated(void **state)
{
    (void)state;
    uint32_t bad = 0;
    for (uint32_t k = 0; k < TDC_TRM_WEXP_ENTRIES; k++) {
        bad += tdc_trm_wexp_q30[k] != tdc_exp_neg_q16_q30(k << 8);
    }
    assert_int_equal(bad, 0);
    assert_int_equal(tdc_trm_wexp_q30[0], 1u << 30);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_config_errors),
    cmocka_unit_test(test_refuses_low_refresh),
    cmocka_unit_test(test_call_order_keeps_last_frame),
    cmocka_unit_test(test_arena_bound),
    cmocka_unit_test(test_passthrough_elision),
    cmocka_unit_test(test_static_pair_skips_weight),
    cmocka_unit_test(test_stereo_alternation),
    cmocka_unit_test(test_row_bands),
    cmocka_unit_test(test_weight_accuracy),
    cmocka_unit_test(test_weight_table_generated),
)
