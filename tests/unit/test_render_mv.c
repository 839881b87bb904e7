/*
 * test_render_mv.c - motion vectors of the renderer (issue 6):
 *   a surface point reprojected with its MV lands on the same surface point
 *   in the previous frame within 0.01 px, for a camera pan, object motion and
 *   a mirror reflection (TDRT §3.1.2); shadow MVs (Zeng §4.1) follow a
 *   moving shadow over a static receiver; dual MVs (Zeng §4.3) send
 *   disoccluded pixels to the background; static scenes skip MV work.
 * Tiny resolutions: each case traces a few thousand rays.
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

#define W 64
#define H 48

static tdc_render_t *open_text(const char *text, int shadow_mv, int dual_mv)
{
    static tdc_scene_t sc;
    char err[256];
    tdc_scene_status_t st = tdc_scene_parse(text, "test", NULL, &sc, err, sizeof err);
    if (st != TDC_SCENE_OK) fprintf(stderr, "%s\n", err);
    assert_int_equal(st, TDC_SCENE_OK);
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.threads = 2;
    cfg.shadow_mv = shadow_mv;
    cfg.dual_mv = dual_mv;
    tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
    if (!r) fprintf(stderr, "%s\n", err);
    assert_non_null(r);
    return r;
}

/* Reprojection check over every pixel centre of frame f.  mode 0: primary
 * surface, 1: reflected surface seen in the mirror.  Returns the max error
 * in px and the number of pixels checked; `use_zero_mv` checks MV = 0
 * instead (to show the test can fail). */
static double reproject_err(tdc_render_t *r, uint32_t f, int mode, int use_zero_mv, int *checked, int *occluded)
{
    double maxe = 0;
    *checked = *occluded = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double px = x + 0.5, py = y + 0.5;
            tdc_render_probe_t a, b;
            tdc_render_probe(r, f, px, py, &a);
            if (!a.hit) continue;
            if (mode == 1 && !a.mirror_hit) continue;
            if (mode == 0 && a.mirror_hit) continue;
            double mx = use_zero_mv ? 0 : a.mv[0], my = use_zero_mv ? 0 : a.mv[1];
            double qx = px + mx, qy = py + my;
            if (qx < 0 || qy < 0 || qx >= W || qy >= H) continue; /* came from outside the view */
            tdc_render_probe(r, f - 1, qx, qy, &b);
            double ex, ey;
            if (mode == 0) {
                if (!b.hit || b.obj != a.obj) {
                    (*occluded)++;
                    continue;
                }
                /* where the previous frame's surface point is now */
                assert_int_equal(tdc_render_project(r, f, b.obj, b.q, &ex, &ey), 0);
            } else {
                if (!b.mirror_hit || b.refl_obj != a.refl_obj || b.obj != a.obj) {
                    (*occluded)++;
                    continue;
                }
                assert_int_equal(tdc_render_project_reflected(r, f, a.obj, a.q, b.refl_obj, b.refl_q, &ex, &ey), 0);
            }
            double e = hypot(ex - px, ey - py);
            if (e > maxe) maxe = e;
            (*checked)++;
        }
    return maxe;
}

static const char scene_pan[] = "tdc-scene 1\n"
                                "fps 8\n"
                                "material wall diffuse 0.8 0.8 0.8 checker 0.3 0.1 0.1 0.1\n"
                                "material ball diffuse 0.9 0.3 0.1\n"
                                "camera 0 pos -0.5 1 5 yaw -5 pitch -3 fov 50\n"
                                "camera 1 pos 0.5 1.2 5 yaw 5 pitch 2 fov 50\n"
                                "object wall rect size 20 10 material wall pos 0 1 -2\n"
                                "object ball sphere radius 0.6 material ball pos 0.3 1 0\n"
                                "light l point pos 0 5 5 intensity 30 30 30\n";

static void test_mv_camera_pan(void **state)
{
    (void)state;
    tdc_render_t *r = open_text(scene_pan, 0, 0);
    int n, occ;
    double e = reproject_err(r, 5, 0, 0, &n, &occ);
    printf("camera pan: max reprojection error %.2e px over %d pixels (%d occluded)\n", e, n, occ);
    assert_true(n > W * H * 8 / 10);
    assert_true(e < 0.01);
    /* MV = 0 would be wrong by far more */
    double e0 = reproject_err(r, 5, 0, 1, &n, &occ);
    assert_true(e0 > 0.2);
    tdc_render_close(r);
}

static const char scene_object[] = "tdc-scene 1\n"
                                   "fps 8\n"
                                   "material floor diffuse 0.7 0.7 0.7 checker 0.5 0.2 0.2 0.2\n"
                                   "material ball diffuse 0.9 0.3 0.1 checker 0.2 0.1 0.1 0.9\n"
                                   "material cube diffuse 0.1 0.3 0.9 stripes 0.1 0.9 0.9 0.9\n"
                                   "camera 0 pos 0 2 6 look 0 0.5 0 fov 45\n"
                                   "object floor rect size 20 20 material floor rot -90 0 0\n"
                                   "object ball sphere radius 0.7 material ball pos -1.5 0.8 0\n"
                                   "key ball 0 pos -1.5 0.8 0 rot 0 0 0\n"
                                   "key ball 1 pos 1.5 1.2 0.5 rot 30 0 -180 scale 1.3\n"
                                   "object cube box size 0.8 0.8 0.8 material cube pos 1 0.5 -1\n"
                                   "key cube 0 rot 0 0 0\n"
                                   "key cube 1 pos 0 0.7 -1 rot 20 90 10\n"
                                   "light l point pos 2 6 4 intensity 50 50 50\n";

static void test_mv_object_motion(void **state)
{
    (void)state;
    tdc_render_t *r = open_text(scene_object, 0, 0);
    int n, occ;
    double e = reproject_err(r, 5, 0, 0, &n, &occ);
    printf("object motion: max reprojection error %.2e px over %d pixels (%d occluded)\n", e, n, occ);
    assert_true(n > W * H / 2);
    assert_true(occ < n / 10);
    assert_true(e < 0.01);
    tdc_render_close(r);
}

static const char scene_mirror[] = "tdc-scene 1\n"
                                   "fps 8\n"
                                   "background 0.3 0.4 0.6\n"
                                   "material floor diffuse 0 0 0 mirror 1\n"
                                   "material ball diffuse 0.9 0.3 0.1 checker 0.2 0.1 0.1 0.9\n"
                                   "camera 0 pos 0 1.5 5 look 0 0 0 fov 50\n"
                                   "camera 1 pos 0.3 1.6 5 look 0 0 0\n"
                                   "object floor rect size 30 30 material floor rot -90 0 0\n"
                                   "object ball sphere radius 0.8 material ball pos -2 1 -1\n"
                                   "key ball 0 pos -2 1 -1 rot 0 0 0\n"
                                   "key ball 1 pos 2 1.3 0 rot 0 40 -90\n";

static void test_mv_mirror(void **state)
{
    (void)state;
    tdc_render_t *r = open_text(scene_mirror, 0, 0);
    int n, occ;
    double e = reproject_err(r, 5, 1, 0, &n, &occ);
    printf("mirror: max reprojection error of reflected MVs %.2e px over %d reflected pixels (%d occluded)\n", e, n,
           occ);
    assert_true(n > 50);
    assert_true(e < 0.01);
    tdc_render_close(r);
}

/* Primary vs reflected: with reflected MVs disabled the error is large. */
static void test_mv_mirror_needs_reflected(void **state)
{
    (void)state;
    static tdc_scene_t sc;
    char err[256];
    assert_int_equal(tdc_scene_parse(scene_mirror, "t", NULL, &sc, err, sizeof err), TDC_SCENE_OK);
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.reflect_mv = 0;
    tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
    assert_non_null(r);
    int n, occ;
    double e = reproject_err(r, 5, 1, 0, &n, &occ);
    printf("mirror with primary MVs only: max error %.2f px\n", e);
    assert_true(e > 0.5);
    tdc_render_close(r);
}

static const char scene_fence[] =
    "tdc-scene 1\n"
    "fps 8\n"
    "material ground diffuse 0.8 0.8 0.8\n"
    "material paint diffuse 0.7 0.2 0.1\n"
    "camera 0 pos 0 4 5 look 0 0 0.5 fov 45\n"
    "object floor rect size 12 12 material ground rot -90 0 0\n"
    "object fence fence slats 5 width 0.15 gap 0.2 height 1 depth 0.05 material paint pos -0.8 0.4 -1\n"
    "key fence 0 pos -0.8 0.4 -1\n"
    "key fence 1 pos 0.8 0.4 -1\n"
    "light lamp point pos 0 3 -3.5 intensity 20 20 20\n";

static void test_shadow_mv_follows_shadow(void **state)
{
    (void)state;
    tdc_render_t *r = open_text(scene_fence, 1, 0);
    const uint32_t f = 5;
    int shadowed = 0, followed = 0, primary_followed = 0;
    double maxd = 0, minw = 1;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            tdc_render_probe_t a, b, c;
            tdc_render_probe(r, f, x + 0.5, y + 0.5, &a);
            if (!a.hit || a.obj != 0 || !a.in_shadow) continue; /* shadowed floor pixels */
            shadowed++;
            /* static receiver: the primary MV is zero */
            assert_true(fabs(a.mv[0]) < 1e-6 && fabs(a.mv[1]) < 1e-6);
            /* the shadow MV moves with the shadow, against the fence motion (+x) */
            assert_true(a.shadow_mv[0] < -0.05);
            double qx = x + 0.5 + a.shadow_mv[0], qy = y + 0.5 + a.shadow_mv[1];
            tdc_render_probe(r, f - 1, qx, qy, &b);
            if (b.in_shadow && b.blocker_obj == a.blocker_obj) {
                double d = sqrt(pow(b.blocker_q[0] - a.blocker_q[0], 2) + pow(b.blocker_q[1] - a.blocker_q[1], 2) +
                                pow(b.blocker_q[2] - a.blocker_q[2], 2));
                if (d > maxd) maxd = d;
                if (d < 1e-3) followed++;
            }
            if (a.shadow_weight < minw) minw = a.shadow_weight;
            /* with the primary MV (= 0) the previous frame's pixel is shadowed
             * by a different point of the fence (or not at all) */
            tdc_render_probe(r, f - 1, x + 0.5, y + 0.5, &c);
            if (c.in_shadow) {
                double d = sqrt(pow(c.blocker_q[0] - a.blocker_q[0], 2) + pow(c.blocker_q[2] - a.blocker_q[2], 2));
                if (d < 1e-3) primary_followed++;
            }
        }
    printf("shadow MVs: %d shadowed pixels, %d followed to the same blocker point (max dist %.2e), min falloff "
           "weight %.3f; primary MV followed %d\n",
           shadowed, followed, maxd, minw, primary_followed);
    assert_true(shadowed > 50);
    assert_true(followed >= shadowed * 95 / 100);
    assert_true(primary_followed < shadowed / 10);
    assert_true(minw > 0.99); /* planar receiver: theta = 90 degrees */

    /* the full-frame output carries the same vectors */
    static int16_t mv[W * H * 2], mvs[W * H * 2];
    static float wgt[W * H];
    tdc_render_out_t out = {0};
    out.mv = mv;
    out.mv_shadow = mvs;
    out.shadow_weight = wgt;
    tdc_render_stats_t st;
    assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &out, &st), 0);
    assert_true(st.ran[TDC_STAGE_MV_SHADOW]);
    int nz = 0;
    for (int i = 0; i < W * H; i++)
        if (wgt[i] > 0) {
            nz++;
            assert_true(mvs[2 * i] < 0);
            assert_int_equal(mv[2 * i], 0);
        }
    assert_true(nz > 50);
    tdc_render_close(r);
}

/* The same fence under a small rect (area) light: shadow MVs from the
 * blocked light sample (one random sample per pixel and frame, so only the
 * direction is checked: the shadow moves with the fence, +x). */
static void test_shadow_mv_area_light(void **state)
{
    (void)state;
    char text[2048];
    snprintf(text, sizeof text, "%s", scene_fence);
    char *l = strstr(text, "light lamp point");
    assert_non_null(l);
    snprintf(l, sizeof text - (size_t)(l - text),
             "light lamp rect pos 0 3 -3.5 u 0.3 0 0 v 0 0 0.3 intensity 20 20 20 samples 4\n");
    tdc_render_t *r = open_text(text, 1, 0);
    int shadowed = 0, left = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            tdc_render_probe_t a;
            tdc_render_probe(r, 5, x + 0.5, y + 0.5, &a);
            if (!a.hit || a.obj != 0 || !a.in_shadow) continue;
            shadowed++;
            assert_int_equal(a.blocker_obj, 1);
            if (a.shadow_mv[0] < -0.05) left++;
            assert_true(a.shadow_weight >= 0 && a.shadow_weight <= 1);
        }
    printf("area light: %d floor pixels with a blocked light sample, %d with shadow MVs against the fence motion\n",
           shadowed, left);
    assert_true(shadowed > 50);
    assert_true(left >= shadowed * 95 / 100);
    tdc_render_close(r);
}

static const char scene_disocc[] = "tdc-scene 1\n"
                                   "fps 8\n"
                                   "material ground diffuse 0.8 0.8 0.8 checker 0.3 0.2 0.2 0.2\n"
                                   "material box diffuse 0.2 0.3 0.9\n"
                                   "camera 0 pos 0 0 5 look 0 0 0 fov 40\n"
                                   "object wall rect size 20 20 material ground\n"
                                   "object box box size 1 1 0.2 material box pos -0.5 0 1\n"
                                   "key box 0 pos -0.5 0 1\n"
                                   "key box 1 pos 0.5 0 1\n";

static void test_dual_mv_disocclusion(void **state)
{
    (void)state;
    tdc_render_t *r = open_text(scene_disocc, 0, 1);
    const uint32_t f = 5; /* the box moves 1/8 unit per frame */
    int dis = 0, to_bg = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            tdc_render_probe_t a, b;
            tdc_render_probe(r, f, x + 0.5, y + 0.5, &a);
            if (!a.disoccluded) continue;
            dis++;
            assert_int_equal(a.obj, 0); /* the wall became visible */
            tdc_render_probe(r, f - 1, x + 0.5 + a.dual_mv[0], y + 0.5 + a.dual_mv[1], &b);
            if (b.hit && b.obj == 0) to_bg++;
        }
    printf("dual MVs: %d disoccluded pixels, %d sent to the background in the previous frame\n", dis, to_bg);
    assert_true(dis > 0);
    assert_int_equal(to_bg, dis);
    tdc_render_close(r);
}

static const char scene_static[] = "tdc-scene 1\n"
                                   "fps 8\n"
                                   "material m diffuse 0.5 0.5 0.5 checker 0.2 0.1 0.1 0.1\n"
                                   "camera 0 pos 0 0 5 look 0 0 0\n"
                                   "object wall rect size 20 20 material m\n"
                                   "light l point pos 0 0 4 intensity 10 10 10\n";

static void test_static_scene_skips_mv(void **state)
{
    (void)state;
    tdc_render_t *r = open_text(scene_static, 1, 1);
    tdc_render_features_t ft;
    tdc_render_get_features(r, &ft);
    assert_int_equal(ft.motion, 0);
    assert_int_equal(ft.mirrors, 0);
    assert_int_equal(ft.moving_blocker, 0);
    static int16_t mv[W * H * 2];
    memset(mv, 0x55, sizeof mv);
    tdc_render_out_t out = {0};
    out.mv = mv;
    tdc_render_stats_t st;
    assert_int_equal(tdc_render_frame(r, 7, TDC_RENDER_FULL, &out, &st), 0);
    assert_int_equal(st.frame_static, 1);
    for (int s = TDC_STAGE_REFLECT; s <= TDC_STAGE_MV_DUAL; s++) {
        assert_int_equal(st.ran[s], 0);
        assert_true(st.ms[s] == 0.0);
    }
    assert_true(st.rays[TDC_RAY_REFLECT] == 0 && st.rays[TDC_RAY_MV] == 0);
    for (int i = 0; i < W * H * 2; i++) assert_int_equal(mv[i], 0);
    tdc_render_close(r);
}

/* Full-frame Q4 output = rounded float MVs = probe MVs. */
static void test_frame_mv_matches_probe(void **state)
{
    (void)state;
    tdc_render_t *r = open_text(scene_object, 0, 0);
    static int16_t mv[W * H * 2];
    static float mvf[W * H * 2];
    tdc_render_out_t out = {0};
    out.mv = mv;
    out.mv_f = mvf;
    assert_int_equal(tdc_render_frame(r, 5, TDC_RENDER_FULL, &out, NULL), 0);
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
            tdc_render_probe_t a;
            tdc_render_probe(r, 5, x + 0.5, y + 0.5, &a);
            size_t i = (size_t)y * W + x;
            assert_true(fabs(mvf[2 * i] - a.mv[0]) < 1e-4 && fabs(mvf[2 * i + 1] - a.mv[1]) < 1e-4);
            assert_int_equal(mv[2 * i], (int)floor(mvf[2 * i] * 16 + 0.5));
            assert_int_equal(mv[2 * i + 1], (int)floor(mvf[2 * i + 1] * 16 + 0.5));
        }
    tdc_render_close(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mv_camera_pan),
        cmocka_unit_test(test_mv_object_motion),
        cmocka_unit_test(test_mv_mirror),
        cmocka_unit_test(test_mv_mirror_needs_reflected),
        cmocka_unit_test(test_shadow_mv_follows_shadow),
        cmocka_unit_test(test_shadow_mv_area_light),
        cmocka_unit_test(test_dual_mv_disocclusion),
        cmocka_unit_test(test_static_scene_skips_mv),
        cmocka_unit_test(test_frame_mv_matches_probe),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
