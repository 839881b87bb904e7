/*
 * test_render_mv.c - motion vectors of the renderer (issue 6):
 *   a surface point reprojected with its MV lands on the same surface point
 *   in the previous frame within 0.01 px, for a camera pan, object motion and
 *   a mirror reflection (TDRT §3.1.2); shadow MVs (Zeng §4.1) follow a
 *   moving shadow over a static receiver; dual MVs (Zeng §4.3) send
 *   disoccluded pixels to the background; static scenes skip MV work;
 *   stochastic glossy MVs (Zeng eq. 5) against a brute-force search of the
 *   previous frame for the pixel whose specular reflection sees the same
 *   point, and their Gaussian against the brute-force lobe footprint;
 *   layers recombine to the frame; dual-MV culling changes no vector; the
 *   dual pass's G-buffer lookup (Zeng eq. 6 from the previous frame's
 *   depth and object ids) against the traced previous-frame rays.
 * Tiny resolutions: each case traces a few thousand rays.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tdc_cmocka.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/tdc_render.h"
#include "render/tdc_render_trace.h"

#define W 64
#define H 48

/* dual_trace: the dual vectors traced as well (the check on the lookup) */
static tdc_render_t *open_cfg(const char *text, int shadow_mv, int dual_mv, int dual_trace)
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
    cfg.dual_trace = dual_trace;
    tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
    if (!r) fprintf(stderr, "%s\n", err);
    assert_non_null(r);
    return r;
}

static tdc_render_t *open_text(const char *text, int shadow_mv, int dual_mv)
{
    return open_cfg(text, shadow_mv, dual_mv, 0);
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

/* a fence moving +x between a point light and a floor (FENCE_FLOOR then
 * FENCE_LIGHT; test_shadow_falloff_lookup puts a step between them) */
#define FENCE_FLOOR                                                                                                    \
    "tdc-scene 1\n"                                                                                                    \
    "fps 8\n"                                                                                                          \
    "material ground diffuse 0.8 0.8 0.8\n"                                                                            \
    "material paint diffuse 0.7 0.2 0.1\n"                                                                             \
    "camera 0 pos 0 4 5 look 0 0 0.5 fov 45\n"                                                                         \
    "object floor rect size 12 12 material ground rot -90 0 0\n"
#define FENCE_LIGHT                                                                                                    \
    "object fence fence slats 5 width 0.15 gap 0.2 height 1 depth 0.05 material paint pos -0.8 0.4 -1\n"              \
    "key fence 0 pos -0.8 0.4 -1\n"                                                                                    \
    "key fence 1 pos 0.8 0.4 -1\n"                                                                                     \
    "light lamp point pos 0 3 -3.5 intensity 20 20 20\n"
static const char scene_fence[] = FENCE_FLOOR FENCE_LIGHT;

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

/* ---- glossy reflections (Zeng §4.2, eq. 5) ---- */

#define GLOSSY_ALPHA 0.06
/* scene_mirror with a glossy floor: the reflector of test_mv_mirror */
static char scene_glossy[1024];
static const char *glossy_text(void)
{
    const char *m = strstr(scene_mirror, "mirror 1\n");
    assert_non_null(m);
    snprintf(scene_glossy, sizeof scene_glossy, "%.*smirror 1 roughness %.2f%s", (int)(m - scene_mirror), scene_mirror,
             GLOSSY_ALPHA, m + strlen("mirror 1"));
    return scene_glossy;
}

/* World position at time t of a point q of object obj (the scene's own keys). */
static void world_at(const tdc_scene_t *sc, int obj, double t, const double q[3], double w[3])
{
    double m[12];
    tdc_scene_object_matrix(&sc->objects[obj], t, m);
    for (int i = 0; i < 3; i++) w[i] = m[4 * i] * q[0] + m[4 * i + 1] * q[1] + m[4 * i + 2] * q[2] + m[4 * i + 3];
}

/* Angle between the specular reflection (floor normal +y) of the view ray
 * camera -> floor point s and the direction from s to the point h. */
static double refl_angle(const double cam[3], const double s[3], const double h[3])
{
    double v[3] = {s[0] - cam[0], -(s[1] - cam[1]), s[2] - cam[2]}; /* mirrored by the y = 0 plane */
    double d[3] = {h[0] - s[0], h[1] - s[1], h[2] - s[2]};
    double c = (v[0] * d[0] + v[1] * d[1] + v[2] * d[2]) / sqrt((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) *
                                                               (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    return acos(c > 1 ? 1 : c < -1 ? -1 : c);
}

/* Brute force: the previous-frame image position whose specular reflection
 * sees the world point h (min angle over all pixel centres, then a
 * shrinking 3x3 search down to 1/512 px, each step a probe of the floor). */
static int specular_pixel(tdc_render_t *r, uint32_t fp, const double cam[3], const double (*fl)[3], const int *onfl,
                          const double h[3], double *bx, double *by)
{
    double best = 1e9;
    for (int i = 0; i < W * H; i++) {
        if (!onfl[i]) continue;
        double a = refl_angle(cam, fl[i], h);
        if (a < best) {
            best = a;
            *bx = i % W + 0.5;
            *by = i / W + 0.5;
        }
    }
    if (best > 0.5) return -1;
    for (double step = 0.5; step > 1.0 / 512; step *= 0.5) {
        double cx = *bx, cy = *by;
        for (int j = -1; j <= 1; j++)
            for (int i = -1; i <= 1; i++) {
                tdc_render_probe_t p;
                tdc_render_probe(r, fp, cx + i * step, cy + j * step, &p);
                if (!p.hit || p.obj != 0) continue;
                double a = refl_angle(cam, p.world, h);
                if (a < best) {
                    best = a;
                    *bx = cx + i * step;
                    *by = cy + j * step;
                }
            }
    }
    return 0;
}

static void test_glossy_mv_vs_brute_force(void **state)
{
    (void)state;
    tdc_render_t *r = open_text(glossy_text(), 0, 0);
    const tdc_scene_t *sc = tdc_render_scene(r);
    const uint32_t f = 5;
    const double tp = (f - 1) / sc->fps;
    tdc_camera_key_t ck;
    tdc_scene_camera_at(sc, tp, &ck);
    /* the previous frame's floor points at every pixel centre */
    static double fl[W * H][3];
    static int onfl[W * H];
    for (int i = 0; i < W * H; i++) {
        tdc_render_probe_t p;
        tdc_render_probe(r, f - 1, i % W + 0.5, i / W + 0.5, &p);
        onfl[i] = p.hit && p.obj == 0;
        memcpy(fl[i], p.world, sizeof fl[i]);
    }
    int n = 0, nsig = 0;
    double maxc = 0, se_g = 0, se_o = 0, se_c = 0, gg = 0, gm[2] = {0, 0}, tr_ratio_min = 1e9, tr_ratio_max = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            tdc_render_probe_t a;
            tdc_render_probe(r, f, x + 0.5, y + 0.5, &a);
            if (!a.hit || a.obj != 0 || !a.refl_mv_ok || a.refl_obj != 1) continue; /* the ball seen in the floor */
            double h[3], bx = 0, by = 0;
            world_at(sc, 1, tp, a.refl_q, h);
            if (specular_pixel(r, f - 1, ck.pos, (const double(*)[3])fl, onfl, h, &bx, &by) < 0) continue;
            double px = x + 0.5, py = y + 0.5;
            double ec = hypot(px + a.refl_mu[0] - bx, py + a.refl_mu[1] - by); /* centre of eq. 5 */
            if (ec > maxc) maxc = ec;
            double ex = px + a.refl_mv[0] - bx, ey = py + a.refl_mv[1] - by; /* the stochastic vector */
            se_g += ex * ex + ey * ey;
            se_c += ec * ec;
            /* ordinary reprojection: the floor point's own motion (camera pan) */
            double xs, ys;
            assert_int_equal(tdc_render_project(r, f - 1, 0, a.q, &xs, &ys), 0);
            double ox = xs - bx, oy = ys - by;
            se_o += ox * ox + oy * oy;
            /* the residual in the Gaussian's own axes: standard normal */
            double a11 = a.refl_axes[0], a21 = a.refl_axes[1], a12 = a.refl_axes[2], a22 = a.refl_axes[3];
            double det = a11 * a22 - a12 * a21;
            assert_true(fabs(det) > 1e-12);
            double rx = ex - (px + a.refl_mu[0] - bx), ry = ey - (py + a.refl_mu[1] - by);
            double g1 = (a22 * rx - a12 * ry) / det, g2 = (-a21 * rx + a11 * ry) / det;
            gg += g1 * g1 + g2 * g2;
            gm[0] += g1;
            gm[1] += g2;
            n++;
            /* every 16th: the Gaussian against the brute-force lobe footprint,
             * the angle-weighted covariance of previous positions on a fine
             * grid (weight exp(-theta^2 / (2 sigma^2)), sigma = sqrt(2) alpha) */
            if (n % 16 == 1) {
                double sg = sqrt(2.0) * GLOSSY_ALPHA, sw = 0, m1[2] = {0, 0}, m2[3] = {0, 0, 0};
                double ext = 4 * (fabs(a11) + fabs(a12) + fabs(a21) + fabs(a22)) + 0.5, st = ext / 40;
                for (double v = -ext; v <= ext; v += st)
                    for (double u = -ext; u <= ext; u += st) {
                        tdc_render_probe_t p;
                        tdc_render_probe(r, f - 1, bx + u, by + v, &p);
                        if (!p.hit || p.obj != 0) continue;
                        double th = refl_angle(ck.pos, p.world, h), w = exp(-th * th / (2 * sg * sg));
                        sw += w;
                        m1[0] += w * u;
                        m1[1] += w * v;
                        m2[0] += w * u * u;
                        m2[1] += w * u * v;
                        m2[2] += w * v * v;
                    }
                double cu = m1[0] / sw, cv = m1[1] / sw;
                double tr_bf = m2[0] / sw - cu * cu + m2[2] / sw - cv * cv;
                double tr = a11 * a11 + a21 * a21 + a12 * a12 + a22 * a22;
                double ratio = tr / tr_bf;
                if (ratio < tr_ratio_min) tr_ratio_min = ratio;
                if (ratio > tr_ratio_max) tr_ratio_max = ratio;
                nsig++;
            }
        }
    double rms_g = sqrt(se_g / n), rms_o = sqrt(se_o / n), rms_c = sqrt(se_c / n);
    printf("glossy MVs (alpha %.2f): %d reflected pixels; centre (eq. 5 mean) vs brute force: max %.3f rms %.3f px; "
           "stochastic vector rms %.3f px; ordinary floor vector rms %.3f px; residual in the Gaussian's axes: "
           "E[g^2] %.3f (2 = standard), mean (%.3f, %.3f); covariance trace / brute-force lobe footprint %.2f..%.2f "
           "over %d pixels\n",
           GLOSSY_ALPHA, n, maxc, rms_c, rms_g, rms_o, gg / n, gm[0] / n, gm[1] / n, tr_ratio_min, tr_ratio_max, nsig);
    assert_true(n > 100);
    assert_true(maxc < 0.05);                          /* planar reflector: the centre is exact */
    assert_true(gg / n > 1.6 && gg / n < 2.4);         /* the vector spreads by its own covariance */
    assert_true(fabs(gm[0] / n) < 0.25 && fabs(gm[1] / n) < 0.25);
    /* the covariance is the lobe's footprint (measured 0.64..0.98; the
     * paper's apex at the virtual image gave 0.98..3.75) */
    assert_true(tr_ratio_min > 0.5 && tr_ratio_max < 1.5);
    assert_true(rms_o > 2 * rms_g); /* ordinary reprojection misses by far more (measured 6.4 vs 2.5 px) */
    tdc_render_close(r);
}

/* GGX sampler (tdc_r_ggx_sample): the mean weight is the directional
 * albedo of the Smith-GGX lobe, the integral of D(m) G1(v) G1(l) / (4 cos_o)
 * over the hemisphere of l (by quadrature here); small roughness sends the
 * sample to the mirror direction. */
static double ggx_d(double cm, double a)
{
    double c2 = cm * cm, t = c2 * (a * a - 1) + 1;
    return a * a / (M_PI * t * t);
}

static double ggx_g1(double c, double a)
{
    double t2 = (1 - c * c) / (c * c);
    return 2 / (1 + sqrt(1 + a * a * t2));
}

static void test_ggx_sampler(void **state)
{
    (void)state;
    const double alphas[3] = {0.05, 0.3, 0.8}, views[3] = {0, 60, 80};
    const double N[3] = {0, 0, 1};
    double prev_mir[3] = {1, 1, 1};
    for (int ia = 0; ia < 3; ia++)
        for (int iv = 0; iv < 3; iv++) {
            double a = alphas[ia], th = views[iv] * M_PI / 180;
            double wo[3] = {sin(th), 0, cos(th)}, d[3] = {-wo[0], -wo[1], -wo[2]};
            /* quadrature over the hemisphere of l (cos-theta, phi grid) */
            double q = 0;
            const int nt = 2000, np = 400;
            for (int i = 0; i < nt; i++) {
                double cl = (i + 0.5) / nt, sl = sqrt(1 - cl * cl);
                for (int j = 0; j < np; j++) {
                    double ph = 2 * M_PI * (j + 0.5) / np;
                    double l[3] = {sl * cos(ph), sl * sin(ph), cl};
                    double h[3] = {l[0] + wo[0], l[1] + wo[1], l[2] + wo[2]};
                    double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                    double cm = h[2] / hl;
                    q += ggx_d(cm, a) * ggx_g1(wo[2], a) * ggx_g1(cl, a) / (4 * wo[2]) * (1.0 / nt) *
                         (2 * M_PI / np);
                }
            }
            double sum = 0, mir = 0;
            const int ns = 200000;
            for (int k = 0; k < ns; k++) {
                double u1 = (k + 0.5) / ns, u2 = fmod(k * 0.6180339887498949, 1.0), out[3];
                double w = tdc_r_ggx_sample(d, N, a, u1, u2, out);
                assert_true(w >= 0 && w <= 1);
                if (w > 0) {
                    assert_true(fabs(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] - 1) < 1e-9);
                    assert_true(out[2] > 0);
                    mir += out[0] * -wo[0] + out[1] * -wo[1] + out[2] * wo[2]; /* cos to the mirror direction */
                }
                sum += w;
            }
            double mean = sum / ns;
            printf("GGX alpha %.2f view %2.0f deg: mean weight %.4f, quadrature albedo %.4f, mean cos to the mirror "
                   "direction %.4f\n",
                   a, views[iv], mean, q, mir / ns);
            /* the sampled estimator's mean is the lobe's albedo */
            assert_true(fabs(mean - q) < 0.01 + 0.01 * q);
            /* near the mirror direction for a small alpha (GGX's long tail
             * keeps the mean cosine at 0.976 for alpha 0.05), farther for larger */
            if (a < 0.1) assert_true(mir / ns > 0.95);
            if (ia > 0) assert_true(mir / ns < prev_mir[iv]);
            prev_mir[iv] = mir / ns;
        }
}

static int16_t q4ref(double v)
{
    double f = floor(v * 16 + 0.5);
    return (int16_t)(f > 32767 ? 32767 : f < -32767 ? -32767 : f);
}

/* Layers (Zeng §4): vis * shade + refl is the frame, in-shadow pixels are
 * the splatting sources, the layer vectors are the probe's, and asking for
 * layers changes no pixel of the frame. */
static void check_layers(const char *text, int want_refl)
{
    tdc_render_t *r = open_text(text, 1, 1);
    const uint32_t f = 5;
    static float rgb[W * H * 3], rgb0[W * H * 3], sh[W * H * 3], vis[W * H], refl[W * H * 3];
    static int16_t ms[W * H * 2], mr[W * H * 2];
    static uint8_t src[W * H];
    tdc_render_out_t o0 = {0}, o = {0};
    o0.rgb = rgb0;
    assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &o0, NULL), 0);
    o.rgb = rgb;
    o.shade = sh;
    o.vis = vis;
    o.refl = refl;
    o.mv_surf = ms;
    o.mv_refl = mr;
    o.shadow_src = src;
    assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &o, NULL), 0);
    assert_memory_equal(rgb, rgb0, sizeof rgb);
    double maxe = 0;
    int shadowed = 0, reflective = 0, mvr_checked = 0;
    for (int i = 0; i < W * H; i++) {
        for (int c = 0; c < 3; c++) {
            double e = fabs(vis[i] * sh[3 * i + c] + refl[3 * i + c] - rgb[3 * i + c]) / (rgb[3 * i + c] + 1e-3);
            if (e > maxe) maxe = e;
        }
        assert_true(vis[i] >= 0 && vis[i] <= 1);
        tdc_render_probe_t p;
        tdc_render_probe(r, f, i % W + 0.5, i / W + 0.5, &p);
        assert_int_equal(src[i], p.in_shadow);
        if (p.in_shadow) { /* a blocked light: less than all of the light (unless nothing is shaded locally) */
            shadowed++;
            if (sh[3 * i] + sh[3 * i + 1] + sh[3 * i + 2] > 1e-6) assert_true(vis[i] < 1);
        }
        if (refl[3 * i] + refl[3 * i + 1] + refl[3 * i + 2] > 0) reflective++;
        if (p.refl_mv_ok) {
            assert_int_equal(mr[2 * i], q4ref(p.refl_mv[0]));
            assert_int_equal(mr[2 * i + 1], q4ref(p.refl_mv[1]));
            mvr_checked++;
        } else {
            assert_int_equal(mr[2 * i], ms[2 * i]);
            assert_int_equal(mr[2 * i + 1], ms[2 * i + 1]);
        }
    }
    printf("layers: max relative |vis shade + refl - rgb| %.2e; %d in-shadow (splat source) pixels, %d with a "
           "reflection layer, %d reflected vectors = probe\n",
           maxe, shadowed, reflective, mvr_checked);
    assert_true(maxe < 0.02); /* the lights' colour: 20 20 19 (fence), 50 50 48 (glossy) */
    if (want_refl) {
        assert_true(reflective > W * H / 10);
        assert_true(mvr_checked > W * H / 10);
    } else {
        assert_true(shadowed > 50);
    }
    tdc_render_close(r);
}

static void test_layers(void **state)
{
    (void)state;
    check_layers(scene_fence, 0);
    char text[2048];
    snprintf(text, sizeof text, "%slight sun point pos 2 6 4 intensity 50 50 48\n", glossy_text());
    check_layers(text, 1);
}

/* tdc_render_set_samples: a FOVEATED frame at given positions (here every
 * 7th pixel centre) gives, sample for sample, the FULL frame's layers and
 * shadow, dual and reflected vectors there. */
static void test_samples_at_positions(void **state)
{
    (void)state;
    char text[2048];
    snprintf(text, sizeof text, "%slight sun point pos 2 6 4 intensity 50 50 48\n", glossy_text());
    tdc_render_t *r = open_text(text, 1, 1);
    const uint32_t f = 5;
    static float rgb[W * H * 3], sh[W * H * 3], vis[W * H], refl[W * H * 3], sw[W * H];
    static int16_t mv[W * H * 2], mr[W * H * 2], ms[W * H * 2], md[W * H * 2];
    static float srgb[W * H * 3], ssh[W * H * 3], svis[W * H], srefl[W * H * 3], ssw[W * H];
    static int16_t smv[W * H * 2], smr[W * H * 2], sms[W * H * 2], smd[W * H * 2];
    static double xy[W * H * 2];
    tdc_render_out_t o = {.rgb = rgb, .mv = mv, .mv_shadow = ms, .shadow_weight = sw, .mv_dual = md,
                          .shade = sh, .vis = vis, .refl = refl, .mv_refl = mr};
    assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &o, NULL), 0);
    int n = 0;
    static int idx[W * H];
    for (int i = 0; i < W * H; i += 7) {
        xy[2 * n] = i % W + 0.5;
        xy[2 * n + 1] = i / W + 0.5;
        idx[n++] = i;
    }
    assert_int_equal(tdc_render_set_samples(r, xy, n), 0);
    tdc_render_out_t so = {.rgb = srgb, .mv = smv, .mv_shadow = sms, .shadow_weight = ssw, .mv_dual = smd,
                           .shade = ssh, .vis = svis, .refl = srefl, .mv_refl = smr};
    assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FOVEATED, &so, NULL), 0);
    for (int k = 0; k < n; k++) {
        int i = idx[k];
        assert_memory_equal(&srgb[3 * k], &rgb[3 * i], 12);
        assert_memory_equal(&ssh[3 * k], &sh[3 * i], 12);
        assert_memory_equal(&srefl[3 * k], &refl[3 * i], 12);
        assert_true(svis[k] == vis[i] && ssw[k] == sw[i]);
        assert_memory_equal(&smv[2 * k], &mv[2 * i], 4);
        assert_memory_equal(&smr[2 * k], &mr[2 * i], 4);
        assert_memory_equal(&sms[2 * k], &ms[2 * i], 4);
        assert_memory_equal(&smd[2 * k], &md[2 * i], 4);
    }
    double bad[2] = {NAN, 1};
    assert_int_equal(tdc_render_set_samples(r, bad, 1), -1);
    assert_int_equal(tdc_render_set_samples(r, xy, 0), -1);
    tdc_render_close(r);
}

/* Dual-MV culling: under a still camera the pass skips the previous-frame
 * ray outside the moving objects' previous screen rectangles; every dual
 * MV of the frame equals the probe's (which traces every ray). */
static void test_dual_mv_culling(void **state)
{
    (void)state;
    tdc_render_t *r = open_text(scene_disocc, 0, 1);
    static int16_t mvd[W * H * 2];
    tdc_render_out_t o = {0};
    o.mv_dual = mvd;
    tdc_render_stats_t st;
    const uint32_t f = 5;
    assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &o, &st), 0);
    int dis = 0;
    for (int i = 0; i < W * H; i++) {
        tdc_render_probe_t p;
        tdc_render_probe(r, f, i % W + 0.5, i / W + 0.5, &p);
        assert_int_equal(mvd[2 * i], q4ref(p.dual_mv[0]));
        assert_int_equal(mvd[2 * i + 1], q4ref(p.dual_mv[1]));
        dis += p.disoccluded;
    }
    printf("dual culling: %llu of %d samples without a ray, %llu previous-frame rays; %d disoccluded, all = probe\n",
           (unsigned long long)st.dual_culled, W * H, (unsigned long long)st.rays[TDC_RAY_MV], dis);
    assert_true(dis > 0);
    assert_true(st.dual_culled > (uint64_t)(W * H / 2));
    assert_true(st.rays[TDC_RAY_MV] + st.dual_culled == (uint64_t)(W * H));
    tdc_render_close(r);
    /* a moving camera: no culling */
    r = open_text(scene_pan, 0, 1);
    assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &o, &st), 0);
    assert_true(st.dual_culled == 0);
    tdc_render_close(r);
}

/* Dual MVs by the G-buffer lookup (frame f - 1 rendered FULL first) against
 * the traced pass (dual_trace) on the same frame: a still camera with a
 * moving box, a panning camera whose parallax uncovers the wall behind a
 * ball, and a turning box (its own faces occlude each other).  The lookup
 * traces no previous-frame ray.  It reads the sample nearest y, not the
 * exact point, so within half a pixel of a silhouette it may decide
 * otherwise than the ray: it must find at least 9 in 10 of the traced
 * disocclusions, and at most a tenth of them may end with a vector more
 * than 0.5 px from the traced one.  Under the moving box every pixel it
 * calls disoccluded is sent to the wall of frame f - 1 (under the pan,
 * parallax moves the ball against the wall, which eq. 6 assumes does not
 * happen). */
static void dual_lookup_vs_trace(const char *text, uint32_t f, int *dis_l, int *dis_t, int *both, int *bad,
                                 int *bg_l, int *bg_t)
{
    static int16_t mvl[W * H * 2], mvt[W * H * 2], mv[W * H * 2];
    tdc_render_t *r = open_text(text, 0, 1);
    tdc_render_out_t o = {.mv = mv, .mv_dual = mvl};
    tdc_render_stats_t st;
    assert_int_equal(tdc_render_frame(r, f - 1, TDC_RENDER_FULL, &o, &st), 0);
    assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &o, &st), 0);
    assert_int_equal(st.dual_lookup, 1);
    assert_true(st.rays[TDC_RAY_MV] == 0); /* a lookup, not a ray */
    tdc_render_close(r);
    r = open_cfg(text, 0, 1, 1);
    o.mv_dual = mvt;
    assert_int_equal(tdc_render_frame(r, f - 1, TDC_RENDER_FULL, &o, &st), 0);
    assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &o, &st), 0);
    assert_int_equal(st.dual_lookup, 0);
    *dis_l = *dis_t = *both = *bg_l = *bg_t = *bad = 0;
    for (int i = 0; i < W * H; i++) {
        int l = mvl[2 * i] != mv[2 * i] || mvl[2 * i + 1] != mv[2 * i + 1];
        int t = mvt[2 * i] != mv[2 * i] || mvt[2 * i + 1] != mv[2 * i + 1];
        *dis_l += l;
        *dis_t += t;
        *both += l && t;
        *bad += hypot((mvl[2 * i] - mvt[2 * i]) / 16.0, (mvl[2 * i + 1] - mvt[2 * i + 1]) / 16.0) > 0.5;
        for (int k = 0; k < 2; k++) { /* where the vectors land in f - 1: on the pixel's own object? */
            const int16_t *m = k ? mvt : mvl;
            if (!(k ? t : l)) continue;
            tdc_render_probe_t a, b;
            tdc_render_probe(r, f, i % W + 0.5, i / W + 0.5, &a);
            tdc_render_probe(r, f - 1, i % W + 0.5 + m[2 * i] / 16.0, i / W + 0.5 + m[2 * i + 1] / 16.0, &b);
            *(k ? bg_t : bg_l) += b.obj == a.obj;
        }
    }
    tdc_render_close(r);
}

/* a box turning about its vertical axis: the faces it turns into view were
 * hidden by its own front face (the same object), which only the depth
 * test of the lookup tells apart */
static const char scene_spin[] = "tdc-scene 1\n"
                                 "fps 8\n"
                                 "material ground diffuse 0.8 0.8 0.8 checker 0.3 0.2 0.2 0.2\n"
                                 "material box diffuse 0.2 0.3 0.9 checker 0.2 0.9 0.9 0.9\n"
                                 "camera 0 pos 0 0 5 look 0 0 0 fov 40\n"
                                 "object wall rect size 20 20 material ground\n"
                                 "object box box size 1.2 1.2 1.2 material box pos 0 0 1 rot 0 10 0\n"
                                 "key box 0 rot 0 10 0\n"
                                 "key box 1 rot 0 130 0\n";

/* The fence's shadow falls across a box on the floor: at the box's edges the
 * previous frame's point at x^V lies off the receiver plane and eq. 4's
 * falloff drops below 1.  The falloff read from the previous FULL frame's
 * G-buffer (the nearest sample's object and depth, as a GPU renderer reads
 * it) against the traced previous-frame ray (dual_trace): the same weights
 * within 0.1 at 90 % of the shadowed pixels (190 of 190), with under a tenth
 * of the MV rays (0 of 139). */
static const char scene_fence_step[] =
    FENCE_FLOOR "object step box size 0.9 0.3 1.2 material ground pos 0.2 0.15 0.3\n" FENCE_LIGHT;

static void test_shadow_falloff_lookup(void **state)
{
    (void)state;
    static float wl[W * H], wt[W * H];
    static int16_t mvl[W * H * 2], mvt[W * H * 2];
    uint64_t mv_rays[2] = {0, 0};
    for (int k = 0; k < 2; k++) { /* 0: G-buffer lookup, 1: traced */
        tdc_render_t *r = open_cfg(scene_fence_step, 1, 0, k);
        tdc_render_out_t out = {0};
        out.mv_shadow = k ? mvt : mvl;
        out.shadow_weight = k ? wt : wl;
        tdc_render_stats_t st;
        assert_int_equal(tdc_render_frame(r, 4, TDC_RENDER_FULL, &out, &st), 0); /* frame 4's G-buffer */
        assert_int_equal(tdc_render_frame(r, 5, TDC_RENDER_FULL, &out, &st), 0);
        assert_true(st.ran[TDC_STAGE_MV_SHADOW]);
        mv_rays[k] = st.rays[TDC_RAY_MV];
        tdc_render_close(r);
    }
    int shadowed = 0, same = 0, falloff = 0;
    for (int i = 0; i < W * H; i++) {
        if (mvl[2 * i] == 0 && mvt[2 * i] == 0 && wl[i] == 0 && wt[i] == 0) continue;
        assert_int_equal(mvl[2 * i], mvt[2 * i]); /* eq. 3's vector does not read the previous frame */
        assert_int_equal(mvl[2 * i + 1], mvt[2 * i + 1]);
        shadowed++;
        if (fabsf(wl[i] - wt[i]) <= 0.1f) same++;
        if (wt[i] < 0.9f) falloff++;
    }
    printf("shadow falloff: %d shadowed pixels, %d with a falloff below 0.9 (traced), %d within 0.1 of the traced "
           "weights; MV rays %llu lookup, %llu traced\n",
           shadowed, falloff, same, (unsigned long long)mv_rays[0], (unsigned long long)mv_rays[1]);
    assert_true(shadowed > 50);
    assert_true(falloff > 0);
    assert_true(same * 10 >= shadowed * 9);
    assert_true(mv_rays[1] > 0);
    assert_true(mv_rays[0] * 10 < mv_rays[1]);
}

static void test_dual_mv_lookup(void **state)
{
    (void)state;
    const char *const scenes[3] = {scene_disocc, scene_pan, scene_spin};
    const char *const names[3] = {"moving box", "camera pan", "turning box"};
    for (int k = 0; k < 3; k++) {
        int dl, dt, both, bad, bl, bt;
        dual_lookup_vs_trace(scenes[k], 5, &dl, &dt, &both, &bad, &bl, &bt);
        printf("dual lookup (%s): %d disoccluded by the lookup, %d by the rays, %d by both; %d pixels' vectors "
               "> 0.5 px from the rays'; sent to their own object in f - 1: %d lookup, %d rays\n",
               names[k], dl, dt, both, bad, bl, bt);
        assert_true(dt > 0);
        assert_true(both * 10 >= dt * 9);
        assert_true(bad * 10 <= dt);
        if (k == 0) assert_int_equal(bl, dl);
    }
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_mv_camera_pan),
    cmocka_unit_test(test_mv_object_motion),
    cmocka_unit_test(test_mv_mirror),
    cmocka_unit_test(test_mv_mirror_needs_reflected),
    cmocka_unit_test(test_shadow_mv_follows_shadow),
    cmocka_unit_test(test_shadow_mv_area_light),
    cmocka_unit_test(test_dual_mv_disocclusion),
    cmocka_unit_test(test_static_scene_skips_mv),
    cmocka_unit_test(test_frame_mv_matches_probe),
    cmocka_unit_test(test_glossy_mv_vs_brute_force),
    cmocka_unit_test(test_ggx_sampler),
    cmocka_unit_test(test_layers),
    cmocka_unit_test(test_dual_mv_culling),
    cmocka_unit_test(test_samples_at_positions),
    cmocka_unit_test(test_dual_mv_lookup),
    cmocka_unit_test(test_shadow_falloff_lookup),
)
