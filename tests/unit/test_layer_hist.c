/*
 * test_layer_hist.c - the per-layer history (firmware/tdc_layer_hist.h)
 * against its double-precision reference (ref/ref_layer_hist.c), closed
 * loop: both run the same noisy panning layers (tests/golden/
 * tdc_lhist_content.h) at an odd size for 40 frames, 1 and 3 channels, no
 * clamp / 1 sigma / 3 sigma, with and without eq. 4 falloff, tracked and
 * random vectors (some leaving the frame).  Per scenario: share of output
 * bytes within 1 LSB of the unrounded reference, the largest difference,
 * the largest error of the Q8 history.  Target (team standard): >= 99.9 %
 * within 1 LSB.  Also: the arena's refusals, a known answer of eq. 2, and
 * that the history averages the noise (output error below the input's).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "golden/tdc_lhist_content.h"
#include "ref_layer_hist.h"
#include "tdc_layer_hist.h"

#define W 37
#define H 23
#define FRAMES 40

static uint64_t g_arena[TDC_LHIST_MEM_BYTES(W, H) / 8u];

typedef struct {
    const char *name;
    tdc_lhist_content_t c;
    uint8_t k;
    uint16_t alpha;
} scen_t;

static const scen_t scens[] = {
    {"pan, 3 ch, 3 sigma", {W, H, 3, 30, 20, -6, 0, 0, 1u}, 3, 3277},
    {"pan, 3 ch, 1 sigma", {W, H, 3, 30, 20, -6, 0, 0, 2u}, 1, 3277},
    {"pan, 3 ch, no clamp", {W, H, 3, 30, 20, -6, 0, 0, 3u}, 0, 3277},
    {"visibility, falloff, 3 sigma", {W, H, 1, 60, -12, 4, 0, 1, 4u}, 3, 3277},
    {"random vectors, 3 sigma", {W, H, 3, 20, 0, 0, 40, 0, 5u}, 3, 3277},
    {"random vectors, falloff, alpha 0.2", {W, H, 1, 20, 0, 0, 300, 1, 6u}, 1, 6554},
};

static void test_vs_reference(void **state)
{
    (void)state;
    static uint8_t x[W * H * 3];
    static int16_t mv[W * H * 2];
    static uint16_t g[W * H];
    uint64_t total = 0, within = 0;
    double worst = 0;
    for (size_t s = 0; s < sizeof scens / sizeof scens[0]; s++) {
        const scen_t *sc = &scens[s];
        const tdc_lhist_config_t cfg = {W, H, sc->c.ch, sc->k, sc->alpha};
        tdc_lhist_t st;
        tdc_ref_lhist_t ref;
        assert_int_equal(tdc_lhist_init(&st, &cfg, g_arena, sizeof g_arena), TDC_OK);
        assert_int_equal(tdc_ref_lhist_init(&ref, &cfg), 0);
        uint64_t n = 0, in1 = 0;
        double maxd = 0, maxh = 0;
        for (uint32_t f = 0; f < FRAMES; f++) {
            tdc_lhist_content(&sc->c, f, x, mv, g);
            assert_int_equal(tdc_lhist_step(&st, x, mv, sc->c.falloff ? g : NULL), TDC_OK);
            tdc_ref_lhist_step(&ref, x, mv, sc->c.falloff ? g : NULL);
            const uint8_t *o = tdc_lhist_output(&st);
            const uint16_t *hq = tdc_lhist_history_q8(&st);
            for (size_t i = 0; i < (size_t)W * H * sc->c.ch; i++) {
                const double d = fabs(o[i] - ref.out[i]);
                maxd = d > maxd ? d : maxd;
                in1 += d <= 1.0;
                n++;
                const double dh = fabs(hq[i] / 256.0 - ref.out[i]);
                maxh = dh > maxh ? dh : maxh;
            }
        }
        print_message("%-36s within 1 LSB %.4f %%, max %.3f LSB, Q8 history max error %.4f LSB, clamped %llu, "
                      "reset %llu\n", sc->name, 100.0 * in1 / n, maxd, maxh, (unsigned long long)st.stats.clamped,
                      (unsigned long long)st.stats.reset);
        /* the history never drifts: alpha contracts each step's rounding */
        assert_true(maxh < 0.1);
        total += n;
        within += in1;
        worst = maxd > worst ? maxd : worst;
        tdc_ref_lhist_free(&ref);
    }
    print_message("all: %.4f %% within 1 LSB, max %.3f LSB\n", 100.0 * within / total, worst);
    assert_true(within >= total - total / 1000u);
    assert_true(worst < 1.1);
}

static void test_known_answer(void **state)
{
    (void)state;
    /* history 200, new frame 100, zero vectors, no clamp, alpha 3277:
     * (3277 * 25600 + 29491 * 51200 + 16384) >> 15 = 48640 (Q8), 190 */
    const tdc_lhist_config_t cfg = {5, 4, 1, 0, 3277};
    tdc_lhist_t st;
    static uint8_t x[20];
    assert_int_equal(tdc_lhist_init(&st, &cfg, g_arena, sizeof g_arena), TDC_OK);
    memset(x, 200, sizeof x);
    assert_int_equal(tdc_lhist_step(&st, x, NULL, NULL), TDC_OK);
    assert_int_equal(tdc_lhist_output(&st)[7], 200); /* first frame: no history */
    memset(x, 100, sizeof x);
    assert_int_equal(tdc_lhist_step(&st, x, NULL, NULL), TDC_OK);
    assert_int_equal(tdc_lhist_history_q8(&st)[7], 48640);
    assert_int_equal(tdc_lhist_output(&st)[7], 190);
    /* eq. 4 with G = 0: alpha^V = 1, the new frame alone */
    static uint16_t g0[20];
    assert_int_equal(tdc_lhist_step(&st, x, NULL, g0), TDC_OK);
    assert_int_equal(tdc_lhist_history_q8(&st)[7], 100 * 256);
    /* a constant neighbourhood (sigma 0) clamps any history to it */
    const tdc_lhist_config_t c3 = {5, 4, 1, 3, 3277};
    assert_int_equal(tdc_lhist_init(&st, &c3, g_arena, sizeof g_arena), TDC_OK);
    memset(x, 200, sizeof x);
    assert_int_equal(tdc_lhist_step(&st, x, NULL, NULL), TDC_OK);
    memset(x, 100, sizeof x);
    assert_int_equal(tdc_lhist_step(&st, x, NULL, NULL), TDC_OK);
    assert_int_equal(tdc_lhist_output(&st)[7], 100);
    assert_int_equal(st.stats.clamped, 20);
}

static void test_denoises(void **state)
{
    (void)state;
    /* a still noisy layer (+-40): after 30 frames the output's error to
     * the noise-free layer is a fraction of the input's */
    static uint8_t x[W * H * 3], clean[W * H * 3];
    static int16_t mv[W * H * 2];
    static uint16_t g[W * H];
    const tdc_lhist_content_t noisy = {W, H, 3, 40, 0, 0, 0, 0, 9u}, flat = {W, H, 3, 0, 0, 0, 0, 0, 9u};
    const tdc_lhist_config_t cfg = {W, H, 3, 3, 3277};
    tdc_lhist_t st;
    assert_int_equal(tdc_lhist_init(&st, &cfg, g_arena, sizeof g_arena), TDC_OK);
    tdc_lhist_content(&flat, 0, clean, mv, g);
    double ein = 0, eout = 0;
    for (uint32_t f = 0; f < 30; f++) {
        tdc_lhist_content(&noisy, f, x, mv, g);
        assert_int_equal(tdc_lhist_step(&st, x, mv, NULL), TDC_OK);
    }
    for (size_t i = 0; i < sizeof x; i++) {
        ein += (x[i] - clean[i]) * (double)(x[i] - clean[i]);
        eout += (tdc_lhist_output(&st)[i] - clean[i]) * (double)(tdc_lhist_output(&st)[i] - clean[i]);
    }
    print_message("still noisy layer: RMSE in %.2f, out %.2f\n", sqrt(ein / sizeof x), sqrt(eout / sizeof x));
    assert_true(eout < 0.25 * ein);
}

static void test_refusals(void **state)
{
    (void)state;
    tdc_lhist_config_t cfg = {W, H, 3, 3, 3277};
    tdc_lhist_t st;
    const size_t need = tdc_lhist_get_size(&cfg);
    assert_int_equal(need, TDC_LHIST_MEM_BYTES(W, H));
    assert_int_equal(tdc_lhist_init(&st, &cfg, g_arena, need - 8u), TDC_ERR_SIZE);
    assert_int_equal(tdc_lhist_init(&st, &cfg, (uint8_t *)g_arena + 4, need), TDC_ERR_ARG);
    assert_int_equal(tdc_lhist_init(&st, &cfg, g_arena, need), TDC_OK);
    assert_int_equal(tdc_lhist_step(&st, NULL, NULL, NULL), TDC_ERR_ARG);
    const tdc_lhist_config_t bad[] = {{0, H, 3, 3, 3277}, {W, H, 2, 3, 3277}, {W, H, 3, 2, 3277},
                                      {W, H, 3, 3, 0},    {W, 5000, 3, 3, 1}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(tdc_lhist_get_size(&bad[i]), 0);
        assert_int_equal(tdc_lhist_init(&st, &bad[i], g_arena, sizeof g_arena), TDC_ERR_ARG);
    }
    /* one channel needs a third of three */
    cfg.channels = 1;
    assert_true(tdc_lhist_get_size(&cfg) * 3 <= need + 24);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vs_reference), cmocka_unit_test(test_known_answer), cmocka_unit_test(test_denoises),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
