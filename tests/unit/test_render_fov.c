/*
 * test_render_fov.c - the renderer's FOVEATED mode (kernel log-polar
 * sampling, thesis §4.2) on built-in scenes, and the firmware remap of its
 * output:
 *   - ray counts are exact: primary rays = log-polar samples + disk pixels,
 *     with the counts the firmware geometry gives;
 *   - every disk sample is bit-identical to the FULL frame's pixel (same
 *     position, same random-number key), every log-polar sample to a probe
 *     ray through its eq. 2.3 position;
 *   - the gaze moves per frame (the sample set follows it);
 *   - remapped by tdc_fov_frame, the disk interior is exactly the FULL
 *     frame and the periphery stays close to it (mean error reported);
 *   - texture LOD of the log-polar samples (thesis §4.1.2, cfg.fov_lod):
 *     the footprint cone equals the cell of eq. 2.3 measured by finite
 *     differences of the sample positions, disk samples keep one pixel's
 *     cone, the thesis's eq. 4.3 bias runs 1 -> 8 with u, and the LOD changes
 *     only samples whose cone grew (the others stay bit-identical); the
 *     simulator's photograph / procedural path (ref_fov_lp_samples) gives
 *     every log-polar sample the same footprint as the renderer's cone
 *     (one function, ref_fov_lod_cone, with the same jittered arguments).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "tdc_fov.h"
#include "ref_fov.h"
#include "render/tdc_render.h"

#define W 160
#define H 96

static tdc_scene_t sc;

static tdc_render_t *open_builtin(const char *name)
{
    char err[256];
    if (tdc_scene_builtin(name, &sc, err, sizeof err) != TDC_SCENE_OK) fail_msg("%s", err);
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = W;
    cfg.height = H;
    cfg.threads = 2;
    tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
    if (!r) fail_msg("%s", err);
    return r;
}

static void run_scene(const char *name)
{
    tdc_render_t *r = open_builtin(name);
    tdc_render_set_fov_lod(r, TDC_FOV_LOD_OFF); /* samples == probes (one pixel's cone) */
    float *full = malloc(W * H * 3 * sizeof(float));
    int16_t *fmv = malloc(W * H * 2 * sizeof(int16_t));
    float *samp = malloc(W * H * 3 * sizeof(float));
    int16_t *smv = malloc(W * H * 2 * sizeof(int16_t));
    uint8_t *lp = malloc(W * H * 3), *disk = malloc(W * H * 3), *out = malloc(W * H * 3), *ref = malloc(W * H * 3);
    uint8_t *code = malloc(W * H * 3);
    for (uint32_t f = 3; f < 6; f++) {
        tdc_render_out_t o = {.rgb = full, .mv = fmv};
        tdc_render_stats_t st;
        assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FULL, &o, &st), 0);
        tdc_render_fov_t fv = {W * (0.3 + 0.15 * (f - 3)), H * (0.6 - 0.1 * (f - 3)), 4, 0.555, 0.12443, 0, 0,
                               TDC_FOV_JITTER_TEXEL};
        tdc_render_halton(f, &fv.jx, &fv.jy);
        int nlp, nd;
        assert_int_equal(tdc_render_set_foveation(r, &fv, &nlp, &nd), 0);
        tdc_fov_params_t p = {(int32_t)lround(fv.gaze_x * 256), (int32_t)lround(fv.gaze_y * 256), 1024, 4077,
                              (uint16_t)(W * 555 / 1000),       (uint16_t)(H * 555 / 1000), {0, 0}, 0, 0};
        tdc_fov_geom_t g;
        assert_int_equal(tdc_fov_geom(&g, W, H, &p), TDC_OK);
        assert_int_equal(nlp, (g.lp_w - g.u0) * g.lp_h);
        assert_int_equal(nd, (int)tdc_fov_disk_pixels(&g));
        int ow, oh;
        tdc_render_output_size(r, TDC_RENDER_FOVEATED, &ow, &oh);
        assert_int_equal(ow, nlp + nd);
        assert_int_equal(oh, 1);
        tdc_render_out_t so = {.rgb = samp, .mv = smv};
        assert_int_equal(tdc_render_frame(r, f, TDC_RENDER_FOVEATED, &so, &st), 0);
        assert_int_equal(st.rays[TDC_RAY_PRIMARY], (uint64_t)(nlp + nd));
        /* disk samples == FULL pixels, bit for bit */
        int k = nlp;
        for (int j = 0; j < H; j++) {
            int32_t x0;
            uint32_t n = tdc_fov_disk_span(&g, j, &x0);
            for (uint32_t i = 0; i < n; i++, k++) {
                assert_memory_equal(&samp[3 * k], &full[3 * ((size_t)j * W + x0 + i)], 3 * sizeof(float));
            }
        }
        /* a few log-polar samples == probes through their eq. 2.3 positions */
        const double ex = fmax(p.gaze_x_q8 / 256.0, W - p.gaze_x_q8 / 256.0);
        const double ey = fmax(p.gaze_y_q8 / 256.0, H - p.gaze_y_q8 / 256.0);
        const double L = log(sqrt(ex * ex + ey * ey));
        for (int t = 0; t < 40; t++) {
            const int j = (t * 7) % g.lp_h, i = g.u0 + (t * 13) % (g.lp_w - g.u0);
            const double rad = exp(L * pow(fmax(i + fv.jx, 0) / g.lp_w, 4.0)), th = 2 * M_PI * (j + fv.jy) / g.lp_h;
            const float x = (float)(p.gaze_x_q8 / 256.0 + rad * cos(th)),
                        y = (float)(p.gaze_y_q8 / 256.0 + rad * sin(th));
            if (x < 0 || y < 0 || x >= W || y >= H) {
                continue; /* off screen: the renderer keys its random numbers by the clamped pixel, a probe does not */
            }
            tdc_render_probe_t pr;
            tdc_render_probe(r, f, x, y, &pr);
            const float *sv = &samp[3 * ((size_t)j * (g.lp_w - g.u0) + (size_t)(i - g.u0))];
            for (int c = 0; c < 3; c++) {
                if (!(fabs(sv[c] - pr.rgb[c]) < 1e-5))
                    fail_msg("sample (%d, %d) at (%g, %g): %g vs probe %g", i, j, x, y, sv[c], pr.rgb[c]);
            }
        }
        /* remap: the link payload into the stage's buffers */
        tdc_render_linear_to_rgb888(samp, (size_t)(nlp + nd), code);
        memset(lp, 0, (size_t)g.lp_w * g.lp_h * 3);
        for (int j = 0; j < g.lp_h; j++)
            memcpy(lp + ((size_t)j * g.lp_w + g.u0) * 3, code + (size_t)j * (g.lp_w - g.u0) * 3,
                   (size_t)(g.lp_w - g.u0) * 3);
        k = nlp;
        for (int j = 0; j < H; j++) {
            int32_t x0;
            uint32_t n = tdc_fov_disk_span(&g, j, &x0);
            memcpy(disk + ((size_t)j * W + x0) * 3, code + (size_t)k * 3, n * 3);
            k += (int)n;
        }
        tdc_fov_config_t cfg = {W, H, 0};
        size_t mn = tdc_fov_get_size(&cfg);
        void *mem = malloc(mn);
        tdc_fov_t fs;
        assert_int_equal(tdc_fov_init(&fs, &cfg, mem, mn), TDC_OK);
        assert_int_equal(tdc_fov_frame(&fs, &p, lp, (size_t)g.lp_w * 3, NULL, 0, disk, W * 3, 0, out, W * 3), TDC_OK);
        free(mem);
        tdc_render_linear_to_rgb888(full, W * H, ref);
        double err_per = 0;
        long n_per = 0;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++) {
                const double dx = i + 0.5 - p.gaze_x_q8 / 256.0, dy = j + 0.5 - p.gaze_y_q8 / 256.0;
                const double rr = sqrt(dx * dx + dy * dy);
                const size_t q = ((size_t)j * W + i) * 3;
                if (rr < g.r_disk_q8 / 256.0 - 4.01) {
                    assert_memory_equal(out + q, ref + q, 3);
                } else if (rr > g.r_disk_q8 / 256.0) {
                    for (int c = 0; c < 3; c++) err_per += fabs((double)out[q + c] - ref[q + c]);
                    n_per += 3;
                }
            }
        printf("  %-9s frame %u: %d log-polar + %d disk = %d rays (%.1f %% of %d); periphery mean |error| %.1f codes\n",
               name, f, nlp, nd, nlp + nd, 100.0 * (nlp + nd) / (W * H), W * H, err_per / (double)n_per);
        assert_true(err_per / (double)n_per < 40); /* blurred, not garbage */
    }
    free(full), free(fmv), free(samp), free(smv), free(lp), free(disk), free(out), free(ref), free(code);
    tdc_render_close(r);
}

static void test_foveated_scenes(void **state)
{
    (void)state;
    run_scene("room");
    run_scene("discs");
    run_scene("mirror");
}

/* eq. 2.3's screen position of buffer coordinates (u, v) (columns, rows). */
static void lp_pos(double cx, double cy, double L, double alpha, int w, int h, double u, double v, double *x, double *y)
{
    const double rad = exp(L * pow(fmax(u, 0) / w, alpha)), th = 2 * M_PI * v / h;
    *x = cx + rad * cos(th);
    *y = cy + rad * sin(th);
}

static void test_fov_lod(void **state)
{
    (void)state;
    tdc_render_t *r = open_builtin("panorama");
    tdc_render_fov_t fv = {W * 0.4, H * 0.55, 4, 0.555, 0.12443, 0.25, -0.125, TDC_FOV_JITTER_TEXEL};
    const int modes[3] = {TDC_FOV_LOD_OFF, TDC_FOV_LOD_FOOTPRINT, TDC_FOV_LOD_THESIS};
    float *samp[3];
    int nlp = 0, nd = 0;
    double cmax[3] = {0, 0, 0};
    tdc_fov_params_t p = {(int32_t)lround(fv.gaze_x * 256), (int32_t)lround(fv.gaze_y * 256), 1024, 4077,
                          (uint16_t)(W * 555 / 1000),       (uint16_t)(H * 555 / 1000), {0, 0}, TDC_FOV_KERNEL_LOG_POLAR, 0};
    tdc_fov_geom_t g;
    assert_int_equal(tdc_fov_geom(&g, W, H, &p), TDC_OK);
    const double cx = p.gaze_x_q8 / 256.0, cy = p.gaze_y_q8 / 256.0;
    const double ex = fmax(cx, W - cx), ey = fmax(cy, H - cy), L = log(sqrt(ex * ex + ey * ey));
    /* the simulator's photograph / procedural path (ref_fov_lp_samples) on the same geometry */
    const ref_fov_params_t rp = {cx, cy, 4, p.disk_q15 / 32768.0, g.lp_w, g.lp_h, 0, 0, 0};
    ref_fov_geom_t rg;
    ref_fov_geom(&rg, W, H, &rp);
    const size_t nsim = (size_t)(g.lp_w - g.u0) * g.lp_h;
    double *sxy = malloc(nsim * 2 * sizeof(double)), *sside = malloc(nsim * sizeof(double));
    for (int m = 0; m < 3; m++) {
        tdc_render_set_fov_lod(r, modes[m]);
        assert_int_equal(tdc_render_set_foveation(r, &fv, &nlp, &nd), 0);
        /* one footprint function: the simulator's box side is the renderer's cone, sample by sample */
        assert_int_equal(ref_fov_lp_samples(&rg, g.u0, fv.jx, fv.jy, fv.jitter, modes[m], sxy, sside), (size_t)nlp);
        for (int k = 0; k < nlp; k++) {
            if (!(fabs(sside[k] - tdc_render_fov_cone(r, k)) <= 1e-6 * sside[k]))
                fail_msg("lod %d sample %d: simulator footprint %g, renderer cone %g", modes[m], k, sside[k],
                         tdc_render_fov_cone(r, k));
        }
        int k = 0;
        double prev_u_cone = 0;
        for (int j = 0; j < g.lp_h; j++)
            for (int i = g.u0; i < g.lp_w; i++, k++) {
                const double c = tdc_render_fov_cone(r, k), u = i + fv.jx, v = j + fv.jy;
                assert_true(c >= 1);
                cmax[m] = fmax(cmax[m], c);
                if (modes[m] == TDC_FOV_LOD_OFF) {
                    assert_true(c == 1);
                } else if (modes[m] == TDC_FOV_LOD_FOOTPRINT) {
                    /* the cell's longer side by central differences of the positions */
                    double x0, y0, x1, y1, x2, y2, x3, y3;
                    lp_pos(cx, cy, L, 4, g.lp_w, g.lp_h, u - 0.01, v, &x0, &y0);
                    lp_pos(cx, cy, L, 4, g.lp_w, g.lp_h, u + 0.01, v, &x1, &y1);
                    lp_pos(cx, cy, L, 4, g.lp_w, g.lp_h, u, v - 0.01, &x2, &y2);
                    lp_pos(cx, cy, L, 4, g.lp_w, g.lp_h, u, v + 0.01, &x3, &y3);
                    const double dr = hypot(x1 - x0, y1 - y0) / 0.02, dt = hypot(x3 - x2, y3 - y2) / 0.02;
                    const double want = fmax(1, fmax(dr, dt));
                    if (!(fabs(c - want) <= 1e-3 * want))
                        fail_msg("footprint cone of (%d, %d): %g, finite differences %g", i, j, c, want);
                } else if (j == 0) { /* thesis: 2^(3 S1((u/w)^alpha)^3), non-decreasing in u, in [1, 8] */
                    assert_true(c >= prev_u_cone && c <= 8);
                    prev_u_cone = c;
                }
            }
        for (; k < nlp + nd; k++) assert_true(tdc_render_fov_cone(r, k) == 1); /* disk: one pixel */
        assert_true(tdc_render_fov_cone(r, nlp + nd) == 0);                   /* out of range */
        int ow, oh;
        tdc_render_output_size(r, TDC_RENDER_FOVEATED, &ow, &oh);
        samp[m] = malloc((size_t)ow * 3 * sizeof(float));
        tdc_render_out_t so = {.rgb = samp[m]};
        tdc_render_stats_t st;
        assert_int_equal(tdc_render_frame(r, 4, TDC_RENDER_FOVEATED, &so, &st), 0);
    }
    assert_true(cmax[1] > 4 && cmax[2] > 7); /* the periphery's cells are large at alpha 4 */
    /* the LOD changes exactly the samples whose cone grew, and some of them (textured surfaces) */
    tdc_render_set_fov_lod(r, TDC_FOV_LOD_FOOTPRINT);
    assert_int_equal(tdc_render_set_foveation(r, &fv, &nlp, &nd), 0);
    int changed = 0, same_cone_changed = 0;
    for (int k = 0; k < nlp + nd; k++) {
        const int differs = memcmp(&samp[0][3 * k], &samp[1][3 * k], 3 * sizeof(float)) != 0;
        if (tdc_render_fov_cone(r, k) == 1)
            same_cone_changed += differs;
        else
            changed += differs;
    }
    printf("  fov LOD: footprint cone up to %.1f px (thesis %.1f); %d of %d log-polar samples changed, %d with one "
           "pixel's cone\n",
           cmax[1], cmax[2], changed, nlp, same_cone_changed);
    assert_int_equal(same_cone_changed, 0);
    assert_true(changed > 0);
    /* the same with the display-pixel jitter (ref_fov_lp_jitter's PIXEL): footprints still agree */
    fv.jitter = TDC_FOV_JITTER_PIXEL;
    assert_int_equal(tdc_render_set_foveation(r, &fv, &nlp, &nd), 0);
    assert_int_equal(ref_fov_lp_samples(&rg, g.u0, fv.jx, fv.jy, fv.jitter, TDC_FOV_LOD_FOOTPRINT, sxy, sside),
                     (size_t)nlp);
    for (int k = 0; k < nlp; k++) assert_true(fabs(sside[k] - tdc_render_fov_cone(r, k)) <= 1e-6 * sside[k]);
    for (int m = 0; m < 3; m++) free(samp[m]);
    free(sxy);
    free(sside);
    tdc_render_close(r);
}

static void test_bad_foveation(void **state)
{
    (void)state;
    tdc_render_t *r = open_builtin("discs");
    tdc_render_fov_t fv = {W / 2.0, H / 2.0, 4, 0.555, 0.12443, 0, 0, TDC_FOV_JITTER_TEXEL};
    assert_int_equal(tdc_render_frame(r, 0, TDC_RENDER_FOVEATED, NULL, NULL), -1); /* not set yet */
    fv.alpha = 9;
    assert_int_equal(tdc_render_set_foveation(r, &fv, NULL, NULL), -1);
    fv.alpha = 4;
    fv.disk = 1.5;
    assert_int_equal(tdc_render_set_foveation(r, &fv, NULL, NULL), -1);
    fv.disk = 0.2;
    fv.gaze_x = 3 * W; /* more than one screen outside */
    assert_int_equal(tdc_render_set_foveation(r, &fv, NULL, NULL), -1);
    tdc_render_close(r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_foveated_scenes), cmocka_unit_test(test_fov_lod),
                                       cmocka_unit_test(test_bad_foveation)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
