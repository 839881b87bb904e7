/*
 * test_sim_eye.c - eye model (Talbot-Plateau, smooth pursuit), panel
 * simulation (OLED gamma, LCD response incl. stiff time constants) and the
 * procedural scenes' exact motion.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "eye/tdc_eye.h"
#include "panel/tdc_panel_sim.h"
#include "simulator/tdc_sim_scene.h"
#include "tdc_sim_codes.h"

#define W 24
#define H 16
#define N (W * H * 3)

static double maxdiff(const double *a, const double *b, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++) {
        m = fmax(m, fabs(a[i] - b[i]));
    }
    return m;
}

/* Steady light on a full-duty panel is perceived at its level. */
static void test_eye_steady(void **state)
{
    (void)state;
    static double img[N], out[N];
    for (int i = 0; i < N; i++) {
        img[i] = (double)(i % 97) / 97.0;
    }
    tdc_eye_slice_t s[3] = {{0.0, 0.01, img, NULL, NULL}, {0.01, 0.02, img, NULL, NULL}, {0.02, 0.03, img, NULL, NULL}};
    tdc_eye_cfg_t c = {W, H, 0.02, 1.0, 0.5, 1.0};
    double v[2] = {0, 0};
    tdc_eye_perceive(&c, s, 3, 0.03, v, out);
    assert_true(maxdiff(out, img, N) < 1e-12);
}

/* Talbot-Plateau: two frames in the window fuse to their mean (eq. 3). */
static void test_eye_talbot_plateau(void **state)
{
    (void)state;
    static double a[N], b[N], out[N], mean[N];
    for (int i = 0; i < N; i++) {
        a[i] = (i & 1) ? 0.9 : 0.1;
        b[i] = 0.3;
        mean[i] = 0.5 * (a[i] + b[i]);
    }
    /* low persistence 0.25: each frame emits a quarter of its period */
    tdc_eye_slice_t s[2] = {{0.0, 0.0025, a, NULL, NULL}, {0.01, 0.0125, b, NULL, NULL}};
    tdc_eye_cfg_t c = {W, H, 0.02, 4.0, 0.5, 1.0};
    double v[2] = {0, 0};
    tdc_eye_perceive(&c, s, 2, 0.02, v, out);
    assert_true(maxdiff(out, mean, N) < 1e-12);
}

/* Pursuit: a pattern displayed 2 px further right each frame, tracked at
 * 2 px/frame, is perceived exactly (short flashes, integer shifts). */
static void test_eye_pursuit(void **state)
{
    (void)state;
    static double f0[N], f1[N], out[N];
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            for (int c = 0; c < 3; c++) {
                f0[3 * (y * W + x) + c] = (x % 5 == 0) ? 1.0 : 0.0;
                f1[3 * (y * W + x) + c] = ((x - 2 + 50) % 5 == 0) ? 1.0 : 0.0;
            }
        }
    }
    /* flashes of 1 us at t = 0 and t = 0.01 (pursuit shift within a flash
     * is 0.0002 px: one sub-step, bilinear weight ~1) */
    tdc_eye_slice_t s[2] = {{0.0, 1e-6, f0, NULL, NULL}, {0.01, 0.01 + 1e-6, f1, NULL, NULL}};
    tdc_eye_cfg_t c = {W, H, 0.02, 0.02 / 2e-6, 0.5, 1.0};
    double v[2] = {200.0, 0.0}; /* 2 px per 10 ms */
    tdc_eye_perceive(&c, s, 2, 0.01 + 1e-6, v, out);
    /* interior columns: perceived = f1 (the pattern at the last frame) */
    for (int y = 0; y < H; y++) {
        for (int x = 3; x < W - 3; x++) {
            assert_true(fabs(out[3 * (y * W + x)] - f1[3 * (y * W + x)]) < 1e-3);
        }
    }
    /* without pursuit the two positions blur into two half-bright lines */
    v[0] = 0.0;
    tdc_eye_perceive(&c, s, 2, 0.01 + 1e-6, v, out);
    assert_true(fabs(out[3 * (0 * W + 10)] - 0.5) < 1e-9);
}

static void test_panel_oled(void **state)
{
    (void)state;
    tdc_panel_sim_t p;
    const double g[3] = {2.2912, 2.2520, 2.1940};
    assert_int_equal(tdc_panel_sim_init(&p, TDC_PANEL_SIM_OLED, 4, 2, g, 0.2), 0);
    uint8_t codes[4 * 2 * 3];
    for (int i = 0; i < 24; i++) {
        codes[i] = (uint8_t)(i * 11);
    }
    tdc_eye_slice_t s[TDC_PANEL_SIM_MAX_SLICES];
    int n = tdc_panel_sim_show(&p, codes, 1.0, 0.01, s);
    assert_int_equal(n, 1);
    assert_true(fabs(s[0].t1 - s[0].t0 - 0.002) < 1e-12);
    /* the slice is the codes with the panel's decode, no light plane */
    assert_null(s[0].lin);
    assert_ptr_equal(s[0].codes, codes);
    for (int i = 0; i < 24; i++) {
        assert_true(fabs(s[0].lut[256 * (i % 3) + codes[i]] - pow(codes[i] / 255.0, g[i % 3])) < 1e-12);
    }
    assert_true(fabs(tdc_panel_sim_duty(&p) - 0.2) < 1e-12);
    tdc_panel_sim_free(&p);
}

/* LCD fallback: exact mean of the exponential response; converges to the
 * target; stiff time constants (1 ns, 1000 s) stay finite and bounded. */
static void test_panel_lcd(void **state)
{
    (void)state;
    const double g[3] = {2.2, 2.2, 2.2};
    const double taus[3] = {0.004, 1e-9, 1e3};
    for (int k = 0; k < 3; k++) {
        tdc_panel_sim_t p;
        assert_int_equal(tdc_panel_sim_init(&p, TDC_PANEL_SIM_LCD, 2, 1, g, 1.0), 0);
        p.tau_rise_s = p.tau_fall_s = taus[k];
        uint8_t white[6] = {255, 255, 255, 255, 255, 255};
        tdc_eye_slice_t s[TDC_PANEL_SIM_MAX_SLICES];
        int n = tdc_panel_sim_show(&p, white, 0.0, 1.0 / 120, s);
        assert_int_equal(n, TDC_PANEL_SIM_MAX_SLICES);
        /* numerical check of the first slice's mean: L(t) = 1 - exp(-t/tau) */
        double a = s[0].t0, b = s[0].t1, num = 0.0;
        for (int i = 0; i < 100000; i++) {
            double t = a + (i + 0.5) * (b - a) / 100000;
            num += (1.0 - exp(-t / taus[k])) / 100000;
        }
        assert_true(fabs(s[0].lin[0] - num) < 1e-6);
        for (int f = 0; f < 200; f++) {
            tdc_panel_sim_show(&p, white, f / 120.0, 1.0 / 120, s);
            for (int i = 0; i < n; i++) {
                for (int j = 0; j < 6; j++) {
                    assert_true(isfinite(s[i].lin[j]) && s[i].lin[j] >= 0.0 && s[i].lin[j] <= 1.0);
                }
            }
        }
        if (taus[k] < 1.0) {
            assert_true(fabs(s[n - 1].lin[0] - 1.0) < 1e-9);
        }
        tdc_panel_sim_free(&p);
    }
}

/* Scenes: exact motion vectors; rigid pan ground truth is the same
 * content shifted by v t; static scene ground truth does not change. */
static void test_scene_motion(void **state)
{
    (void)state;
    tdc_scene_params_t sp = {TDC_SCENE_PAN, 32, 16, 160.0, 0.0, 1.0, 3, 1, 2, 0.0};
    const double g[3] = {2.2, 2.2, 2.2};
    tdc_source_t *s = tdc_scene_create(&sp, g);
    assert_non_null(s);
    double xy[2] = {10.5, 5.5};
    uint8_t rgb[3];
    int16_t mv[2];
    s->samples(s, 0.1, 1, xy, 1, rgb, mv, 1.0 / 80, TDC_MV_SURFACE);
    assert_int_equal(mv[0], -32); /* -160 px/s * 1/80 s = -2 px = -32 Q4 */
    assert_int_equal(mv[1], 0);
    static double a[32 * 16 * 3], b[32 * 16 * 3];
    s->ground_truth(s, 0.0, 0.0, 0.0, a);
    s->ground_truth(s, 0.05, 8.0, 0.0, b); /* content moved 8 px; sample 8 px further */
    assert_true(maxdiff(a, b, 32 * 16 * 3) < 1e-12);
    double v[2];
    s->pursuit(s, 0.0, v);
    assert_true(v[0] == 160.0 && v[1] == 0.0);
    s->destroy(s);
    sp.kind = TDC_SCENE_FENCE;
    s = tdc_scene_create(&sp, g);
    /* fence: the floor is static (surface MV 0); shadow MVs follow the shadow */
    int shadow_seen = 0;
    for (int x = 0; x < 32; x++) {
        xy[0] = x + 0.5;
        s->samples(s, 0.0, 1, xy, 1, rgb, mv, 1.0 / 80, TDC_MV_SURFACE);
        assert_int_equal(mv[0], 0);
        s->samples(s, 0.0, 1, xy, 1, rgb, mv, 1.0 / 80, TDC_MV_SHADOW);
        assert_true(mv[0] == 0 || mv[0] == -32);
        shadow_seen |= mv[0] == -32;
    }
    assert_true(shadow_seen);
    s->destroy(s);
}

/* An OLED decode table (gammas 2.1, 2.2, 2.3) and n pseudo-random codes
 * from seed: the code slices of the next two tests. */
static void random_codes(double lut[3 * 256], uint8_t *codes, int n, uint32_t seed)
{
    for (int k = 0; k < 3; k++) {
        for (int c = 0; c < 256; c++) {
            lut[256 * k + c] = tdc_panel_sim_decode(c, 2.1 + 0.1 * k);
        }
    }
    for (int i = 0; i < n; i++) {
        seed = seed * 1664525u + 1013904223u;
        codes[i] = (uint8_t)(seed >> 24);
    }
}

/* The drive-code table (EXACT) gives tdc_sim_encode_code's code on both
 * sides of every level, at 0, 1, out of range and on 10^5 random values,
 * for gammas 1.8-2.6. */
static void test_code_table_exact(void **state)
{
    (void)state;
    static const double gammas[] = {1.8, 2.0, 2.19, 2.2, 2.2375, 2.4, 2.6};
    static tdc_sim_code_table_t t; /* 6 kB */
    for (size_t g = 0; g < sizeof(gammas) / sizeof(gammas[0]); g++) {
        memset(&t, 0, sizeof(t));
        tdc_sim_code_table_init(&t, gammas[g], TDC_SIM_CODES_EXACT);
        for (int k = 1; k < 256; k++) {
            const double at = t.level[k], below = nextafter(at, -1.0);
            assert_int_equal(tdc_sim_code_lookup(&t, at), tdc_sim_encode_code(at, gammas[g]));
            assert_int_equal(tdc_sim_code_lookup(&t, below), tdc_sim_encode_code(below, gammas[g]));
            assert_int_equal(tdc_sim_code_lookup(&t, at), k); /* the level is where k starts */
        }
        static const double edge[] = {0.0, 1.0, -0.5, 1.5, 1e-300, 0.999999999};
        for (size_t i = 0; i < sizeof(edge) / sizeof(edge[0]); i++) {
            assert_int_equal(tdc_sim_code_lookup(&t, edge[i]), tdc_sim_encode_code(edge[i], gammas[g]));
        }
        uint32_t x = 3;
        for (int i = 0; i < 100000; i++) {
            x = x * 1664525u + 1013904223u;
            const double lin = (double)x / 4294967296.0 * (i & 1 ? 1.0 : 0.01);
            assert_int_equal(tdc_sim_code_lookup(&t, lin), tdc_sim_encode_code(lin, gammas[g]));
        }
    }
}

/* OLED slices kept as codes + the panel's decode table perceive exactly as
 * the decoded light itself (the ring keeps codes to save 7/8 of its memory),
 * at integer and fractional retinal shifts. */
static void test_code_slices_equal_light(void **state)
{
    (void)state;
    enum { CW = 23, CH = 17, CN = CW * CH * 3 };
    uint8_t codes[CN];
    double lut[3 * 256], lin[CN], a[CN], b[CN];
    random_codes(lut, codes, CN, 7);
    for (int i = 0; i < CN; i++) {
        lin[i] = lut[256 * (i % 3) + codes[i]];
    }
    tdc_eye_cfg_t c = {CW, CH, 0.02, 5.0, 0.5, 1.0};
    static const double speeds[3] = {0.0, 100.0, 437.0};
    for (int k = 0; k < 3; k++) {
        double v[2] = {speeds[k], -0.5 * speeds[k]};
        tdc_eye_slice_t s1[1] = {{0.01, 0.014, lin, NULL, NULL}}, s2[1] = {{0.01, 0.014, NULL, codes, lut}};
        assert_int_equal(tdc_eye_perceive(&c, s1, 1, 0.02, v, a), 0);
        assert_int_equal(tdc_eye_perceive(&c, s2, 1, 0.02, v, b), 0);
        assert_memory_equal(a, b, sizeof(a));
        /* decoded once into scratch for the sub-steps: the same bits */
        double scratch[CN];
        assert_int_equal(tdc_eye_perceive_buf(&c, s2, 1, 0.02, v, b, scratch), 0);
        assert_memory_equal(a, b, sizeof(a));
    }
}

/* The luminance-only integral (the judge's retinal signal) is the
 * luminance of the per-channel one, for code and light slices, at integer,
 * fractional and edge-clamped shifts (to rounding: 1e-12 relative); the
 * sub-steps in one call give the bits of one call each. */
static void test_accumulate_y_is_luminance(void **state)
{
    (void)state;
    enum { CW = 23, CH = 17, CP = CW * CH, CN = CP * 3 };
    static const double y3[3] = {0.2126, 0.7152, 0.0722};
    static const double shifts[4][2] = {{0.0, 0.0}, {2.0, -3.0}, {0.37, -1.61}, {-25.3, 19.2}};
    uint8_t codes[CN];
    double lut[3 * 256], lin[CN], a[CN], b[CP];
    random_codes(lut, codes, CN, 11);
    for (int i = 0; i < CN; i++) {
        lin[i] = 0.5 * lut[256 * (i % 3) + codes[i]] + 0.01 * (i % 7);
    }
    for (int src = 0; src < 2; src++) {
        tdc_eye_slice_t sl = {0.0, 1.0, src ? lin : NULL, src ? NULL : codes, src ? NULL : lut};
        for (int k = 0; k < 4; k++) {
            memset(a, 0, sizeof(a));
            memset(b, 0, sizeof(b));
            assert_int_equal(tdc_eye_accumulate(a, &sl, CW, CH, shifts[k][0], shifts[k][1], 0.7), 0);
            assert_int_equal(tdc_eye_accumulate_y(b, &sl, y3, CW, CH, shifts[k][0], shifts[k][1], 0.7), 0);
            for (int i = 0; i < CP; i++) {
                double want = y3[0] * a[3 * i] + y3[1] * a[3 * i + 1] + y3[2] * a[3 * i + 2];
                assert_true(fabs(b[i] - want) <= 1e-12 * (1.0 + want));
            }
            /* decoded once, then integrated: the same bits */
            double plane[CP], c[CP];
            memset(c, 0, sizeof(c));
            tdc_eye_slice_luminance(&sl, y3, CW, CH, plane);
            assert_int_equal(tdc_eye_accumulate_plane(c, plane, CW, CH, shifts[k][0], shifts[k][1], 0.7), 0);
            assert_memory_equal(b, c, sizeof(c));
        }
        /* the four shifts in one call (tdc_eye_accumulate_steps): the same
         * bits as one call each, per channel and for the luminance plane */
        static const double wg[4] = {0.7, 0.25, 1.5, 0.125};
        double plane[CP], one[CN], all[CN];
        tdc_eye_slice_luminance(&sl, y3, CW, CH, plane);
        for (int lum = 0; lum < 2; lum++) {
            memset(one, 0, sizeof(one));
            memset(all, 0, sizeof(all));
            for (int k = 0; k < 4; k++) {
                assert_int_equal(lum ? tdc_eye_accumulate_plane(one, plane, CW, CH, shifts[k][0], shifts[k][1], wg[k])
                                     : tdc_eye_accumulate(one, &sl, CW, CH, shifts[k][0], shifts[k][1], wg[k]),
                                 0);
            }
            assert_int_equal(tdc_eye_accumulate_steps(all, &sl, lum ? plane : NULL, CW, CH, 4, &shifts[0][0], wg), 0);
            assert_memory_equal(one, all, sizeof(one));
        }
    }
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_code_table_exact),
    cmocka_unit_test(test_code_slices_equal_light),
    cmocka_unit_test(test_accumulate_y_is_luminance),
    cmocka_unit_test(test_eye_steady),
    cmocka_unit_test(test_eye_talbot_plateau),
    cmocka_unit_test(test_eye_pursuit),
    cmocka_unit_test(test_panel_oled),
    cmocka_unit_test(test_panel_lcd),
    cmocka_unit_test(test_scene_motion),
)
