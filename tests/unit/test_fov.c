/*
 * test_fov.c - properties of the foveated remap stage (firmware/tdc_fov.c):
 * the integer log2 / exp2 / atan against double; the transform pair eq. 2.2
 * / exact eq. 2.3 round-trips; eq. 4.5's disk <-> rectangle mapping is exact
 * (firmware l equals the double formula, the disk predicate, spans and
 * counts agree pixel by pixel); a uniform field remaps to the same uniform
 * field (with and without TAA, any gaze, alpha, disk); disk fraction 0 never
 * reads the disk and 1 shows the disk; gaze far outside, bad alpha / disk /
 * sizes are refused; a whole-screen gaze jump rejects the TAA history
 * (output bit-identical to the stage without TAA, no ghost); a 10^5-frame
 * run keeps its state bounded and converges on a static field.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include "fov_fixture.h"
#include "tdc_math.h"
#include "golden/golden.h"

static uint32_t g_rng = 12345u;
static uint32_t rnd(void)
{
    return tdc_golden_rand(&g_rng);
}
static double rndu(void)
{
    return (rnd() >> 8) / 16777216.0;
}

static void test_building_blocks(void **state)
{
    (void)state;
    double e_log = 0, e_exp = 0, e_atan = 0;
    for (int k = 0; k < 200000; k++) {
        const uint64_t x = 1 + ((uint64_t)rnd() << (rnd() % 31)) + (rnd() & 0xFFFF);
        const double l = tdc_log2_q24(x) / 16777216.0;
        e_log = fmax(e_log, fabs(l - log2((double)x)));
        const int32_t s = (int32_t)(rnd() % (40u << 24)) - (26 << 24); /* [-26, 14) */
        const double ex = exp2(s / 16777216.0) * 65536.0;
        /* within 2e-6 relative or 1 LSB of Q16, whichever is larger: <= 1 */
        e_exp = fmax(e_exp, fabs(tdc_fov_exp2_q16(s) - ex) / fmax(2e-6 * ex, 1.0));
        const int32_t dx = (int32_t)(rnd() % 2000001u) - 1000000, dy = (int32_t)(rnd() % 2000001u) - 1000000;
        double a = atan2(dy, dx) / (2 * M_PI);
        a = a < 0 ? a + 1 : a;
        double d = fabs(tdc_fov_turns_q32(dx, dy) / 4294967296.0 - a);
        e_atan = fmax(e_atan, fmin(d, 1 - d));
    }
    printf("log2 max error %.3g, exp2 error %.3g of max(2e-6 relative, 1 LSB), atan max error %.3g turns\n", e_log,
           e_exp, e_atan);
    assert_true(e_log < 3.5e-6);
    assert_true(e_exp <= 1.0);
    assert_true(e_atan < 3e-7);
    assert_int_equal(tdc_fov_turns_q32(5, 0), 0);
    assert_int_equal(tdc_fov_turns_q32(0, 5), 1u << 30);
    assert_int_equal(tdc_fov_turns_q32(-5, 0), 1u << 31);
    assert_int_equal(tdc_fov_turns_q32(0, -5), 3u << 30);
    assert_int_equal(tdc_fov_exp2_q16(0), 65536);
    assert_int_equal(tdc_fov_exp2_q16(14 << 24), INT32_MAX);
}

/* eq. 2.2 (firmware, fixed point) of the exact eq. 2.3 (double) of a sample
 * returns the sample; and the double pair round-trips to 1e-9. */
static void test_transform_pair(void **state)
{
    (void)state;
    static const double alphas[] = {1, 2.5, 4, 8};
    double worst_u = 0, worst_v = 0, worst_d = 0;
    for (unsigned a = 0; a < 4; a++) {
        for (int c = 0; c < 6; c++) {
            ref_fov_params_t rp = {rndu() * 1920, rndu() * 1080, alphas[a], 0.12443, 1065, 599, 0, 0, 0};
            if (c == 0) {
                rp.cx = -500;
                rp.cy = 1500; /* outside the screen */
            }
            fov_quantise(&rp);
            tdc_fov_params_t fp;
            fov_params(&rp, &fp);
            ref_fov_geom_t g;
            ref_fov_geom(&g, 1920, 1080, &rp);
            tdc_fov_geom_t fg;
            assert_int_equal(tdc_fov_geom(&fg, 1920, 1080, &fp), TDC_OK);
            for (int k = 0; k < 4000; k++) {
                const double u = 1 + rndu() * (g.lp_w - 1), v = rndu() * g.lp_h;
                double x, y, u2, v2;
                ref_fov_from_lp(&g, u, v, &x, &y);
                ref_fov_to_lp(&g, x, y, &u2, &v2);
                double dv = fabs(v2 - v);
                dv = fmin(dv, g.lp_h - dv);
                const double r = hypot(x - g.cx, y - g.cy);
                if (r > 1.001) { /* below, r - 1 is not representable for small u^alpha */
                    worst_d = fmax(worst_d, fmax(fabs(u2 - u), dv));
                }
                if (r < 4) {
                    continue; /* Q8 coordinates: below 4 px du/dr is steeper than 1/256 px resolves */
                }
                uint32_t uq, vq;
                tdc_fov_to_lp(&fg, (int32_t)lround(x * 256), (int32_t)lround(y * 256), &uq, &vq);
                /* the tolerance scales with du/dr at this radius (1/256 px input rounding) */
                const double dudr = u / (g.alpha * log(r) * r);
                const double eu = fabs(uq / 65536.0 - u) / (1e-4 * u + dudr / 256 + 1e-3);
                double ev = fabs(vq / 65536.0 - v);
                ev = fmin(ev, g.lp_h - ev) / (g.lp_h / (2 * M_PI * r) / 256 + 1e-3);
                worst_u = fmax(worst_u, eu);
                worst_v = fmax(worst_v, ev);
            }
        }
    }
    printf("round trip: double %.3g samples; fixed u error %.3f, v error %.3f of tolerance\n", worst_d, worst_u,
           worst_v);
    assert_true(worst_d < 1e-7); /* conditioning near r = 1.001 */
    assert_true(worst_u <= 1.0);
    assert_true(worst_v <= 1.0);
}

/* eq. 4.5 exact: firmware l == ceil(K^-1(ln r_d / L) w) of the double
 * formula (at the firmware's own r_d), except where the double value is
 * within 1e-4 of an integer (counted, none expected in practice); every
 * column >= l maps to radius >= r_d, every column < l below it; and the
 * disk predicate, spans and pixel count agree for every pixel. */
static void test_disk_rectangle(void **state)
{
    (void)state;
    int checked = 0, near_int = 0;
    for (int c = 0; c < 400; c++) {
        const int Wd = 16 + (int)(rnd() % 300), Hd = 16 + (int)(rnd() % 200);
        ref_fov_params_t rp = {rndu() * 3 * Wd - Wd, rndu() * 3 * Hd - Hd, 1 + rndu() * 7, rndu(),
                               (int)(Wd * 0.555),    (int)(Hd * 0.555), 0, 0, 0};
        if (c % 10 == 0) {
            rp.disk = c % 20 ? 0 : 1;
        }
        fov_quantise(&rp);
        tdc_fov_params_t fp;
        fov_params(&rp, &fp);
        tdc_fov_geom_t fg;
        assert_int_equal(tdc_fov_geom(&fg, (uint16_t)Wd, (uint16_t)Hd, &fp), TDC_OK);
        ref_fov_geom_t g;
        ref_fov_geom(&g, Wd, Hd, &rp);
        const double rd = fg.r_disk_q8 / 256.0;
        double ex;
        const int l = ref_fov_disk_columns(&g, rd, &ex);
        const int want = l > g.lp_w ? g.lp_w : l;
        if (fg.l != want) {
            /* allowed only where the double value is within 1e-4 of an integer */
            assert_true(fabs(ex - lround(ex)) < 1e-4);
            near_int++;
        } else {
            checked++;
            for (int i = 0; i < g.lp_w; i++) {
                double x, y;
                ref_fov_from_lp(&g, i, 0, &x, &y);
                const double r = hypot(x - g.cx, y - g.cy);
                if (i >= fg.l) {
                    assert_true(r >= rd * (1 - 1e-12));
                } else {
                    assert_true(r < rd);
                }
            }
        }
        assert_true(fg.u0 <= fg.l);
        uint32_t n = 0;
        for (int j = 0; j < Hd; j++) {
            int32_t x0;
            const uint32_t span = tdc_fov_disk_span(&fg, j, &x0);
            for (int i = 0; i < Wd; i++) {
                const int in = tdc_fov_in_disk(&fg, i, j);
                const int in_span = span && i >= x0 && i < x0 + (int32_t)span;
                assert_int_equal(in, in_span);
                n += (uint32_t)in;
            }
        }
        assert_int_equal(n, tdc_fov_disk_pixels(&fg));
    }
    printf("eq. 4.5: %d configurations exact, %d differ by the rounding of a value within 1e-4 of an integer\n",
           checked, near_int);
    assert_true(near_int * 50 < checked);
}

static void run_stage(tdc_fov_t *st, int taa, int W, int H, void **mem)
{
    tdc_fov_config_t cfg = {(uint16_t)W, (uint16_t)H, (uint8_t)taa};
    const size_t n = tdc_fov_get_size(&cfg);
    *mem = malloc(n);
    assert_int_equal(tdc_fov_init(st, &cfg, *mem, n), TDC_OK);
}

/* A uniform field remaps to exactly the same field: any gaze (corners,
 * outside), alpha 1..8, disk 0..1, with TAA and random motion vectors. */
static void test_uniform(void **state)
{
    (void)state;
    enum { W = 61, H = 43 };
    static uint8_t lp[W * H * 3], dk[W * H * 3], out[W * H * 3];
    static int16_t mv[W * H * 2];
    for (int c = 0; c < 60; c++) {
        const int taa = c & 1;
        tdc_fov_t st;
        void *mem;
        run_stage(&st, taa, W, H, &mem);
        const uint8_t col[3] = {(uint8_t)rnd(), (uint8_t)rnd(), (uint8_t)(c == 0 ? 255 : rnd())};
        for (int k = 0; k < W * H; k++) {
            memcpy(lp + 3 * k, col, 3);
            memcpy(dk + 3 * k, col, 3);
        }
        static const double corner[][2] = {{0, 0}, {W, 0}, {0, H}, {W, H}, {-W, -H}, {2 * W, 2 * H}};
        tdc_fov_params_t fp = {0, 0, (uint16_t)(256 + rnd() % 1793), (uint16_t)(rnd() % 32769), 33, 23, {0, 0}, 0, 0};
        for (int f = 0; f < 4; f++) {
            const double gx = c < 12 ? corner[c / 2][0] : rndu() * 3 * W - W;
            const double gy = c < 12 ? corner[c / 2][1] : rndu() * 3 * H - H;
            fp.gaze_x_q8 = (int32_t)lround(gx * 256);
            fp.gaze_y_q8 = (int32_t)lround(gy * 256);
            for (int k = 0; k < W * H * 2; k++) {
                mv[k] = (int16_t)((int32_t)(rnd() % 801) - 400);
            }
            assert_int_equal(tdc_fov_frame(&st, &fp, lp, 33 * 3, mv, 33 * 2, dk, W * 3, 11111, out, W * 3), TDC_OK);
            for (int k = 0; k < W * H; k++) {
                assert_memory_equal(out + 3 * k, col, 3);
            }
        }
        free(mem);
    }
}

/* Disk fraction 0: the disk is never read; 1: every pixel farther than
 * 4 px from the farthest corner is the disk pixel exactly, the log-polar
 * buffer never read there. */
static void test_disk_extremes(void **state)
{
    (void)state;
    enum { W = 80, H = 50, LW = 44, LH = 28 };
    static uint8_t lp[LW * LH * 3], dk[W * H * 3], dk2[W * H * 3], out[W * H * 3], out2[W * H * 3];
    ref_fov_params_t rp = {31.7, 18.2, 4, 0, LW, LH, 0, 0, 0};
    ref_fov_geom_t g;
    ref_fov_geom(&g, W, H, &rp);
    fov_make_inputs(&g, 0, 0, 0, lp, dk);
    for (int k = 0; k < W * H * 3; k++) {
        dk2[k] = (uint8_t)rnd();
    }
    tdc_fov_params_t fp;
    fov_params(&rp, &fp);
    tdc_fov_t st;
    void *mem;
    run_stage(&st, 0, W, H, &mem);
    assert_int_equal(tdc_fov_frame(&st, &fp, lp, LW * 3, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_OK);
    assert_int_equal(tdc_fov_frame(&st, &fp, lp, LW * 3, NULL, 0, dk2, W * 3, 0, out2, W * 3), TDC_OK);
    assert_memory_equal(out, out2, sizeof out);
    tdc_fov_geom_t fg;
    assert_int_equal(tdc_fov_geom(&fg, W, H, &fp), TDC_OK);
    assert_int_equal(fg.l, 0);
    assert_int_equal(fg.u0, 0);
    assert_int_equal(tdc_fov_disk_pixels(&fg), 0);

    fp.disk_q15 = 32768;
    static uint8_t lp2[LW * LH * 3];
    for (size_t k = 0; k < sizeof lp2; k++) {
        lp2[k] = (uint8_t)rnd();
    }
    assert_int_equal(tdc_fov_geom(&fg, W, H, &fp), TDC_OK);
    assert_int_equal(fg.l, LW);
    assert_int_equal(tdc_fov_disk_pixels(&fg), W * H);
    assert_int_equal(tdc_fov_frame(&st, &fp, lp, LW * 3, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_OK);
    assert_int_equal(tdc_fov_frame(&st, &fp, lp2, LW * 3, NULL, 0, dk, W * 3, 0, out2, W * 3), TDC_OK);
    int same = 0;
    for (int j = 0; j < H; j++) {
        for (int i = 0; i < W; i++) {
            const double r = hypot(i + 0.5 - fp.gaze_x_q8 / 256.0, j + 0.5 - fp.gaze_y_q8 / 256.0);
            if (r < fg.r_disk_q8 / 256.0 - 4.01) {
                assert_memory_equal(out + (j * W + i) * 3, dk + (j * W + i) * 3, 3);
                assert_memory_equal(out2 + (j * W + i) * 3, dk + (j * W + i) * 3, 3);
                same++;
            }
        }
    }
    assert_true(same > W * H * 95 / 100);
    free(mem);
}

static void test_bad_input(void **state)
{
    (void)state;
    enum { W = 40, H = 30 };
    static uint8_t lp[W * H * 3], dk[W * H * 3], out[W * H * 3], before[W * H * 3];
    tdc_fov_t st;
    void *mem;
    run_stage(&st, 1, W, H, &mem);
    memset(out, 77, sizeof out);
    memcpy(before, out, sizeof out);
    const tdc_fov_params_t ok = {W * 128, H * 128, 1024, 4077, 22, 16, {0, 0}, 0, 0};
    tdc_fov_params_t p = ok;
    p.alpha_q8 = 255;
    assert_int_equal(tdc_fov_frame(&st, &p, lp, 66, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_ARG);
    p = ok;
    p.alpha_q8 = 2049;
    assert_int_equal(tdc_fov_frame(&st, &p, lp, 66, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_ARG);
    p = ok;
    p.disk_q15 = 32769;
    assert_int_equal(tdc_fov_frame(&st, &p, lp, 66, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_ARG);
    p = ok;
    p.gaze_x_q8 = 2 * W * 256 + 1; /* more than one screen outside */
    assert_int_equal(tdc_fov_frame(&st, &p, lp, 66, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_ARG);
    p = ok;
    p.gaze_y_q8 = -H * 256 - 1;
    assert_int_equal(tdc_fov_frame(&st, &p, lp, 66, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_ARG);
    p = ok;
    p.lp_w = W + 1;
    assert_int_equal(tdc_fov_frame(&st, &p, lp, (W + 1) * 3, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_SIZE);
    p = ok;
    p.lp_h = 3;
    assert_int_equal(tdc_fov_frame(&st, &p, lp, 66, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_ARG);
    p = ok;
    assert_int_equal(tdc_fov_frame(&st, &p, lp, 65, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_ARG); /* stride */
    assert_int_equal(tdc_fov_frame(&st, &p, NULL, 66, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_ARG);
    /* a log-polar buffer of 2^31 bytes or more (the tap descriptors' offsets): refused, never read */
    assert_int_equal(tdc_fov_frame(&st, &p, lp, (size_t)1 << 29, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_ERR_ARG);
    assert_memory_equal(out, before, sizeof out); /* nothing written on a refusal */
    assert_int_equal(st.frames, 0);
    /* gaze exactly one screen outside is accepted */
    p.gaze_x_q8 = 2 * W * 256;
    p.gaze_y_q8 = -H * 256;
    assert_int_equal(tdc_fov_frame(&st, &p, lp, 66, NULL, 0, dk, W * 3, 0, out, W * 3), TDC_OK);
    tdc_fov_config_t cfg = {3, 30, 0};
    assert_int_equal(tdc_fov_get_size(&cfg), 0);
    assert_int_equal(tdc_fov_init(&st, &cfg, mem, 16), TDC_ERR_ARG);
    cfg.width = 40;
    cfg.taa = 1;
    assert_int_equal(tdc_fov_init(&st, &cfg, mem, tdc_fov_get_size(&cfg) - 1), TDC_ERR_SIZE);
    free(mem);
}

/* A whole-screen gaze jump: the history is rejected (a saccade), the
 * frame equals the no-TAA stage bit for bit, so nothing of the old
 * picture ghosts; the next frame uses history again. */
static void test_gaze_jump(void **state)
{
    (void)state;
    enum { W = 96, H = 60, LW = 53, LH = 33 };
    static uint8_t lp[LW * LH * 3], dk[W * H * 3], out[W * H * 3], plain[W * H * 3];
    static int16_t mv[LW * LH * 2];
    tdc_fov_t st, st0;
    void *mem, *mem0;
    run_stage(&st, 1, W, H, &mem);
    run_stage(&st0, 0, W, H, &mem0);
    ref_fov_params_t rp = {8, 6, 4, 0.12443, LW, LH, 0, 0, 0};
    for (int f = 0; f < 12; f++) {
        const int jump = f == 8;
        if (jump) {
            rp.cx = W - 5; /* gaze to the opposite corner */
            rp.cy = H - 4;
        }
        ref_fov_geom_t g;
        ref_fov_geom(&g, W, H, &rp);
        /* the picture changes completely at the jump (old content must not ghost) */
        fov_make_inputs(&g, f < 8 ? 0.7 * f : 500 + 0.7 * f, (f % 4) * 0.25 - 0.375, (f % 3) * 0.33 - 0.33, lp, dk);
        for (int k = 0; k < LW * LH; k++) {
            mv[2 * k] = -11; /* the picture moves +0.7 px/frame: backward MV -0.7 px, Q4 */
            mv[2 * k + 1] = 0;
        }
        tdc_fov_params_t fp;
        fov_params(&rp, &fp);
        assert_int_equal(tdc_fov_frame(&st, &fp, lp, LW * 3, mv, LW * 2, dk, W * 3, 11111, out, W * 3), TDC_OK);
        assert_int_equal(tdc_fov_frame(&st0, &fp, lp, LW * 3, mv, LW * 2, dk, W * 3, 11111, plain, W * 3), TDC_OK);
        if (f == 0 || jump) {
            assert_memory_equal(out, plain, sizeof out);
        } else {
            assert_memory_not_equal(out, plain, sizeof out);
        }
    }
    assert_int_equal(st.rejected_frames, 1);
    free(mem);
    free(mem0);
}

/* 10^5 frames: random pictures, gaze walks with saccades, random motion
 * vectors and frame times, TAA on.  The history stays within [0, 255*256],
 * the stage never fails, and a static uniform field afterwards converges to
 * exactly that field (no drift, no stuck history). */
static void test_long_run(void **state)
{
    (void)state;
    enum { W = 14, H = 11, LW = 8, LH = 6 };
    static uint8_t lp[LW * LH * 3], dk[W * H * 3], out[W * H * 3];
    static int16_t mv[LW * LH * 2];
    tdc_fov_t st;
    void *mem;
    run_stage(&st, 1, W, H, &mem);
    tdc_fov_params_t fp = {W * 128, H * 128, 1024, 4077, LW, LH, {0, 0}, 0, 0};
    for (uint32_t f = 0; f < 100000u; f++) {
        for (size_t k = 0; k < sizeof lp; k++) {
            lp[k] = (uint8_t)rnd();
        }
        for (size_t k = 0; k < sizeof dk; k++) {
            dk[k] = (uint8_t)rnd();
        }
        for (int k = 0; k < LW * LH * 2; k++) {
            mv[k] = (int16_t)((int32_t)(rnd() % 4001) - 2000);
        }
        if (f % 97 == 0) {
            fp.gaze_x_q8 = (int32_t)(rnd() % (3 * W * 256)) - W * 256;
            fp.gaze_y_q8 = (int32_t)(rnd() % (3 * H * 256)) - H * 256;
        } else {
            fp.gaze_x_q8 += (int32_t)(rnd() % 65) - 32;
            fp.gaze_y_q8 += (int32_t)(rnd() % 65) - 32;
            fp.gaze_x_q8 =
                fp.gaze_x_q8 < -W * 256 ? -W * 256 : (fp.gaze_x_q8 > 2 * W * 256 ? 2 * W * 256 : fp.gaze_x_q8);
            fp.gaze_y_q8 =
                fp.gaze_y_q8 < -H * 256 ? -H * 256 : (fp.gaze_y_q8 > 2 * H * 256 ? 2 * H * 256 : fp.gaze_y_q8);
        }
        if (f % 1000 == 0) {
            fp.alpha_q8 = (uint16_t)(256 + rnd() % 1793);
            fp.disk_q15 = (uint16_t)(rnd() % 32769);
        }
        const uint32_t dt = 4000u + rnd() % 30000u;
        if (tdc_fov_frame(&st, &fp, lp, LW * 3, mv, LW * 2, dk, W * 3, dt, out, W * 3) != TDC_OK) {
            fail_msg("frame %u refused", f);
        }
    }
    for (int b = 0; b < 2; b++) {
        for (int k = 0; k < W * H * 3; k++) {
            if (st.hist[b][k] > 255u * 256u) {
                fail_msg("history out of range: %u", st.hist[b][k]);
            }
        }
    }
    assert_int_equal(st.frames, 100000u);
    /* static uniform field, no motion: converges exactly */
    memset(lp, 200, sizeof lp);
    memset(dk, 200, sizeof dk);
    memset(mv, 0, sizeof mv);
    int f = 0;
    for (; f < 200; f++) {
        assert_int_equal(tdc_fov_frame(&st, &fp, lp, LW * 3, mv, LW * 2, dk, W * 3, 11111, out, W * 3), TDC_OK);
        int all = 1;
        for (int k = 0; k < W * H * 3; k++) {
            all &= out[k] == 200 && st.hist[st.cur][k] == 200u * 256u;
        }
        if (all) {
            break;
        }
    }
    printf("10^5 frames: %u saccades rejected; static field exact after %d frames\n", st.rejected_frames, f + 1);
    assert_true(f < 200);
    free(mem);
}

/* The per-frame tables are a cache: a stage that kept them from earlier
 * frames (other gazes, alpha, buffer sizes, disks; the radial table rebuilt
 * only when R, alpha or lp_w change) gives the same bytes as a fresh stage,
 * with the SIMD tap kernel and with the C one; the table is rebuilt exactly
 * when its key changes. */
static void test_tables_cached(void **state)
{
    (void)state;
    enum { W = 97, H = 71 };
    static uint8_t lp[W * H * 3], dk[W * H * 3], out_a[W * H * 3], out_b[W * H * 3], out_c[W * H * 3];
    for (size_t i = 0; i < sizeof lp; i++) {
        lp[i] = (uint8_t)rnd();
        dk[i] = (uint8_t)rnd();
    }
    tdc_fov_t kept, fresh;
    void *mem_k, *mem_f;
    run_stage(&kept, 0, W, H, &mem_k);
    run_stage(&fresh, 0, W, H, &mem_f);
    uint32_t builds = 0;
    tdc_fov_params_t prev = {0, 0, 0, 0, 0, 0, {0, 0}, TDC_FOV_KERNEL_LOG_POLAR, 0};
    for (int c = 0; c < 120; c++) {
        tdc_fov_params_t p = prev; /* kernel log-polar, every field set */
        p.gaze_x_q8 = (int32_t)(rnd() % (3u * W * 256u)) - W * 256;
        p.gaze_y_q8 = (int32_t)(rnd() % (3u * H * 256u)) - H * 256;
        if (c % 3 == 1) {
            p = prev; /* the same R: no rebuild */
            p.disk_q15 = (uint16_t)(rnd() % 32769u);
        } else if (c % 3 == 2) { /* the mirrored gaze: the same R, other columns */
            p = prev;
            p.gaze_x_q8 = W * 256 - prev.gaze_x_q8;
        } else {
            p.alpha_q8 = (uint16_t)(256u + rnd() % 1793u);
            p.disk_q15 = (uint16_t)(rnd() % 32769u);
            p.lp_w = (uint16_t)(4u + rnd() % (W - 3u));
            p.lp_h = (uint16_t)(4u + rnd() % (H - 3u));
        }
        const int same_key = c > 0 && p.alpha_q8 == prev.alpha_q8 && p.lp_w == prev.lp_w &&
                             (c % 3 != 0) /* the same R by construction */;
        prev = p;
        tdc_fov_set_simd(&kept, c & 1);
        assert_int_equal(tdc_fov_frame(&kept, &p, lp, W * 3u, NULL, 0, dk, W * 3u, 0, out_a, W * 3u), TDC_OK);
        assert_int_equal(tdc_fov_init(&fresh, &fresh.cfg, mem_f, tdc_fov_get_size(&fresh.cfg)), TDC_OK);
        assert_int_equal(tdc_fov_frame(&fresh, &p, lp, W * 3u, NULL, 0, dk, W * 3u, 0, out_b, W * 3u), TDC_OK);
        tdc_fov_set_simd(&fresh, 0);
        assert_int_equal(tdc_fov_frame(&fresh, &p, lp, W * 3u, NULL, 0, dk, W * 3u, 0, out_c, W * 3u), TDC_OK);
        assert_memory_equal(out_a, out_b, sizeof out_a);
        assert_memory_equal(out_a, out_c, sizeof out_a);
        assert_int_equal(fresh.rad_builds, 1u); /* the C-kernel frame reused the table */
        builds += same_key ? 0u : 1u;
        if (same_key) {
            assert_int_equal(kept.rad_builds, builds);
        }
        builds = kept.rad_builds;
    }
    printf("tables: %u radial builds in 120 frames (80 with the same R, alpha, lp_w as the frame before)\n", builds);
    assert_true(builds <= 40u + 1u);
    free(mem_k);
    free(mem_f);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_building_blocks), cmocka_unit_test(test_transform_pair),
    cmocka_unit_test(test_disk_rectangle),  cmocka_unit_test(test_uniform),
    cmocka_unit_test(test_disk_extremes),   cmocka_unit_test(test_bad_input),
    cmocka_unit_test(test_gaze_jump),       cmocka_unit_test(test_long_run),
    cmocka_unit_test(test_tables_cached),
)
