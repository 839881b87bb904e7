/*
 * test_sim_heatmap.c - the judge's visible-difference map
 * (sim/simulator/tdc_sim_heatmap.c through the hook tdc_fvvdp_set_dmap):
 *   - identical test and reference: the map is 0 everywhere;
 *   - noise in the top-left quadrant only: the map's mean there is more
 *     than 20x its mean in the bottom-right quadrant, and positive;
 *   - the hook does not change the metric: the same JOD bits with and
 *     without it;
 *   - the map is the mean over the frames added (two identical frames give
 *     the one frame's map);
 *   - a view the pyramid refuses (3x3, below its 4 px) gives no map.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "metrics/tdc_fvvdp.h"
#include "simulator/tdc_sim_heatmap.h"

#define W 96
#define H 96

static float ref[W * H], tst[W * H];

static void frames(int noisy)
{
    uint32_t s = 7;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            /* a mid-grey grating, 20-80 cd/m^2 */
            ref[y * W + x] = (float)(50.0 + 30.0 * sin(0.4 * x) * cos(0.3 * y));
            s = s * 1664525u + 1013904223u;
            double n = noisy && x < W / 2 && y < H / 2 ? 20.0 * ((s >> 8) / 16777216.0 - 0.5) : 0.0;
            tst[y * W + x] = (float)(ref[y * W + x] + n);
        }
    }
}

/* One image judged (fps 0), with the map's hook when hm is given. */
static double judge(tdc_sim_heatmap_t *hm)
{
    char why[160];
    tdc_fvvdp_geometry_t g = tdc_fvvdp_geometry_ppd(W, H, 20.0);
    tdc_fvvdp_t *m = tdc_fvvdp_new(&g, 0.0, why, sizeof why);
    assert_non_null(m);
    if (hm) {
        tdc_fvvdp_set_dmap(m, tdc_sim_heatmap_bands(hm));
    }
    double j = tdc_fvvdp_frame(m, tst, ref, NULL);
    if (hm) {
        tdc_sim_heatmap_add(hm, ref);
    }
    tdc_fvvdp_free(m);
    return j;
}

static double quad_mean(const double *d, int qx, int qy)
{
    double s = 0.0;
    for (int y = qy * H / 2; y < (qy + 1) * H / 2; y++) {
        for (int x = qx * W / 2; x < (qx + 1) * W / 2; x++) {
            s += d[y * W + x];
        }
    }
    return s / (W / 2 * H / 2);
}

static void test_identical_is_zero(void **st)
{
    (void)st;
    frames(0);
    tdc_sim_heatmap_t *hm = tdc_sim_heatmap_new(W, H, 20.0);
    assert_non_null(hm);
    assert_null(tdc_sim_heatmap_map(hm));
    assert_true(judge(hm) == 10.0);
    const double *d = tdc_sim_heatmap_map(hm);
    assert_non_null(d);
    for (int i = 0; i < W * H; i++) {
        assert_true(d[i] == 0.0);
    }
    tdc_sim_heatmap_free(hm);
}

static void test_local_difference(void **st)
{
    (void)st;
    frames(1);
    double plain = judge(NULL);
    tdc_sim_heatmap_t *hm = tdc_sim_heatmap_new(W, H, 20.0);
    assert_non_null(hm);
    double hooked = judge(hm);
    assert_true(plain == hooked); /* the hook leaves the metric's bits */
    assert_true(plain < 9.9);
    const double *d = tdc_sim_heatmap_map(hm);
    double in = quad_mean(d, 0, 0), out = quad_mean(d, 1, 1);
    print_message("heat map: noisy quadrant %.4f, clean quadrant %.6f (JOD %.3f)\n", in, out, plain);
    assert_true(in > 0.05);
    assert_true(in > 20.0 * out);
    /* a second identical frame: the mean stays */
    double first = d[10 * W + 10];
    judge(hm);
    assert_int_equal(tdc_sim_heatmap_frames(hm), 2);
    assert_true(fabs(tdc_sim_heatmap_map(hm)[10 * W + 10] - first) <= 1e-12 * fabs(first));
    tdc_sim_heatmap_free(hm);
}

static void test_no_band(void **st)
{
    (void)st;
    assert_null(tdc_sim_heatmap_new(3, 3, 20.0));
    tdc_sim_heatmap_t *hm = tdc_sim_heatmap_new(4, 4, 1.0); /* the smallest: one band */
    assert_non_null(hm);
    tdc_sim_heatmap_free(hm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identical_is_zero),
        cmocka_unit_test(test_local_difference),
        cmocka_unit_test(test_no_band),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
