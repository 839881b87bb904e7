/*
 * test_fov_ref.c - the fixed-point foveated remap (firmware/tdc_fov.c)
 * against the double-precision reference (ref/ref_fov.c) on a procedural
 * picture sampled as the renderer samples it.  Per case: max abs error of
 * the 8-bit output against the unrounded reference, share within 1 LSB.
 * Cases: gaze at the centre, off-centre, each corner and outside the
 * screen; alpha = 1, 4, 8; disk fraction 0, 12.443 %, 40 %, 1; and TAA runs
 * (8 frames of a 1.3 px/frame pan with Halton jitter and motion vectors).
 * Target (team standard): >= 99.9 % within 1 LSB and max <= 2 LSB per case.
 * Measured (gcc -O2, this file's cases): worst case max 1.201 LSB, 99.9917 %
 * within 1 LSB (with 8-bit angular fractions it was 1.36 LSB / 99.28 %: the
 * periphery interpolates between rows tens of codes apart).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fov_fixture.h"

#define W 160
#define H 100

static fov_worst_t g_worst = {0, 100, 0};

static void run_case(const char *name, double cx, double cy, double alpha, double disk, int taa)
{
    ref_fov_params_t rp = {cx, cy, alpha, disk, (int)lround(0.555 * W), (int)lround(0.555 * H), 0, 0, 0};
    fov_quantise(&rp);
    tdc_fov_params_t fp;
    fov_params(&rp, &fp);
    tdc_fov_config_t cfg = {W, H, (uint8_t)taa};
    size_t mn = tdc_fov_get_size(&cfg);
    void *mem = malloc(mn);
    tdc_fov_t st;
    assert_int_equal(tdc_fov_init(&st, &cfg, mem, mn), TDC_OK);
    fov_case_t c;
    assert_int_equal(fov_case_open(&c, W, H, &rp, taa), 0);
    const int frames = taa ? 8 : 1;
    for (int f = 0; f < frames; f++) {
        /* Halton(2,3) jitter in [-0.5, 0.5) where TAA follows */
        double hx = 0, hy = 0;
        if (taa) {
            for (int k = f + 1, b = 2; k; k /= 2, b *= 2) hx += (double)(k % 2) / b;
            for (int k = f + 1, b = 3; k; k /= 3, b *= 3) hy += (double)(k % 3) / b;
            hx -= 0.5;
            hy -= 0.5;
        }
        fov_make_inputs(&c.g, taa ? 1.3 * f : 0, hx, hy, c.lp, c.disk);
        assert_int_equal(fov_case_frame(&c, &st, &fp, &rp), TDC_OK);
    }
    double share;
    const int ok = fov_err_done(&c.err, &g_worst, &share);
    printf("  %-22s alpha %.0f disk %6.3f %s: max %.3f LSB, within 1 LSB %.4f %%  l=%d u0=%d  %s\n", name, alpha, disk,
           taa ? "taa" : "   ", c.err.maxe, share, c.g.l, c.g.u0, ok ? "ok" : "FAIL");
    fov_case_close(&c);
    free(mem);
}

static void test_fixed_vs_double(void **state)
{
    (void)state;
    static const fov_gaze_t gz[] = {FOV_REF_GAZES(W, H)};
    static const double alphas[] = {1, 4, 8};
    static const double disks[] = {0, 0.12443, 0.4, 1};
    for (unsigned a = 0; a < 3; a++) {
        for (unsigned d = 0; d < 4; d++) {
            for (unsigned k = 0; k < sizeof gz / sizeof gz[0]; k++) {
                if (a != 1 && k > 1 && d != 1) {
                    continue; /* the full gaze sweep at alpha = 4 and at the 12.443 % disk */
                }
                run_case(gz[k].name, gz[k].cx, gz[k].cy, alphas[a], disks[d], 0);
            }
        }
    }
    run_case("centre", W / 2.0, H / 2.0, 4, 0.12443, 1);
    run_case("off-centre", 37.3, 61.7, 4, 0.12443, 1);
    run_case("corner BR", W, H, 4, 0.12443, 1);
    run_case("centre", W / 2.0, H / 2.0, 1, 0.0, 1);
    run_case("centre", W / 2.0, H / 2.0, 8, 0.4, 1);
    printf("worst case: max %.3f LSB, within 1 LSB %.4f %%\n", g_worst.max, g_worst.share);
    assert_false(g_worst.fail);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_fixed_vs_double)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
