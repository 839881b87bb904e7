/*
 * test_render_texture.c - texture filtering by ray cones (TDRT §3.1.1): a
 * minified checker (about 8 checks per pixel) renders at one ray per pixel
 * as its mean, not as aliases (point-sampled it is noise between the two
 * colours); a magnified one keeps its full contrast (the filter does not
 * blur what the pixels resolve); the filtered full frame agrees with the
 * 64-sample ground truth; the footprint grows with distance and obliquity,
 * and through a planar mirror with the total path length.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/tdc_render.h"
#include "render/tdc_render_internal.h"

#define W 64
#define H 48

static tdc_scene_t sc;

static tdc_render_t *open_scene(const char *text, int filter)
{
    char err[256];
    if (tdc_scene_parse(text, "t", NULL, &sc, err, sizeof err) != TDC_SCENE_OK) fail_msg("%s", err);
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.threads = 1;
    cfg.gt_samples = 64;
    cfg.tex_filter = filter;
    tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
    if (!r) fail_msg("%s", err);
    return r;
}

static void render(tdc_render_t *r, tdc_render_mode_t mode, float *rgb)
{
    tdc_render_out_t out;
    memset(&out, 0, sizeof out);
    out.rgb = rgb;
    tdc_render_stats_t st;
    assert_int_equal(tdc_render_frame(r, 1, mode, &out, &st), 0);
}

/* A full frame of the scene filtered (f1) and point-sampled (f0). */
static void render_both(const char *text, float *f1, float *f0)
{
    tdc_render_t *r = open_scene(text, 1);
    render(r, TDC_RENDER_FULL, f1);
    tdc_render_close(r);
    r = open_scene(text, 0);
    render(r, TDC_RENDER_FULL, f0);
    tdc_render_close(r);
}

/* mean and standard deviation of the red channel over the whole frame */
static void stats(const float *rgb, double *mean, double *sd)
{
    double s = 0, s2 = 0;
    for (int i = 0; i < W * H; i++) {
        s += rgb[3 * i];
        s2 += (double)rgb[3 * i] * rgb[3 * i];
    }
    *mean = s / (W * H);
    *sd = sqrt(fmax(0, s2 / (W * H) - *mean * *mean));
}

/* An unlit checker 0.1 / 0.9 filling the view at distance 5 (fov 45, 48
 * rows: 0.086 units per pixel).  Scale S: checks of S units. */
static const char scene_fmt[] = "tdc-scene 1\n"
                                "material m unlit diffuse 0.1 0.1 0.1 checker %g 0.9 0.9 0.9\n"
                                "camera 0 pos 0 0 5 look 0 0 0 fov 45\n"
                                "object wall rect size 40 40 material m\n";

static void test_minified_checker_mean(void **state)
{
    (void)state;
    static float f1[W * H * 3], f0[W * H * 3], gt[W * H * 3];
    char text[512];
    snprintf(text, sizeof text, scene_fmt, 0.0107); /* 8 checks per pixel */
    render_both(text, f1, f0);
    tdc_render_t *r = open_scene(text, 1);
    render(r, TDC_RENDER_GROUND_TRUTH, gt);
    tdc_render_close(r);
    double m1, s1, m0, s0, mg, sg;
    stats(f1, &m1, &s1);
    stats(f0, &m0, &s0);
    stats(gt, &mg, &sg);
    print_message("minified checker: filtered mean %.4f sd %.4f; point-sampled mean %.4f sd %.4f; ground truth "
                  "mean %.4f sd %.4f\n",
                  m1, s1, m0, s0, mg, sg);
    assert_true(fabs(m1 - 0.5) < 0.01); /* converges to the checker's mean */
    assert_true(s1 < 0.02);             /* no aliases */
    assert_true(s0 > 0.25);             /* what point sampling gave: noise between 0.1 and 0.9 */
    assert_true(fabs(mg - 0.5) < 0.02 && sg < 0.1);
    double d = 0;
    for (int i = 0; i < W * H; i++) d += fabs(f1[3 * i] - gt[3 * i]) / (W * H);
    assert_true(d < 0.05); /* the filtered frame is what the ground truth sees */
}

static void test_magnified_checker_sharp(void **state)
{
    (void)state;
    static float f1[W * H * 3], f0[W * H * 3];
    char text[512];
    snprintf(text, sizeof text, scene_fmt, 1.0); /* 11.6 px per check */
    render_both(text, f1, f0);
    int same = 0, lo = 0, hi = 0;
    for (int i = 0; i < W * H; i++) {
        same += fabsf(f1[3 * i] - f0[3 * i]) < 1e-6f;
        lo += f1[3 * i] < 0.1001f;
        hi += f1[3 * i] > 0.8999f;
    }
    print_message("magnified checker: %d of %d pixels unchanged by the filter, %d dark, %d bright\n", same, W * H,
                  lo, hi);
    assert_true(same > W * H * 8 / 10); /* only pixels on a check edge change */
    assert_true(lo > W * H / 3 && hi > W * H / 3);
}

/* The footprint: cone x distance / |cos|, cos floored at 1/16; object-space normals through minv. */
static void test_footprint(void **state)
{
    (void)state;
    const double d[3] = {0, 0, -2}, n[3] = {0, 0, 1}, n45[3] = {0, 1, 1}, n90[3] = {0, 1, 0};
    assert_true(fabs(tdc_r_tex_footprint(0.01, 5, d, n, NULL) - 0.05) < 1e-12);
    assert_true(fabs(tdc_r_tex_footprint(0.01, 10, d, n, NULL) - 0.1) < 1e-12);
    assert_true(fabs(tdc_r_tex_footprint(0.01, 5, d, n45, NULL) - 0.05 * sqrt(2)) < 1e-12);
    assert_true(fabs(tdc_r_tex_footprint(0.01, 5, d, n90, NULL) - 0.05 * 16) < 1e-12);
    /* an object rotated 90 degrees about x: world -z is object +y */
    const double minv[12] = {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0};
    const double ny[3] = {0, 1, 0};
    assert_true(fabs(tdc_r_tex_footprint(0.01, 5, d, ny, minv) - 0.05) < 1e-12);
    /* scaled 2x: half the object length per world length */
    const double minv2[12] = {0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0};
    assert_true(fabs(tdc_r_tex_footprint(0.01, 5, d, n, minv2) - 0.025) < 1e-12);
}

/* A checker seen only in a planar mirror: reflected hits filter over the
 * whole path, so the minified reflection is its mean too. */
static const char scene_mirror[] = "tdc-scene 1\n"
                                   "background 0 0 0\n"
                                   "material mir unlit diffuse 0 0 0 mirror 1\n"
                                   "material m unlit diffuse 0.1 0.1 0.1 checker 0.006 0.9 0.9 0.9\n"
                                   "camera 0 pos 0 0 2.5 look 0 0 0 fov 45\n"
                                   "object glass rect size 40 40 material mir\n"
                                   "object wall rect size 40 40 material m pos 0 0 5 rot 0 180 0\n";

static void test_mirror_footprint(void **state)
{
    (void)state;
    static float f1[W * H * 3], f0[W * H * 3];
    render_both(scene_mirror, f1, f0);
    double m1, s1, m0, s0;
    stats(f1, &m1, &s1);
    stats(f0, &m0, &s0);
    print_message("checker in a mirror: filtered mean %.4f sd %.4f; point-sampled mean %.4f sd %.4f\n", m1, s1, m0,
                  s0);
    assert_true(fabs(m1 - 0.5) < 0.02 && s1 < 0.03);
    assert_true(s0 > 0.25);
}

int main(void)
{
    const struct CMUnitTest t[] = {
        cmocka_unit_test(test_minified_checker_mean),
        cmocka_unit_test(test_magnified_checker_sharp),
        cmocka_unit_test(test_footprint),
        cmocka_unit_test(test_mirror_footprint),
    };
    return cmocka_run_group_tests(t, NULL, NULL);
}
