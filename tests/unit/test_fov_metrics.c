/*
 * test_fov_metrics.c - the foveated error statistics (sim/metrics/
 * tdc_fov_metrics.c): FLIP's weighted median on maps with known answers,
 * eccentricity weighting (the same error near the gaze weighs more than in
 * the periphery; a uniform map gives its value), disk means.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <cmocka.h>

#include "metrics/tdc_fov_metrics.h"

static void test_weighted_median(void **state)
{
    (void)state;
    static double m[1000];
    for (int i = 0; i < 1000; i++) m[i] = 0.305;
    assert_true(fabs(tdc_flip_weighted_median(m, 1000) - 0.305) < 0.006); /* within its bucket */
    for (int i = 0; i < 1000; i++) m[i] = 0;
    assert_true(tdc_flip_weighted_median(m, 1000) == 0);
    /* 900 pixels at 0.05, 100 at 0.95: weights 45 vs 95 -> the median falls in the high bucket */
    for (int i = 0; i < 1000; i++) m[i] = i < 900 ? 0.055 : 0.955;
    const double wm = tdc_flip_weighted_median(m, 1000);
    assert_true(wm > 0.9 && wm < 0.96);
    /* the plain median would be 0.055; weighting moves it up (larger errors count more) */
    for (int i = 0; i < 1000; i++) m[i] = i < 990 ? 0.055 : 0.955;
    assert_true(tdc_flip_weighted_median(m, 1000) < 0.06);
}

static void test_eccentricity(void **state)
{
    (void)state;
    enum { W = 200, H = 100 };
    static double m[W * H];
    for (int k = 0; k < W * H; k++) m[k] = 0.4;
    assert_true(fabs(tdc_ecc_weighted_mean(m, W, H, 50, 50, 20) - 0.4) < 1e-12);
    /* error only within 10 px of the gaze vs only beyond 80 px: the first weighs more per pixel */
    double near = 0, far = 0;
    for (int pass = 0; pass < 2; pass++) {
        long n = 0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++) {
                const double r = hypot(i + 0.5 - 50, j + 0.5 - 50);
                const int on = pass ? r > 80 : r <= 10;
                m[j * W + i] = on;
                n += on;
            }
        const double v = tdc_ecc_weighted_mean(m, W, H, 50, 50, 20) / ((double)n / (W * H));
        if (pass)
            far = v;
        else
            near = v;
    }
    printf("per-pixel weight of a foveal error / a peripheral one: %.2f\n", near / far);
    assert_true(near > 2 * far);
    for (int k = 0; k < W * H; k++) m[k] = (k % W) < 100 ? 1 : 0;
    assert_true(fabs(tdc_disk_mean(m, W, H, 50, 50, 20, 1) - 1) < 1e-12);
    assert_true(fabs(tdc_disk_mean(m, W, H, 150, 50, 20, 1)) < 1e-12);
    assert_true(tdc_disk_mean(m, W, H, 50, 50, 1000, 0) == 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_weighted_median), cmocka_unit_test(test_eccentricity)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
