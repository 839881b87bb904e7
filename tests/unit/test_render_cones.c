/*
 * test_render_cones.c - the 6-cone incident radiance of Zeng §4.3
 * (render/tdc_render_cones.c): eqs. 9-10 against Monte Carlo, the
 * layout, recording, re-shading under a uniform sky, and the temporal
 * reuse across a change of normal against a cone-by-index copy.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "render/tdc_render_cones.h"

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (rng >> 11) * (1.0 / 9007199254740992.0);
}

/* uniform direction on the sphere */
static void sphere_dir(double d[3])
{
    double z = 2 * urand() - 1, ph = 2 * M_PI * urand(), s = sqrt(1 - z * z);
    d[0] = s * cos(ph);
    d[1] = s * sin(ph);
    d[2] = z;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Eqs. 9-10 vs the Monte Carlo share of the sphere inside both cones,
 * for the half-angle of the pi/3 cones and the pi/6 the equations print. */
static void test_overlap_vs_monte_carlo(void **state)
{
    (void)state;
    const double halves[2] = {acos(TDC_CONE_COS_HALF), M_PI / 6};
    const int n = 600000;
    for (int h = 0; h < 2; h++) {
        double half = halves[h], ch = cos(half), maxe = 0;
        for (int ia = 0; ia <= 8; ia++) {
            double al = ia * 2 * half / 8 * 1.05; /* up to past 2 half: 0 */
            double a1[3] = {0, 0, 1}, a2[3] = {sin(al), 0, cos(al)};
            int in = 0;
            for (int i = 0; i < n; i++) {
                double d[3];
                sphere_dir(d);
                in += dot3(d, a1) >= ch && dot3(d, a2) >= ch;
            }
            double mc = 4 * M_PI * in / n, f = tdc_cones_overlap(al, half);
            double e = fabs(f - mc) / (2 * M_PI * (1 - ch));
            if (e > maxe) maxe = e;
            if (ia == 0) assert_true(fabs(f - 2 * M_PI * (1 - ch)) < 1e-12);
            if (al >= 2 * half) assert_true(f == 0.0);
        }
        printf("cone overlap (half-angle %.2f deg, solid angle %.4f sr): eqs. 9-10 vs Monte Carlo, max error %.4f of "
               "a cone\n",
               half * 180 / M_PI, 2 * M_PI * (1 - ch), maxe);
        assert_true(maxe < 0.005);
    }
    /* the reuse's table of the formula */
    const double half = acos(TDC_CONE_COS_HALF), full = tdc_cones_overlap(0, half);
    double maxt = 0;
    for (int i = 0; i <= 100000; i++) {
        double al = 2.2 * half * i / 100000;
        double e = fabs(tdc_cones_overlap_share(cos(al)) - tdc_cones_overlap(al, half) / full);
        if (e > maxt) maxt = e;
    }
    printf("overlap table vs eqs. 9-10: max error %.2e of a cone\n", maxt);
    assert_true(maxt < 1e-4);
}

/* Axes: unit, cone 0 on the normal, the ring at 60 deg; the cones cover the
 * hemisphere but for gaps near the horizon, where the nearest cone takes
 * the sample. */
static void test_layout_and_record(void **state)
{
    (void)state;
    double n[3] = {0.3, -0.5, 0.81};
    double l = sqrt(dot3(n, n));
    for (int c = 0; c < 3; c++) n[c] /= l;
    double ax[TDC_CONES][3];
    tdc_cones_axes(n, ax);
    for (int k = 0; k < TDC_CONES; k++) {
        assert_true(fabs(dot3(ax[k], ax[k]) - 1) < 1e-12);
        assert_true(fabs(dot3(ax[k], n) - (k ? 0.5 : 1)) < 1e-12);
    }
    int covered = 0, total = 0, multi = 0;
    for (int i = 0; i < 200000; i++) {
        double d[3];
        sphere_dir(d);
        if (dot3(d, n) <= 0) continue;
        total++;
        double L[3] = {1, 1, 1}, cL[TDC_CONES][3] = {{0}}, cw[TDC_CONES] = {0};
        int in = 0;
        for (int k = 0; k < TDC_CONES; k++) in += dot3(ax[k], d) >= TDC_CONE_COS_HALF;
        int took = tdc_cones_record(ax, d, L, cL, cw);
        assert_int_equal(took, in ? in : 1);
        covered += in > 0;
        multi += in > 1;
    }
    printf("cone layout: %.1f %% of the hemisphere inside a cone, %.1f %% in two or more\n", 100.0 * covered / total,
           100.0 * multi / total);
    assert_true(covered > total * 9 / 10);
}

/* A uniform sky L0 recorded sample by sample re-shades to albedo * L0. */
static void test_shade_uniform_sky(void **state)
{
    (void)state;
    double n[3] = {0, 0, 1}, ax[TDC_CONES][3];
    tdc_cones_axes(n, ax);
    double cL[TDC_CONES][3] = {{0}}, cw[TDC_CONES] = {0};
    const double L0[3] = {0.5, 1.0, 2.0}, alb[3] = {0.8, 0.5, 0.2};
    for (int i = 0; i < 10000; i++) {
        double d[3];
        sphere_dir(d);
        if (d[2] < 0) d[2] = -d[2];
        tdc_cones_record(ax, d, L0, cL, cw);
    }
    for (int k = 0; k < TDC_CONES; k++) {
        assert_true(cw[k] > 0);
        for (int c = 0; c < 3; c++) cL[k][c] /= cw[k];
    }
    double out[3];
    tdc_cones_shade(alb, cL, cw, out);
    for (int c = 0; c < 3; c++) assert_true(fabs(out[c] - alb[c] * L0[c]) < 1e-9 * L0[c]);
    /* eq. 11 as printed (f_r sum L_k pi/3, no cosine) would give twice that */
    double eq11 = alb[1] / M_PI * 6 * L0[1] * M_PI / 3;
    printf("uniform sky: re-shaded %.4f = albedo * L %.4f; eq. 11 as printed %.4f\n", out[1], alb[1] * L0[1], eq11);
    assert_true(fabs(eq11 - 2 * alb[1] * L0[1]) < 1e-12);
}

/* Radiance of a directional sky: brighter toward e. */
static double sky(const double d[3])
{
    const double e[3] = {0.6, 0, 0.8};
    double c = dot3(d, e);
    return 1 + 4 * (c > 0 ? c * c * c : 0);
}

/* Mean sky radiance over cone k of axes ax (Monte Carlo inside the cone). */
static double cone_mean(const double ax[3])
{
    double s = 0;
    int n = 0;
    while (n < 4000) {
        double d[3];
        sphere_dir(d);
        if (dot3(d, ax) < TDC_CONE_COS_HALF) continue;
        s += sky(d);
        n++;
    }
    return s / n;
}

/* The previous pixel's cones (another normal, 25 deg away) hold the sky's
 * cone means; reusing them by overlap predicts the current cones' means
 * better than copying cone k to cone k (what reusing a colour would do). */
static void test_reuse_across_normals(void **state)
{
    (void)state;
    double nc[3] = {0, 0, 1}, np[3] = {sin(25 * M_PI / 180), 0, cos(25 * M_PI / 180)};
    double ca[TDC_CONES][3], pa[TDC_CONES][3];
    tdc_cones_axes(nc, ca);
    tdc_cones_axes(np, pa);
    double pL[TDC_CONES][3], pw[TDC_CONES], truth[TDC_CONES];
    for (int k = 0; k < TDC_CONES; k++) {
        double m = cone_mean(pa[k]);
        pL[k][0] = pL[k][1] = pL[k][2] = m;
        pw[k] = 1;
        truth[k] = cone_mean(ca[k]);
    }
    double cL[TDC_CONES][3] = {{0}}, cw[TDC_CONES] = {0}; /* no current sample: history only */
    tdc_cones_reuse(ca, cL, cw, pa, pL, pw, 0.2);
    double e_reuse = 0, e_copy = 0;
    for (int k = 0; k < TDC_CONES; k++) {
        assert_true(cw[k] > 0);
        e_reuse += (cL[k][0] - truth[k]) * (cL[k][0] - truth[k]);
        e_copy += (pL[k][0] - truth[k]) * (pL[k][0] - truth[k]);
    }
    e_reuse = sqrt(e_reuse / TDC_CONES);
    e_copy = sqrt(e_copy / TDC_CONES);
    printf("reuse across a 25 deg normal change: rms error of the cone means %.4f by overlap, %.4f by index\n",
           e_reuse, e_copy);
    assert_true(e_reuse < 0.7 * e_copy);
    /* the same normal: the history is the previous cones' own values (overlap with
     * itself 1, with the neighbours small) and the current sample's share is a */
    double c2[TDC_CONES][3], w2[TDC_CONES];
    for (int k = 0; k < TDC_CONES; k++) {
        c2[k][0] = c2[k][1] = c2[k][2] = 10;
        w2[k] = 1;
    }
    tdc_cones_reuse(pa, c2, w2, pa, pL, pw, 1.0);
    for (int k = 0; k < TDC_CONES; k++) assert_true(fabs(c2[k][0] - 10) < 1e-12); /* a = 1: the current frame only */
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_overlap_vs_monte_carlo),
    cmocka_unit_test(test_layout_and_record),
    cmocka_unit_test(test_shade_uniform_sky),
    cmocka_unit_test(test_reuse_across_normals),
)
