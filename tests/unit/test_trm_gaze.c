/*
 * test_trm_gaze.c - gaze-aware TRM (firmware/tdc_trm_gaze.h):
 *   - the strength k(u) against the double reference on a dense grid of
 *     retinal motions and at the extremes (max error in Q15 LSB, share
 *     within 1 LSB);
 *   - full and reduced frames with a mixed map (k from 1 down to kmin)
 *     against ref_trm with the per-pixel strength (max LSB, share within
 *     1 LSB: >= 99.9 %, <= 2 LSB, as TRM's own target);
 *   - off state: no map, a detached map and an all-k = 1 map give TRM's
 *     bytes; in a row with a k < 1 tile the other tiles are TRM's bytes too;
 *   - k = 0 everywhere: full frames pass unchanged, reduced frames are U(i)
 *     alone (the unpaired path's bytes);
 *   - bad input: invalid configurations, short or unaligned arenas, NULL,
 *     wrong counts and the INT16_MIN sentinel refused, the last map kept.
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

#include "tdc_cmocka.h"

#include "golden/tdc_content.h"
#include "ref_trm.h"
#include "ref_trm_gaze.h"
#include "tdc_panels.h"
#include "tdc_trm.h"
#include "tdc_trm_gaze.h"

static void test_strength_vs_reference(void **state)
{
    (void)state;
    static const uint16_t kmins[] = {0u, 8192u, 32768u};
    for (int km = 0; km < 3; km++) {
        tdc_trm_gaze_config_t c;
        tdc_trm_gaze_default_config(&c, 64, 64);
        c.kmin_q15 = kmins[km];
        double maxe = 0.0;
        long n = 0, within = 0;
        for (int dy = -48; dy <= 48; dy++) {
            for (int dx = -48; dx <= 48; dx++) {
                double r = 32768.0 * tdc_ref_trm_gaze_strength(c.u0_q4 / 16.0, c.u1_q4 / 16.0, c.kmin_q15 / 32768.0,
                                                                dx / 16.0, dy / 16.0);
                double e = fabs((double)tdc_trm_gaze_strength_q15(&c, dx, dy) - r);
                maxe = fmax(maxe, e);
                within += e <= 1.0;
                n++;
            }
        }
        print_message("  kmin %5u: k(u) vs double on %ld retinal motions: max %.3f Q15 LSB, %.2f %% within 1 LSB\n",
                      kmins[km], n, maxe, 100.0 * within / n);
        assert_true(maxe <= 0.5 + 1e-9); /* one rounding */
        /* extremes: the largest differences of two int16, both signs */
        assert_int_equal(tdc_trm_gaze_strength_q15(&c, 65534, -65534), c.kmin_q15);
        assert_int_equal(tdc_trm_gaze_strength_q15(&c, -65534, 0), c.kmin_q15);
        assert_int_equal(tdc_trm_gaze_strength_q15(&c, 0, 0), 32768);
        assert_int_equal(tdc_trm_gaze_strength_q15(&c, c.u0_q4, 0), 32768);
        assert_int_equal(tdc_trm_gaze_strength_q15(&c, 0, c.u1_q4), c.kmin_q15);
    }
}

typedef struct {
    tdc_trm_t trm;
    tdc_trm_gaze_t gaze;
    void *mem, *gmem;
    int w, h;
} stage_t;

static void stage_init(stage_t *s, int w, int h, int rn, int rd, int tile, uint16_t kmin, int attach)
{
    tdc_trm_config_t cfg;
    tdc_trm_default_config(&cfg, (uint16_t)w, (uint16_t)h, 90);
    cfg.r_num = (uint16_t)rn;
    cfg.r_den = (uint16_t)rd;
    size_t n = tdc_trm_get_size(&cfg);
    s->mem = malloc(n);
    assert_int_equal(tdc_trm_init(&s->trm, &cfg, &tdc_panel_htc_vive, s->mem, n), TDC_OK);
    tdc_trm_gaze_config_t gc;
    tdc_trm_gaze_default_config(&gc, (uint16_t)w, (uint16_t)h);
    gc.tile = (uint16_t)tile;
    gc.kmin_q15 = kmin;
    size_t gn = tdc_trm_gaze_get_size(&gc);
    assert_true(gn > 0 && gn <= TDC_TRM_GAZE_MEM_BYTES(w, h, (uint32_t)tile));
    s->gmem = malloc(gn);
    assert_int_equal(tdc_trm_gaze_init(&s->gaze, &gc, s->gmem, gn), TDC_OK);
    if (attach) {
        assert_int_equal(tdc_trm_set_gaze(&s->trm, &s->gaze), TDC_OK);
    }
    s->w = w;
    s->h = h;
}

static void stage_free(stage_t *s)
{
    free(s->mem);
    free(s->gmem);
}

/* Tile motions (Q4): a ramp 0 .. 3 px/frame in x, alternating 0 / 0.75 px in y. */
static void ramp_map(const tdc_trm_gaze_t *g, int16_t *mv)
{
    for (uint32_t j = 0; j < g->ty; j++) {
        for (uint32_t i = 0; i < g->tx; i++) {
            mv[2 * (j * g->tx + i)] = (int16_t)(48 * i / (g->tx > 1 ? g->tx - 1 : 1));
            mv[2 * (j * g->tx + i) + 1] = (int16_t)((j & 1u) ? 12 : 0);
        }
    }
}

static void test_frames_vs_reference(void **state)
{
    (void)state;
    static const tdc_content_t contents[] = {TDC_CONTENT_EDGE, TDC_CONTENT_TEXT, TDC_CONTENT_NOISE, TDC_CONTENT_CHECKER,
                                             TDC_CONTENT_GRADIENT};
    static const int ratios[][2] = {{1, 2}, {1, 4}};
    const int w = 97, h = 67, tile = 8;
    int fail = 0;
    printf("gaze-aware TRM, fixed point vs double reference (htc-vive, 97x67, 8-px tiles, ramp map):\n");
    for (size_t ci = 0; ci < sizeof contents / sizeof contents[0]; ci++) {
        for (int ri = 0; ri < 2; ri++) {
            stage_t s;
            stage_init(&s, w, h, ratios[ri][0], ratios[ri][1], tile, 4096u, 1);
            int16_t *mv = malloc(sizeof(int16_t) * 2 * s.gaze.tx * s.gaze.ty);
            ramp_map(&s.gaze, mv);
            double gam[3];
            for (int c = 0; c < 3; c++) {
                gam[c] = tdc_panel_htc_vive.gamma_micro[c] / 1e6;
            }
            tdc_ref_trm_t ref;
            assert_int_equal(tdc_ref_trm_init(&ref, w, h, ratios[ri][0], ratios[ri][1], s.trm.cfg.sigma_q8 / 256.0,
                                              s.trm.cfg.s_q8 / 256.0, gam),
                             0);
            double *mx = malloc(sizeof(double) * s.gaze.tx * s.gaze.ty), *my = malloc(sizeof(double) * s.gaze.tx * s.gaze.ty);
            double *kmap = malloc(sizeof(double) * w * h);
            for (uint32_t i = 0; i < s.gaze.tx * s.gaze.ty; i++) {
                mx[i] = mv[2 * i] / 16.0;
                my[i] = mv[2 * i + 1] / 16.0;
            }
            tdc_ref_trm_gaze_map(w, h, tile, s.gaze.cfg.u0_q4 / 16.0, s.gaze.cfg.u1_q4 / 16.0, 4096.0 / 32768.0, mx, my,
                                 0.0, 0.0, kmap);
            ref.strength = kmap;
            size_t n = (size_t)w * h * 3;
            uint8_t *in = malloc(n), *a = malloc(n), *b = malloc(n), *red = malloc(n);
            double emax[2] = {0, 0};
            long en[2] = {0, 0}, ew[2] = {0, 0};
            for (uint32_t t = 0; t < 8; t += 2) {
                tdc_content_frame(contents[ci], t, 7u, in, w, h, w * 3);
                assert_int_equal(tdc_trm_gaze_update(&s.gaze, mv, s.gaze.tx * s.gaze.ty, 0, 0), TDC_OK);
                assert_int_equal(tdc_trm_full(&s.trm, in, (uint32_t)w * 3, a, (uint32_t)w * 3), TDC_OK);
                tdc_ref_trm_full(&ref, in, b, NULL);
                for (int pass = 0; pass < 2; pass++) {
                    if (pass == 1) {
                        tdc_content_frame(contents[ci], t + 1, 7u, in, w, h, w * 3);
                        assert_int_equal(tdc_trm_downsample(&s.trm, in, (uint32_t)w * 3, red, (uint32_t)s.trm.rw * 3),
                                         TDC_OK);
                        assert_int_equal(tdc_trm_reduced(&s.trm, red, (uint32_t)s.trm.rw * 3, a, (uint32_t)w * 3), TDC_OK);
                        assert_int_equal(tdc_ref_trm_reduced(&ref, red, b, NULL), 0);
                    }
                    for (size_t i = 0; i < n; i++) {
                        double d = fabs((double)a[i] - (double)b[i]);
                        emax[pass] = fmax(emax[pass], d);
                        ew[pass] += d <= 1.0;
                        en[pass]++;
                    }
                }
            }
            for (int pass = 0; pass < 2; pass++) {
                double share = 100.0 * ew[pass] / en[pass];
                int ok = share >= 99.9 && emax[pass] <= 2.0;
                printf("  %-8s %-9s r=1/%d  max %.0f LSB  within 1 LSB %8.4f %%  %s\n", pass ? "reduced" : "full",
                       tdc_content_name(contents[ci]), ratios[ri][1], emax[pass], share, ok ? "ok" : "FAIL");
                fail |= !ok;
            }
            tdc_ref_trm_free(&ref);
            stage_free(&s);
            free(mv);
            free(mx);
            free(my);
            free(kmap);
            free(in);
            free(a);
            free(b);
            free(red);
        }
    }
    assert_false(fail);
}

/* Runs 3 full/reduced pairs of EDGE on a stage, outputs concatenated. */
static void run_pairs(stage_t *s, const int16_t *mv, int16_t gx, uint8_t *out)
{
    size_t n = (size_t)s->w * s->h * 3;
    uint8_t *in = malloc(n), *red = malloc(n);
    for (uint32_t t = 0; t < 6; t++) {
        tdc_content_frame(TDC_CONTENT_EDGE, t, 3u, in, s->w, s->h, s->w * 3);
        if ((t & 1u) == 0u) {
            if (mv) {
                assert_int_equal(tdc_trm_gaze_update(&s->gaze, mv, s->gaze.tx * s->gaze.ty, gx, 0), TDC_OK);
            }
            assert_int_equal(tdc_trm_full(&s->trm, in, (uint32_t)s->w * 3, out + t * n, (uint32_t)s->w * 3), TDC_OK);
        } else {
            assert_int_equal(tdc_trm_downsample(&s->trm, in, (uint32_t)s->w * 3, red, (uint32_t)s->trm.rw * 3), TDC_OK);
            assert_int_equal(tdc_trm_reduced(&s->trm, red, (uint32_t)s->trm.rw * 3, out + t * n, (uint32_t)s->w * 3),
                             TDC_OK);
        }
    }
    free(in);
    free(red);
}

static void test_off_state_and_k0(void **state)
{
    (void)state;
    const int w = 48, h = 32, tile = 16;
    size_t n = (size_t)w * h * 3;
    uint8_t *plain = malloc(6 * n), *got = malloc(6 * n);
    stage_t p, s;
    stage_init(&p, w, h, 1, 2, tile, 0u, 0);
    run_pairs(&p, NULL, 0, plain);
    /* the eye tracks the content exactly: u = 0, k = 1 everywhere */
    stage_init(&s, w, h, 1, 2, tile, 0u, 1);
    int16_t mv[2 * 3 * 2];
    for (int i = 0; i < 6; i++) {
        mv[2 * i] = 48;
        mv[2 * i + 1] = 0;
    }
    run_pairs(&s, mv, 48, got);
    assert_memory_equal(plain, got, 6 * n);
    /* detached: TRM's bytes */
    stage_free(&s);
    stage_init(&s, w, h, 1, 2, tile, 0u, 1);
    assert_int_equal(tdc_trm_set_gaze(&s.trm, NULL), TDC_OK);
    run_pairs(&s, NULL, 0, got);
    assert_memory_equal(plain, got, 6 * n);
    stage_free(&s);
    /* one fast tile (index 4: row 1, column 1): the other tiles of its row
     * run the gaze kernel with k = 1 and must still be TRM's bytes */
    stage_init(&s, w, h, 1, 2, tile, 0u, 1);
    for (int i = 0; i < 6; i++) {
        mv[2 * i] = i == 4 ? 200 : 48;
    }
    run_pairs(&s, mv, 48, got);
    for (int t = 0; t < 6; t += 2) { /* full frames: pixels outside tile 4 */
        for (int y = 0; y < h; y++) {
            for (int x = 0; x < w; x++) {
                if (y / tile == 1 && x / tile == 1) {
                    continue;
                }
                assert_memory_equal(plain + t * n + 3 * ((size_t)y * w + x), got + t * n + 3 * ((size_t)y * w + x), 3);
            }
        }
    }
    stage_free(&s);
    /* k = 0 everywhere (fixed gaze, content at 3 px/frame): full frames pass
     * unchanged (beta = I), reduced frames are U(i) alone */
    stage_init(&s, w, h, 1, 2, tile, 0u, 1);
    for (int i = 0; i < 6; i++) {
        mv[2 * i] = 48;
    }
    run_pairs(&s, mv, 0, got);
    uint8_t *in = malloc(n), *red = malloc(n), *alone = malloc(n);
    tdc_content_frame(TDC_CONTENT_EDGE, 0, 3u, in, w, h, w * 3);
    assert_memory_equal(got, in, n);
    tdc_content_frame(TDC_CONTENT_EDGE, 1, 3u, in, w, h, w * 3);
    assert_int_equal(tdc_trm_downsample(&p.trm, in, (uint32_t)w * 3, red, (uint32_t)p.trm.rw * 3), TDC_OK);
    tdc_trm_invalidate(&p.trm);
    assert_int_equal(tdc_trm_reduced_seq(&p.trm, red, (uint32_t)p.trm.rw * 3, alone, (uint32_t)w * 3, 99u), TDC_OK);
    assert_memory_equal(got + n, alone, n);
    print_message("  off state, k = 1 maps and k = 1 tiles: TRM's bytes; k = 0: full frames unchanged, reduced = U(i)\n");
    stage_free(&s);
    stage_free(&p);
    free(plain);
    free(got);
    free(in);
    free(red);
    free(alone);
}

static void test_bad_input(void **state)
{
    (void)state;
    static uint64_t arena[64];
    tdc_trm_gaze_config_t c;
    tdc_trm_gaze_t g;
    tdc_trm_gaze_default_config(&c, 32, 32);
    assert_int_equal(tdc_trm_gaze_init(NULL, &c, arena, sizeof arena), TDC_ERR_ARG);
    assert_int_equal(tdc_trm_gaze_init(&g, NULL, arena, sizeof arena), TDC_ERR_ARG);
    assert_int_equal(tdc_trm_gaze_init(&g, &c, NULL, sizeof arena), TDC_ERR_ARG);
    assert_int_equal(tdc_trm_gaze_init(&g, &c, (uint8_t *)arena + 1, sizeof arena - 8), TDC_ERR_ARG);
    assert_int_equal(tdc_trm_gaze_init(&g, &c, arena, tdc_trm_gaze_get_size(&c) - 1), TDC_ERR_SIZE);
    tdc_trm_gaze_config_t b = c;
    b.tile = 3;
    assert_int_equal(tdc_trm_gaze_get_size(&b), 0);
    assert_int_equal(tdc_trm_gaze_init(&g, &b, arena, sizeof arena), TDC_ERR_ARG);
    b = c;
    b.tile = 257;
    assert_int_equal(tdc_trm_gaze_get_size(&b), 0);
    b = c;
    b.u1_q4 = b.u0_q4;
    assert_int_equal(tdc_trm_gaze_get_size(&b), 0);
    b = c;
    b.kmin_q15 = 32769;
    assert_int_equal(tdc_trm_gaze_get_size(&b), 0);
    b = c;
    b.width = 0;
    assert_int_equal(tdc_trm_gaze_get_size(&b), 0);
    assert_int_equal(tdc_trm_gaze_init(&g, &c, arena, sizeof arena), TDC_OK);
    assert_int_equal(g.tx * g.ty, 4);
    int16_t mv[8] = {64, 0, 64, 0, 64, 0, 64, 0};
    assert_int_equal(tdc_trm_gaze_update(&g, mv, 4, 0, 0), TDC_OK);
    uint16_t kept[4];
    memcpy(kept, g.k_q15, sizeof kept);
    assert_int_equal(kept[0], c.kmin_q15);
    int16_t zero[8] = {0};
    assert_int_equal(tdc_trm_gaze_update(&g, NULL, 4, 0, 0), TDC_ERR_ARG);
    assert_int_equal(tdc_trm_gaze_update(&g, zero, 3, 0, 0), TDC_ERR_ARG);
    assert_int_equal(tdc_trm_gaze_update(&g, zero, 5, 0, 0), TDC_ERR_ARG);
    assert_int_equal(tdc_trm_gaze_update(&g, zero, 4, INT16_MIN, 0), TDC_ERR_ARG);
    zero[5] = INT16_MIN;
    assert_int_equal(tdc_trm_gaze_update(&g, zero, 4, 0, 0), TDC_ERR_ARG);
    assert_memory_equal(kept, g.k_q15, sizeof kept); /* the last good map stays */
    assert_int_equal(g.rejected, 5);
    assert_int_equal(g.updates, 1);
    assert_int_equal(tdc_trm_gaze_update(NULL, mv, 4, 0, 0), TDC_ERR_ARG);
    /* attached to a stage of another size: refused, the stage stays plain */
    stage_t s;
    stage_init(&s, 48, 32, 1, 2, 16, 0u, 0);
    assert_int_equal(tdc_trm_set_gaze(&s.trm, &g), TDC_ERR_SIZE);
    assert_null(s.trm.gaze);
    assert_int_equal(tdc_trm_set_gaze(NULL, &g), TDC_ERR_ARG);
    stage_free(&s);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_strength_vs_reference),
    cmocka_unit_test(test_frames_vs_reference),
    cmocka_unit_test(test_off_state_and_k0),
    cmocka_unit_test(test_bad_input),
)
