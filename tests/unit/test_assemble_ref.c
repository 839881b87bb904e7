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

/*
 * The reference's clamp neighbourhoods (TDRT Fig. 7, tdc_ref_asm_set_nbhd), on a 6x6 frame (3x3 tiles):
 * four static frames of code 100, then every tile moves 1 px and traces code 200 at its top-left pixel
 * (hourglass, k = 0), except the corner tile (0,0), which traces 0.  An old pixel of the centre tile
 * reprojects 100 and is clamped to the box of
 *   NEWEST  its immediate neighbours in the newest subframe: all 200 (pixel (0,0) is beside none of them)
 *   ALL     all 8 neighbours, old ones reprojected (100): the old value widens the box and survives (ghost)
 *   SUB3X3  the 9 tiles' newest samples (eight 200s and one 0): mean 177.8, sd 62.9 -> 114.9, so 115
 */
static void run_nbhd(tdc_ref_nbhd_t nbhd, uint8_t out[6 * 6 * 3], uint8_t isnew_out[36])
{
    tdc_ref_asm_t *r = tdc_ref_asm_new(6, 6);
    assert_non_null(r);
    tdc_ref_asm_set_nbhd(r, nbhd);
    uint8_t samples[9 * 3], bits[TDC_PATTERN_BYTES(6, 6)];
    int16_t mvs[9 * 2];
    memset(bits, 0, sizeof(bits)); /* hourglass everywhere */
    for (uint32_t f = 0; f < 5; f++) {
        for (int t = 0; t < 9; t++) {
            uint8_t v = f < 4 ? 100 : (t == 0 ? 0 : 200);
            memset(samples + t * 3, v, 3);
            mvs[t * 2] = f < 4 ? 0 : 16, mvs[t * 2 + 1] = 0;
        }
        assert_int_equal(tdc_ref_asm_ingest(r, f, samples, mvs, (f & 3) == 0 ? bits : NULL), 0);
        assert_int_equal(tdc_ref_asm_assemble(r, f), 0);
    }
    memcpy(out, tdc_ref_asm_output(r), 6 * 6 * 3);
    /* which pixels frame 4 traced: the hourglass ordering's position 0 in every tile */
    memset(isnew_out, 0, 36);
    unsigned pos = tdc_ordering_pixel(TDC_ORDER_HOURGLASS, 0);
    for (int t = 0; t < 9; t++) isnew_out[(2 * (t / 3) + (int)(pos >> 1)) * 6 + 2 * (t % 3) + (int)(pos & 1u)] = 1;
    tdc_ref_asm_free(r);
}

static void test_nbhd_variants(void **state)
{
    (void)state;
    uint8_t o[3][6 * 6 * 3], isnew[36];
    run_nbhd(TDC_REF_NBHD_NEWEST, o[0], isnew);
    run_nbhd(TDC_REF_NBHD_ALL, o[1], isnew);
    run_nbhd(TDC_REF_NBHD_SUB3X3, o[2], isnew);
    int old = 0;
    for (int y = 2; y < 4; y++)
        for (int x = 2; x < 4; x++) {
            const int p = (y * 6 + x) * 3;
            if (isnew[y * 6 + x]) {
                for (int k = 0; k < 3; k++) assert_int_equal(o[k][p], 200); /* a new pixel is its sample */
                continue;
            }
            old++;
            assert_int_equal(o[0][p], 200); /* NEWEST: clamped into the new samples' box */
            assert_int_equal(o[1][p], 100); /* ALL: the old value is in its own box */
            assert_int_equal(o[2][p], 115); /* SUB3X3: the corner tile's 0 widens the box */
        }
    assert_int_equal(old, 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_fixed_vs_float), cmocka_unit_test(test_nbhd_variants)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
