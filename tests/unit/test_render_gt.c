/*
 * test_render_gt.c - sampling of the renderer (issue 6): same seed -> same
 * bytes (any thread count); ground-truth error falls like 1/sqrt(N);
 * reduced frames are prefiltered (a pattern above the reduced Nyquist limit
 * comes out as its mean, not as aliases); subframes trace the pixel
 * tdc_ordering_pixel() names, jittered when static, at the centre when
 * dynamic, with 1/4 of the full frame's primary rays.
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
#include "tdc_ordering.h"

#define W 40
#define H 30

static tdc_scene_t sc;

static tdc_render_t *open_with(const char *text, int threads, uint32_t seed, int gt_samples, int indirect,
                               int reuse);

/* REDUCED resolve domain of the next open (0: linear light, the default) */
static double g_reduced_gamma;

static tdc_render_t *open_cfg(const char *text, int threads, uint32_t seed, int gt_samples)
{
    return open_with(text, threads, seed, gt_samples, 0, 0);
}

/* shadow and dual MVs on; indirect: the diffuse bounce, reuse: its cone reuse */
static tdc_render_t *open_with(const char *text, int threads, uint32_t seed, int gt_samples, int indirect,
                               int reuse)
{
    char err[256];
    tdc_scene_status_t st = tdc_scene_parse(text, "t", NULL, &sc, err, sizeof err);
    if (st != TDC_SCENE_OK) fail_msg("%s", err);
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.threads = threads;
    cfg.seed = seed;
    cfg.gt_samples = gt_samples;
    cfg.shadow_mv = cfg.dual_mv = 1;
    cfg.indirect = indirect;
    cfg.indirect_reuse = reuse;
    cfg.reduced_gamma[0] = cfg.reduced_gamma[1] = cfg.reduced_gamma[2] = g_reduced_gamma;
    tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
    if (!r) fail_msg("%s", err);
    return r;
}

/* Edges, texture, an area light (random light samples) and motion. */
static const char scene_mix[] = "tdc-scene 1\n"
                                "fps 8\n"
                                "material floor diffuse 0.7 0.7 0.7 checker 0.37 0.2 0.2 0.2\n"
                                "material ball diffuse 0.9 0.3 0.1\n"
                                "material glass diffuse 0 0 0 mirror 0.8\n"
                                "camera 0 pos 0 2 6 look 0 0.5 0 fov 45\n"
                                "camera 1 pos 0.4 2 6 look 0 0.5 0\n"
                                "object floor rect size 20 20 material floor rot -90 0 0\n"
                                "object glass rect size 2 1.5 material glass pos 0 0.75 -2\n"
                                "object ball sphere radius 0.7 material ball pos -1 0.8 0\n"
                                "key ball 0 pos -1 0.8 0\n"
                                "key ball 1 pos 1 0.8 0\n"
                                "light l point pos 2 6 4 intensity 50 50 50\n"
                                "light a rect pos -2 3 2 u 1 0 0 v 0 0 1 intensity 5 5 5 samples 3\n";

static void render(tdc_render_t *r, uint32_t f, tdc_render_mode_t m, float *rgb, int16_t *mv, int16_t *mvs,
                   int16_t *mvd)
{
    tdc_render_out_t out = {0};
    out.rgb = rgb;
    out.mv = mv;
    out.mv_shadow = mvs;
    out.mv_dual = mvd;
    assert_int_equal(tdc_render_frame(r, f, m, &out, NULL), 0);
}

static void test_same_seed_same_bytes(void **state)
{
    (void)state;
    static float a[W * H * 3], b[W * H * 3];
    static int16_t ma[W * H * 2], mb[W * H * 2], sa[W * H * 2], sb[W * H * 2], da[W * H * 2], db[W * H * 2];
    const tdc_render_mode_t modes[] = {TDC_RENDER_FULL, TDC_RENDER_SUBFRAME, TDC_RENDER_REDUCED,
                                       TDC_RENDER_GROUND_TRUTH};
    for (size_t i = 0; i < 4; i++) {
        memset(a, 0, sizeof a);
        memset(b, 0, sizeof b);
        memset(ma, 0, sizeof ma);
        memset(mb, 0, sizeof mb);
        tdc_render_t *r1 = open_cfg(scene_mix, 1, 7, 9);
        tdc_render_t *r2 = open_cfg(scene_mix, 2, 7, 9);
        for (uint32_t f = 2; f < 5; f++) { /* subframes: several frames so history and patterns evolve */
            render(r1, f, modes[i], a, ma, sa, da);
            render(r2, f, modes[i], b, mb, sb, db);
            assert_memory_equal(a, b, sizeof a);
            assert_memory_equal(ma, mb, sizeof ma);
            assert_memory_equal(sa, sb, sizeof sa);
            assert_memory_equal(da, db, sizeof da);
        }
        tdc_render_close(r1);
        tdc_render_close(r2);
    }
    /* a different seed changes the random parts (area light, GT jitter) */
    tdc_render_t *r1 = open_cfg(scene_mix, 2, 7, 9), *r2 = open_cfg(scene_mix, 2, 8, 9);
    render(r1, 3, TDC_RENDER_GROUND_TRUTH, a, NULL, NULL, NULL);
    render(r2, 3, TDC_RENDER_GROUND_TRUTH, b, NULL, NULL, NULL);
    assert_true(memcmp(a, b, sizeof a) != 0);
    tdc_render_close(r1);
    tdc_render_close(r2);
}

/* Glossy reflections and layers (issue 16): one GGX sample per pixel and
 * the stochastic glossy MVs are keyed by the seed, so 1 and 2 threads give
 * the same bytes of every layer, and another seed other bytes. */
static void render_layers(tdc_render_t *r, uint32_t f, tdc_render_mode_t m, float *rgb, float *sh, float *vis,
                          float *refl, int16_t *mr, int16_t *ms, uint8_t *src)
{
    tdc_render_out_t out = {0};
    out.rgb = rgb;
    out.shade = sh;
    out.vis = vis;
    out.refl = refl;
    out.mv_refl = mr;
    out.mv_surf = ms;
    out.shadow_src = src;
    assert_int_equal(tdc_render_frame(r, f, m, &out, NULL), 0);
}

static void test_glossy_layers_deterministic(void **state)
{
    (void)state;
    char text[2048];
    const char *g = strstr(scene_mix, "mirror 0.8\n");
    assert_non_null(g);
    snprintf(text, sizeof text, "%.*smirror 0.8 roughness 0.2%s", (int)(g - scene_mix), scene_mix,
             g + strlen("mirror 0.8"));
    static float a[6][W * H * 3], b[6][W * H * 3];
    static int16_t am[2][W * H * 2], bm[2][W * H * 2];
    static uint8_t as[W * H], bs[W * H];
    const tdc_render_mode_t modes[] = {TDC_RENDER_FULL, TDC_RENDER_SUBFRAME};
    for (int i = 0; i < 2; i++) {
        tdc_render_t *r1 = open_cfg(text, 1, 7, 9), *r2 = open_cfg(text, 2, 7, 9);
        for (uint32_t f = 2; f < 5; f++) {
            render_layers(r1, f, modes[i], a[0], a[1], a[2], a[3], am[0], am[1], as);
            render_layers(r2, f, modes[i], b[0], b[1], b[2], b[3], bm[0], bm[1], bs);
            for (int k = 0; k < 4; k++) assert_memory_equal(a[k], b[k], sizeof a[k]);
            for (int k = 0; k < 2; k++) assert_memory_equal(am[k], bm[k], sizeof am[k]);
            assert_memory_equal(as, bs, sizeof as);
        }
        tdc_render_close(r1);
        tdc_render_close(r2);
    }
    tdc_render_t *r1 = open_cfg(text, 2, 7, 9), *r2 = open_cfg(text, 2, 8, 9);
    render_layers(r1, 3, TDC_RENDER_FULL, a[0], a[1], a[2], a[3], am[0], am[1], as);
    render_layers(r2, 3, TDC_RENDER_FULL, b[0], b[1], b[2], b[3], bm[0], bm[1], bs);
    assert_true(memcmp(a[3], b[3], sizeof a[3]) != 0);   /* the glossy layer's GGX samples */
    assert_true(memcmp(am[0], bm[0], sizeof am[0]) != 0); /* the stochastic glossy MVs */
    tdc_render_close(r1);
    tdc_render_close(r2);
}

/* Hard edges only (no random light samples): discs and a checker, unlit. */
static const char scene_edges[] = "tdc-scene 1\n"
                                  "background 0 0 0\n"
                                  "material w unlit diffuse 1 1 1\n"
                                  "material c unlit diffuse 0.1 0.1 0.1 checker 0.23 0.9 0.6 0.3\n"
                                  "camera 0 pos 0 0 10 look 0 0 0 fov 30\n"
                                  "object back rect size 3 2 material c pos 0.7 0.4 -1 rot 0 0 17\n"
                                  "object d1 disc radius 0.9 segments 64 material w pos -1 -0.3 0\n"
                                  "object d2 sphere radius 0.5 material w pos 1.3 -0.6 0.5\n";

static double rms(const float *a, const float *b, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++) s += (a[i] - (double)b[i]) * (a[i] - (double)b[i]);
    return sqrt(s / n);
}

static void test_ground_truth_convergence(void **state)
{
    (void)state;
    static float ref[W * H * 3], img[W * H * 3];
    tdc_render_t *r = open_cfg(scene_edges, 2, 1, 4096);
    render(r, 0, TDC_RENDER_GROUND_TRUTH, ref, NULL, NULL, NULL);
    tdc_render_close(r);
    const int Ns[] = {1, 4, 16, 64, 256};
    double e[5];
    for (int i = 0; i < 5; i++) {
        /* average the error over 3 seeds to steady the estimate */
        double acc = 0;
        for (uint32_t seed = 11; seed < 14; seed++) {
            r = open_cfg(scene_edges, 2, seed, Ns[i]);
            render(r, 0, TDC_RENDER_GROUND_TRUTH, img, NULL, NULL, NULL);
            acc += rms(img, ref, W * H * 3);
            tdc_render_close(r);
        }
        e[i] = acc / 3;
        printf("N = %3d: rms error %.5f%s", Ns[i], e[i], i ? "" : "\n");
        if (i) printf("  (x%.3f per 4x N; 1/sqrt(N) gives x0.5)\n", e[i] / e[i - 1]);
    }
    double slope = log(e[4] / e[0]) / log(256.0);
    printf("log-log slope %.3f (1/sqrt(N): -0.5; stratification does better at edges)\n", slope);
    /* at least as fast as 1/sqrt(N), and monotone */
    assert_true(slope <= -0.45);
    for (int i = 1; i < 5; i++) assert_true(e[i] < e[i - 1] * 0.62);
    /* non-square N uses Latin hypercube strata: also converges */
    r = open_cfg(scene_edges, 2, 5, 8);
    render(r, 0, TDC_RENDER_GROUND_TRUTH, img, NULL, NULL, NULL);
    double e8 = rms(img, ref, W * H * 3);
    tdc_render_close(r);
    assert_true(e8 < e[1] && e8 > e[3]);
}

/* Vertical stripes of period 2.5 full-res px: resolved at full resolution,
 * above the Nyquist limit of r = 1/2 (4 px).  The prefiltered reduced frame
 * must come out near the mean instead of a beat pattern. */
static const char scene_stripes[] = "tdc-scene 1\n"
                                    "material s unlit diffuse 1 1 1 stripes 0.04466 0 0 0\n"
                                    "camera 0 pos 0 0 1 look 0 0 0 fov 30\n"
                                    "object wall rect size 4 4 material s\n";

static void test_reduced_prefiltered(void **state)
{
    (void)state;
    static float full[W * H * 3], red[W * H * 3];
    tdc_render_t *r = open_cfg(scene_stripes, 2, 1, 1);
    int rw, rh;
    tdc_render_output_size(r, TDC_RENDER_REDUCED, &rw, &rh);
    assert_int_equal(rw, W / 2);
    assert_int_equal(rh, H / 2);
    render(r, 0, TDC_RENDER_FULL, full, NULL, NULL, NULL);
    render(r, 0, TDC_RENDER_REDUCED, red, NULL, NULL, NULL);
    double fmin = 1, fmax = 0, fmean = 0, rmin = 1, rmax = 0, rmean = 0;
    for (int i = 0; i < W * H; i++) {
        fmin = fmin < full[3 * i] ? fmin : full[3 * i];
        fmax = fmax > full[3 * i] ? fmax : full[3 * i];
        fmean += full[3 * i] / (W * H);
    }
    /* interior: the resolve clamps at the frame edges */
    int n = 0;
    for (int y = 3; y < rh - 3; y++)
        for (int x = 3; x < rw - 3; x++) {
            float v = red[3 * (y * rw + x)];
            rmin = rmin < v ? rmin : v;
            rmax = rmax > v ? rmax : v;
            rmean += v;
            n++;
        }
    rmean /= n;
    printf("stripes (2.5 px period): full frame range [%.2f, %.2f] mean %.3f; reduced interior range [%.3f, %.3f] "
           "mean %.3f\n",
           fmin, fmax, fmean, rmin, rmax, rmean);
    assert_true(fmax - fmin > 0.9);  /* the content has full contrast at full resolution */
    assert_true(rmax - rmin < 0.05); /* prefiltered: no beat pattern at r = 1/2 */
    assert_true(fabs(rmean - fmean) < 0.03);
    tdc_render_close(r);
}

/* reduced_gamma: the resolve filters gamma-coded values (what the link carries and
 * the firmware's D filters), so the prefiltered stripes come out at the code-domain
 * mean decoded, (mean v)^gamma with v = I^(1/gamma) - not at the linear mean. */
static void test_reduced_coded_resolve(void **state)
{
    (void)state;
    static float full[W * H * 3], red[W * H * 3];
    g_reduced_gamma = 2.2;
    tdc_render_t *r = open_cfg(scene_stripes, 2, 1, 1);
    g_reduced_gamma = 0;
    int rw, rh;
    tdc_render_output_size(r, TDC_RENDER_REDUCED, &rw, &rh);
    render(r, 0, TDC_RENDER_FULL, full, NULL, NULL, NULL);
    render(r, 0, TDC_RENDER_REDUCED, red, NULL, NULL, NULL);
    double lin = 0, code = 0, rmean = 0;
    for (int i = 0; i < W * H; i++) {
        double v = full[3 * i] < 0 ? 0 : full[3 * i] > 1 ? 1 : full[3 * i];
        lin += v / (W * H);
        code += pow(v, 1 / 2.2) / (W * H);
    }
    int n = 0;
    for (int y = 3; y < rh - 3; y++)
        for (int x = 3; x < rw - 3; x++, n++) rmean += red[3 * (y * rw + x)];
    rmean /= n;
    double want = pow(code, 2.2);
    printf("stripes, coded resolve (gamma 2.2): reduced mean %.3f, code-domain mean decoded %.3f, linear mean %.3f\n",
           rmean, want, lin);
    assert_true(fabs(rmean - want) < 0.03);
    assert_true(fabs(rmean - lin) > 0.1); /* the domain matters on this content */
    tdc_render_close(r);
}

static void test_subframe_positions(void **state)
{
    (void)state;
    static float sub[W * H * 3], full[W * H * 3];
    static int16_t mv[W * H * 2];
    const int tx = (W + 1) / 2, ty = (H + 1) / 2;
    tdc_render_t *r = open_cfg(scene_mix, 2, 3, 1);
    /* frames 0..7 include static (frame 0: no previous motion) and dynamic pixels */
    for (uint32_t f = 0; f < 8; f++) {
        uint8_t bits[TDC_PATTERN_BYTES(W, H)];
        static int16_t hist[W * H * 2];
        memcpy(hist, tdc_render_mv_history(r), sizeof hist);
        if ((f & 3) == 0)
            tdc_ordering_update(hist, W, H, (memcpy(bits, tdc_render_pattern_bits(r), sizeof bits), bits), f);
        else
            memcpy(bits, tdc_render_pattern_bits(r), sizeof bits);
        tdc_render_stats_t st, stf;
        tdc_render_out_t out = {0};
        out.rgb = sub;
        out.mv = mv;
        assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_SUBFRAME, &out, &st), 0);
        assert_memory_equal(bits, tdc_render_pattern_bits(r), sizeof bits);
        int32_t jx, jy;
        tdc_jitter_offset_q4(f, &jx, &jy);
        int checked = 0;
        for (int t = 0; t < tx * ty; t += 7) {
            unsigned p = tdc_ordering_pixel(tdc_ordering_get(bits, (uint32_t)t), f & 3u);
            int px = 2 * (t % tx) + (int)(p & 1), py = 2 * (t / tx) + (int)(p >> 1);
            if (px >= W || py >= H) continue;
            int dyn = 0;
            for (int y = py - 1; y <= py + 1; y++)
                for (int x = px - 1; x <= px + 1; x++)
                    if (x >= 0 && y >= 0 && x < W && y < H && (hist[2 * (y * W + x)] || hist[2 * (y * W + x) + 1]))
                        dyn = 1;
            float sx = px + 0.5f + (dyn ? 0 : jx / 16.0f), sy = py + 0.5f + (dyn ? 0 : jy / 16.0f);
            tdc_render_probe_t pr;
            tdc_render_probe(r, f, sx, sy, &pr);
            for (int c = 0; c < 3; c++) assert_true(fabs(pr.rgb[c] - sub[3 * t + c]) < 1e-6);
            checked++;
        }
        assert_true(checked > 10);
        /* cost: a quarter of the full frame's primary rays */
        assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &(tdc_render_out_t){.rgb = full}, &stf), 0);
        assert_true(st.rays[TDC_RAY_PRIMARY] * 4 == stf.rays[TDC_RAY_PRIMARY]);
        assert_int_equal(st.ran[TDC_STAGE_ORDERING], (f & 3) == 0);
        /* the full frame rewrote the MV history; restore the subframe's view
         * by rendering subframes only from here: re-open for the next frame */
        tdc_render_close(r);
        r = open_cfg(scene_mix, 2, 3, 1);
        for (uint32_t g = 0; g <= f; g++) assert_int_equal(tdc_render_frame(r, g, TDC_RENDER_SUBFRAME, NULL, NULL), 0);
    }
    tdc_render_close(r);
}

/* Option indirect (Zeng §4.3): one diffuse bounce per pixel, 1 sample, so
 * one frame's indirect layer is noisy; with indirect_reuse the 6-cone
 * history of a still scene converges toward the mean of many seeds (the
 * reference), and the result does not depend on the thread count. */
static const char scene_bounce[] = "tdc-scene 1\n"
                                   "fps 8\n"
                                   "ambient 0 0 0\n"
                                   "material floor diffuse 0.8 0.8 0.8\n"
                                   "material red diffuse 0.9 0.1 0.1\n"
                                   "camera 0 pos 0 1.5 4 look 0 0.3 0 fov 50\n"
                                   "object floor rect size 10 10 material floor rot -90 0 0\n"
                                   "object wall rect size 3 2 material red pos -0.5 1 -1 rot 0 30 0\n"
                                   "light l point pos 1.5 2.5 1 intensity 8 8 8\n";

static tdc_render_t *open_bounce(int threads, uint32_t seed, int reuse)
{
    return open_with(scene_bounce, threads, seed, 9, 1, reuse);
}

static void test_indirect_cone_reuse(void **state)
{
    (void)state;
    static float ref[W * H * 3], ind[W * H * 3], ind2[W * H * 3], one[W * H * 3], rgb[W * H * 3];
    static double acc[W * H * 3];
    const int nref = 256;
    memset(acc, 0, sizeof acc);
    for (int k = 0; k < nref; k++) {
        tdc_render_t *r = open_bounce(2, 100 + (uint32_t)k, 0);
        tdc_render_out_t o = {0};
        o.rgb = rgb;
        o.indirect = ind;
        assert_int_equal(tdc_render_frame(r, 3, TDC_RENDER_FULL, &o, NULL), 0);
        for (int i = 0; i < W * H * 3; i++) acc[i] += ind[i];
        if (k == 0) memcpy(one, ind, sizeof one);
        tdc_render_close(r);
    }
    double lum = 0;
    for (int i = 0; i < W * H * 3; i++) {
        ref[i] = (float)(acc[i] / nref);
        lum += ref[i];
    }
    assert_true(lum / (W * H * 3) > 0.01); /* there is indirect light to speak of */
    tdc_render_t *r1 = open_bounce(1, 7, 1), *r2 = open_bounce(2, 7, 1);
    double e_first = 0, e_last = 0;
    for (uint32_t f = 1; f <= 24; f++) {
        tdc_render_out_t o = {0};
        o.rgb = rgb;
        o.indirect = ind;
        assert_int_equal(tdc_render_frame(r1, f, TDC_RENDER_FULL, &o, NULL), 0);
        o.indirect = ind2;
        assert_int_equal(tdc_render_frame(r2, f, TDC_RENDER_FULL, &o, NULL), 0);
        assert_memory_equal(ind, ind2, sizeof ind);
        if (f == 1) e_first = rms(ind, ref, W * H * 3);
        if (f == 24) e_last = rms(ind, ref, W * H * 3);
    }
    double e_one = rms(one, ref, W * H * 3);
    printf("indirect (1 sample per pixel): rms error vs the mean of %d seeds %.4f for one frame (first reused frame "
           "%.4f), %.4f after 24 frames of 6-cone reuse\n",
           nref, e_one, e_first, e_last);
    assert_true(e_last < 0.5 * e_one);
    tdc_render_close(r1);
    tdc_render_close(r2);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_same_seed_same_bytes),
    cmocka_unit_test(test_glossy_layers_deterministic),
    cmocka_unit_test(test_ground_truth_convergence),
    cmocka_unit_test(test_reduced_prefiltered),
    cmocka_unit_test(test_reduced_coded_resolve),
    cmocka_unit_test(test_subframe_positions),
    cmocka_unit_test(test_indirect_cone_reuse),
)
