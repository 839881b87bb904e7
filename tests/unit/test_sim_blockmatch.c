/*
 * test_sim_blockmatch.c - the ASW compositor's motion estimate
 * (sim/simulator/tdc_sim_blockmatch.c) on known translations of a textured
 * image: integer, fractional, large (beyond the coarse level's reach of a
 * single-level search), diagonal; static content estimates zero; a flat
 * image does not invent motion.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "simulator/tdc_sim_blockmatch.h"

#define W 160
#define H 120

/* Value noise: random lattice values, smoothstep-interpolated, three
 * octaves (16, 6 and 2.5 px), so content is textured at every scale and
 * not periodic (a periodic texture has several equally good matches).  A
 * continuous function of position: a fractional translation is exact. */
static double lattice(int i, int j, int o)
{
    uint32_t h = (uint32_t)i * 73856093u ^ (uint32_t)j * 19349663u ^ (uint32_t)o * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return (h & 0xFFFFu) / 65535.0;
}

static double noise(double x, double y, double cell, int o)
{
    double u = x / cell + 1000, v = y / cell + 1000;
    int i = (int)floor(u), j = (int)floor(v);
    double fx = u - i, fy = v - j;
    fx = fx * fx * (3 - 2 * fx);
    fy = fy * fy * (3 - 2 * fy);
    double a = lattice(i, j, o), b = lattice(i + 1, j, o), c = lattice(i, j + 1, o), d = lattice(i + 1, j + 1, o);
    return (a + (b - a) * fx) * (1 - fy) + (c + (d - c) * fx) * fy;
}

static double tex(double x, double y)
{
    return 0.15 + 0.4 * noise(x, y, 16, 0) + 0.3 * noise(x, y, 6, 1) + 0.15 * noise(x, y, 2.5, 2);
}

static void make(uint8_t *img, double ox, double oy, int flat)
{
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            double v = flat ? 0.5 : tex(x + ox, y + oy);
            uint8_t c = (uint8_t)lrint(255.0 * (v < 0 ? 0 : (v > 1 ? 1 : v)));
            uint8_t *p = img + 3 * ((size_t)y * W + x);
            p[0] = p[1] = p[2] = c;
        }
    }
}

/* cur(p) = prev(p + d): prev is the texture, cur the texture shifted by d.
 * Checks every pixel at least 2 blocks plus the shift away from the border
 * (clamped borders cannot be matched): at least 95 % within tol px of d,
 * none beyond 2 tol (the SAD parabola is biased for L1 costs; a wrong
 * match would be off by a pixel or more). */
static void check_shift(double dx, double dy, double tol)
{
    static uint8_t prev[W * H * 3], cur[W * H * 3];
    static int16_t mv[W * H * 2];
    make(prev, 0, 0, 0);
    make(cur, dx, dy, 0);
    tdc_bm_t bm;
    assert_int_equal(tdc_bm_init(&bm, W, H), 0);
    tdc_bm_estimate(&bm, prev, cur, 1.0, mv);
    int m = 2 * TDC_BM_BLOCK + (int)ceil(fmax(fabs(dx), fabs(dy)));
    double worst = 0;
    int n = 0, ok = 0;
    for (int y = m; y < H - m; y++) {
        for (int x = m; x < W - m; x++) {
            const int16_t *v = mv + 2 * ((size_t)y * W + x);
            double e = fmax(fabs(v[0] / 16.0 - dx), fabs(v[1] / 16.0 - dy));
            worst = fmax(worst, e);
            ok += e <= tol;
            n++;
        }
    }
    print_message("shift (%.2f, %.2f): %.1f %% of %d interior pixels within %.2f px, worst error %.3f px\n", dx, dy,
                  100.0 * ok / n, n, tol, worst);
    assert_true(n > 1000);
    assert_true(ok >= 0.95 * n);
    assert_true(worst <= 2 * tol);
    tdc_bm_free(&bm);
}

static void test_bm_integer(void **state)
{
    (void)state;
    check_shift(3, 0, 0.1);
    check_shift(0, -5, 0.1);
    check_shift(-4, 2, 0.1);
}

static void test_bm_fractional(void **state)
{
    (void)state;
    check_shift(2.5, 0, 0.25);
    check_shift(-1.25, 3.75, 0.25);
}

/* 21 px: only the pyramid reaches it (the finest level searches +-1). */
static void test_bm_large(void **state)
{
    (void)state;
    check_shift(21, 0, 0.25);
    check_shift(-14.5, -13.75, 0.25);
}

static void test_bm_static_and_flat(void **state)
{
    (void)state;
    check_shift(0, 0, 0.0);
    static uint8_t a[W * H * 3];
    static int16_t mv[W * H * 2];
    make(a, 0, 0, 1);
    tdc_bm_t bm;
    assert_int_equal(tdc_bm_init(&bm, W, H), 0);
    tdc_bm_estimate(&bm, a, a, 1.0, mv);
    for (size_t i = 0; i < 2 * W * H; i++) {
        assert_int_equal(mv[i], 0);
    }
    tdc_bm_free(&bm);
}

/* scale 0.5 halves the two-frame vector (the extrapolation ASW needs). */
static void test_bm_scale(void **state)
{
    (void)state;
    static uint8_t prev[W * H * 3], cur[W * H * 3];
    static int16_t mv[W * H * 2];
    make(prev, 0, 0, 0);
    make(cur, 6, -2, 0);
    tdc_bm_t bm;
    assert_int_equal(tdc_bm_init(&bm, W, H), 0);
    tdc_bm_estimate(&bm, prev, cur, 0.5, mv);
    const int16_t *v = mv + 2 * ((size_t)(H / 2) * W + W / 2);
    assert_true(abs(v[0] - 48) <= 2 && abs(v[1] + 16) <= 2);
    tdc_bm_free(&bm);
}

int main(void)
{
    const struct CMUnitTest t[] = {
        cmocka_unit_test(test_bm_integer), cmocka_unit_test(test_bm_fractional),
        cmocka_unit_test(test_bm_large),   cmocka_unit_test(test_bm_static_and_flat),
        cmocka_unit_test(test_bm_scale),
    };
    return cmocka_run_group_tests(t, NULL, NULL);
}
