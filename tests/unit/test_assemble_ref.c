/*
 * test_assemble_ref.c - fixed-point assembly against the double-precision
 * reference (ref/ref_assemble.c), closed loop: both run the same synthetic
 * subframe streams (pans at integer, fractional, diagonal, large speeds,
 * moving 1-px lines, a static scene, dropped subframes) at an odd size.
 * Report: share of output bytes within 1 LSB of the reference's 8-bit
 * output, largest difference, largest distance to the unrounded reference.
 * Targets (team standard): >= 99.9 % within 1 LSB, none beyond 2 LSB.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ref_assemble.h"
#include "tdc_assemble.h"

typedef struct {
    const char *name;
    tdc_scene_kind_t kind;
    int32_t vx, vy; /* Q4 px/frame */
    int drop_every; /* drop the subframe of every n-th frame (0: none) */
    int with_bits;  /* stream carries pattern bits */
} scenario_t;

static const scenario_t scenarios[] = {
    {"static", TDC_SCENE_STATIC, 0, 0, 0, 1},
    {"pan 3.5 px x", TDC_SCENE_PAN, 56, 0, 0, 1},
    {"pan 1.125 px x", TDC_SCENE_PAN, 18, 0, 0, 1},
    {"pan 2.5 px y", TDC_SCENE_PAN, 0, 40, 0, 1},
    {"pan (2.3,-1.3) px", TDC_SCENE_PAN, 37, -21, 0, 1},
    {"pan 45 deg 2.5 px", TDC_SCENE_PAN, 40, 40, 0, 1},
    {"pan slow (-0.44,0.19)", TDC_SCENE_PAN, -7, 3, 0, 0},
    {"pan fast (12.5,5.6)", TDC_SCENE_PAN, 200, 90, 0, 0},
    {"pan + drops", TDC_SCENE_PAN, 24, 8, 7, 1},
    {"1-px lines 1.5 px x", TDC_SCENE_LINE, 24, 0, 0, 1},
    {"1-px lines -1.25 px y", TDC_SCENE_HLINE, 0, -20, 0, 1},
};

static void run_scenario(const scenario_t *sc, int w, int h, int frames, tdc_asm_err_t *total)
{
    tdc_asm_config_t cfg = {(uint16_t)w, (uint16_t)h};
    size_t n = tdc_asm_get_size(&cfg);
    void *arena = aligned_alloc(TDC_ARENA_ALIGN, TDC_ARENA_ROUND(n));
    tdc_asm_t st;
    assert_non_null(arena);
    assert_int_equal(tdc_asm_init(&st, &cfg, arena, n), TDC_OK);
    tdc_ref_asm_t *ref = tdc_ref_asm_new(w, h);
    tdc_scene_t scene;
    assert_int_equal(tdc_scene_init(&scene, sc->kind, w, h, sc->vx, sc->vy, 7), 0);
    size_t tiles = (size_t)((w + 1) / 2) * ((h + 1) / 2);
    uint8_t *samples = malloc(tiles * 3), *bits = calloc((size_t)TDC_PATTERN_BYTES(w, h), 1);
    int16_t *mvs = malloc(tiles * 4);
    tdc_asm_err_t e;
    memset(&e, 0, sizeof(e));
    for (int f = 0; f < frames; f++) {
        tdc_scene_subframe(&scene, (uint32_t)f, samples, mvs, bits);
        int drop = sc->drop_every && f % sc->drop_every == sc->drop_every - 1;
        const uint8_t *b = sc->with_bits && (f & 3) == 0 ? bits : NULL;
        if (!drop) {
            assert_int_equal(tdc_asm_ingest(&st, (uint32_t)f, samples, mvs, b), TDC_OK);
            assert_int_equal(tdc_ref_asm_ingest(ref, (uint32_t)f, samples, mvs, b), 0);
        }
        assert_int_equal(tdc_asm_assemble(&st, (uint32_t)f), TDC_OK);
        assert_int_equal(tdc_ref_asm_assemble(ref, (uint32_t)f), 0);
        /* Both sides must use the same orderings (fixed vs double decision
         * when the stream carries no bits). */
        if ((f & 3) != 3) /* after frame 4c+3 the stage already holds the next cycle's */
            assert_memory_equal(tdc_asm_pattern(&st), scene.pattern, (size_t)TDC_PATTERN_BYTES(w, h));
        tdc_asm_err_add(&e, tdc_asm_output(&st, NULL), tdc_ref_asm_output(ref), tdc_ref_asm_output_exact(ref),
                        (size_t)w * h * 3);
    }
    printf("  %-24s within 1 LSB %9.5f %%  max %d LSB  (0:%llu 1:%llu 2:%llu >2:%llu)  max vs exact %.3f  "
           "reproj %llu clamp %llu pattern disagree %u/%u\n",
           sc->name, 100.0 * (double)(e.hist[0] + e.hist[1]) / (double)e.n, e.max_abs, (unsigned long long)e.hist[0],
           (unsigned long long)e.hist[1], (unsigned long long)e.hist[2], (unsigned long long)e.hist[3], e.max_exact,
           (unsigned long long)st.stats.reprojected, (unsigned long long)st.stats.clamp_boxes,
           st.stats.pattern_disagreements, st.stats.pattern_checks);
    assert_int_equal(st.stats.pattern_disagreements, 0);
    total->n += e.n;
    for (int i = 0; i < 4; i++) total->hist[i] += e.hist[i];
    if (e.max_abs > total->max_abs) total->max_abs = e.max_abs;
    if (e.max_exact > total->max_exact) total->max_exact = e.max_exact;
    free(samples), free(bits), free(mvs), free(arena);
    tdc_ref_asm_free(ref);
    tdc_scene_free(&scene);
}

static void test_fixed_vs_float(void **state)
{
    (void)state;
    tdc_asm_err_t total;
    memset(&total, 0, sizeof(total));
    printf("assembly fixed vs double reference, 67x45, 48 frames per stream:\n");
    for (size_t i = 0; i < sizeof(scenarios) / sizeof(scenarios[0]); i++)
        run_scenario(&scenarios[i], 67, 45, 48, &total);
    double share = (double)(total.hist[0] + total.hist[1]) / (double)total.n;
    printf("assembly error report: %llu output bytes, %.4f %% within 1 LSB (target >= 99.9 %%), "
           "%.4f %% exact, max %d LSB (target <= 2), max vs unrounded reference %.3f LSB\n",
           (unsigned long long)total.n, 100.0 * share, 100.0 * (double)total.hist[0] / (double)total.n, total.max_abs,
           total.max_exact);
    assert_true(share >= 0.999);
    assert_true(total.max_abs <= 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_fixed_vs_float)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
