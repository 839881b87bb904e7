/*
 * test_sim_fov.c - the simulator's foveated modes (issue 14 item 5): fov and
 * fov-taa run end to end (renderer -> FOVEATED packets through the firmware
 * decoder -> the firmware stage -> panel -> eye -> metrics) on a procedural
 * scene, mono and stereo; rays and link bytes are exactly the geometry's;
 * the foveal region is perceived better than the periphery, and a tracker
 * latency moves the fovea off the gaze (foveal FLIP rises); the gaze
 * schedules and the tracker's latency and noise are what they claim; a
 * configuration the stage refuses is refused, not run.  fovlr and
 * fovlr-taa (log-rectilinear): rays are the full frame's, link bytes the
 * whole buffer's exactly, and the area-averaged periphery beats the
 * point-sampled kernel log-polar one in FLIP and flicker.  The footprint
 * prefilter (cfg.fov_lod) costs no rays or bytes, leaves the disk and full
 * rate alone and lowers the periphery's flicker.  fov-trm (foveated TRM):
 * exact rays and link bytes of both grids, refusals.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "tdc_cmocka.h"

#include "simulator/tdc_sim.h"
#include "simulator/tdc_sim_gaze.h"
#include "tdc_fov.h"
#include "ref_fov.h"
#include "ref_fov_lr.h"
#include "tdc_fov_link.h"
#include "tdc_fov_lr.h"
#include "tdc_geom.h"

#define W 96
#define H 72

static void config(tdc_sim_config_t *cfg, int frames)
{
    tdc_sim_default_config(cfg);
    cfg->scene.kind = TDC_SCENE_PAN;
    cfg->width = cfg->scene.width = W;
    cfg->height = cfg->scene.height = H;
    cfg->refresh_hz = 90;
    cfg->duration_s = (double)frames / 90;
    cfg->progress = 0;
    cfg->flip_ppd = 20.0;
    cfg->scene.gt_ss = 2;
    cfg->eyes = 1;
}

static int run(tdc_sim_config_t *cfg, const char *const *names, int n, tdc_sim_result_t *res)
{
    const tdc_mode_desc_t *modes[8];
    for (int i = 0; i < n; i++) {
        modes[i] = tdc_sim_mode_find(names[i]);
        assert_non_null(modes[i]);
    }
    tdc_source_t *src = tdc_scene_create(&cfg->scene, NULL);
    assert_non_null(src);
    tdc_source_t *right = NULL;
    if (cfg->eyes == 2) {
        tdc_scene_params_t sp = cfg->scene;
        sp.shift_x = 2.0;
        right = cfg->right = tdc_scene_create(&sp, NULL);
    }
    int rc = tdc_sim_run(cfg, src, modes, n, res, NULL);
    src->destroy(src);
    if (right) {
        right->destroy(right);
    }
    return rc;
}

static void print(const tdc_sim_result_t *r, int n)
{
    for (int i = 0; i < n; i++) {
        printf("  %-8s avail %d FLIP %.4f fovea %.4f periph %.4f ecc %.4f wmed %.4f flicker %.2f/%.2f rays %llu "
               "bytes %llu %s\n",
               r[i].desc->name, r[i].available, r[i].flip, r[i].flip_fovea, r[i].flip_periph, r[i].flip_ecc,
               r[i].flip_wmedian, r[i].flicker, r[i].flicker_periph, (unsigned long long)r[i].rays,
               (unsigned long long)r[i].link_bytes, r[i].note);
    }
}

/* Fixed gaze at the centre: every frame has the same geometry, so rays and
 * bytes are known exactly. */
static void test_modes_exact_costs(void **state)
{
    (void)state;
    for (int eyes = 1; eyes <= 2; eyes++) {
        tdc_sim_config_t cfg;
        config(&cfg, 12);
        cfg.eyes = eyes;
        cfg.gaze = TDC_GAZE_FIXED;
        static const char *const m[] = {"full", "fov", "fov-taa"};
        tdc_sim_result_t r[3];
        assert_int_equal(run(&cfg, m, 3, r), 0);
        print(r, 3);
        const tdc_fov_params_t p = {W * 128, H * 128, 1024, 4077, tdc_fov_lp_size(18187, W), tdc_fov_lp_size(18187, H), {0, 0}, 0, 0};
        tdc_fov_geom_t g;
        assert_int_equal(tdc_fov_geom(&g, W, H, &p), TDC_OK);
        const uint64_t nlp = (uint64_t)(g.lp_w - g.u0) * g.lp_h, nd = tdc_fov_disk_pixels(&g);
        for (int i = 0; i < 3; i++) {
            assert_true(r[i].available);
            assert_int_equal(r[i].link_errors, 0);
            assert_false(r[i].nonfinite);
            assert_true(r[i].evals > 0);
            assert_true(r[i].flip > 0 && r[i].flip < 1);
            assert_int_equal(r[i].foveated, i > 0);
        }
        const uint64_t frames = r[1].frames * (uint64_t)eyes; /* pictures */
        assert_int_equal(r[1].rays, frames * (nlp + nd) * 4u);  /* spp 4 below 200 Hz, like full */
        assert_int_equal(r[2].rays, r[1].rays);
        assert_int_equal(r[0].rays, frames * W * H * 4u);
        const uint64_t stream = 32u + 16u;
        assert_int_equal(r[1].link_bytes, stream + frames * (32u + TDC_FOV_HDR_BYTES + tdc_fov_payload_bytes(&g, 0)));
        assert_int_equal(r[2].link_bytes, stream + frames * (32u + TDC_FOV_HDR_BYTES + tdc_fov_payload_bytes(&g, 1)));
        /* the disk is traced at full rate, the periphery is not */
        for (int i = 1; i < 3; i++) {
            assert_true(r[i].flip_fovea < r[i].flip_periph);
            assert_true(r[i].flip_periph > r[0].flip_periph);
        }
    }
}

/* The log-rectilinear modes beside the kernel log-polar ones. */
static void test_lr_modes(void **state)
{
    (void)state;
    tdc_sim_config_t cfg;
    config(&cfg, 12);
    cfg.gaze = TDC_GAZE_FIXED;
    cfg.fov_lod = TDC_FOV_LOD_OFF; /* against point-sampled log-polar samples */
    static const char *const m[] = {"full", "fov", "fovlr", "fovlr-taa"};
    tdc_sim_result_t r[4];
    assert_int_equal(run(&cfg, m, 4, r), 0);
    print(r, 4);
    const uint16_t lw = tdc_fov_lp_size(18187, W), lh = tdc_fov_lp_size(18187, H);
    const tdc_fov_params_t p = {W * 128,
                                H * 128,
                                256,
                                4077,
                                lw,
                                lh,
                                {(uint16_t)lround(16 * ref_fov_lr_k(W, lw, W / 2.0)),
                                 (uint16_t)lround(16 * ref_fov_lr_k(H, lh, H / 2.0))},
                                TDC_FOV_LOG_RECT,
                                0};
    tdc_fov_geom_t g;
    assert_int_equal(tdc_fov_geom(&g, W, H, &p), TDC_OK);
    assert_int_equal(g.u0, 0);
    for (int i = 0; i < 4; i++) {
        assert_true(r[i].available);
        assert_int_equal(r[i].link_errors, 0);
        assert_false(r[i].nonfinite);
        assert_int_equal(r[i].foveated, i > 0);
    }
    const uint64_t frames = r[2].frames;
    assert_int_equal(r[2].rays, r[0].rays); /* the summed-area table needs the full-rate render */
    assert_int_equal(r[3].rays, r[0].rays);
    const uint64_t stream = 32u + 16u;
    assert_int_equal(tdc_fov_payload_bytes(&g, 0), 3u * lw * lh + 3u * tdc_fov_disk_pixels(&g));
    assert_int_equal(r[2].link_bytes, stream + frames * (32u + TDC_FOV_HDR_BYTES + tdc_fov_payload_bytes(&g, 0)));
    assert_int_equal(r[3].link_bytes, stream + frames * (32u + TDC_FOV_HDR_BYTES + tdc_fov_payload_bytes(&g, 1)));
    /* area averages against point samples: a better periphery, less flicker */
    for (int i = 2; i < 4; i++) {
        assert_true(r[i].flip_periph < r[1].flip_periph);
        assert_true(r[i].flip_fovea < r[i].flip_periph);
        assert_true(r[i].flicker_periph < r[1].flicker_periph);
    }
}

/* The footprint prefilter of the log-polar samples (cfg.fov_lod, the
 * procedural and photograph sources' box average): the same rays and link
 * bytes as point samples (it filters, it does not trace), full rate and
 * the fovea (nearly: FLIP's filters reach across the small disk) are
 * unchanged, and the periphery flickers less, with TAA and without. */
static void test_prefilter(void **state)
{
    (void)state;
    static const char *const m[] = {"full", "fov", "fov-taa"};
    tdc_sim_result_t r[3][3];
    static const int lods[3] = {TDC_FOV_LOD_OFF, TDC_FOV_LOD_FOOTPRINT, TDC_FOV_LOD_THESIS};
    for (int l = 0; l < 3; l++) {
        tdc_sim_config_t cfg;
        config(&cfg, 16);
        cfg.fov_lod = lods[l];
        assert_int_equal(run(&cfg, m, 3, r[l]), 0);
        printf(" lod %d\n", lods[l]);
        print(r[l], 3);
    }
    for (int l = 1; l < 3; l++) {
        assert_true(r[l][0].flip == r[0][0].flip); /* full rate: untouched */
        for (int i = 1; i < 3; i++) {
            assert_int_equal(r[l][i].rays, r[0][i].rays);
            assert_int_equal(r[l][i].link_bytes, r[0][i].link_bytes);
            /* the disk keeps its point samples (a 7.5-px disk here: FLIP's filters reach across it) */
            assert_true(fabs(r[l][i].flip_fovea - r[0][i].flip_fovea) < 0.03);
        }
    }
    for (int i = 1; i < 3; i++) {
        assert_true(r[1][i].flicker_periph < r[0][i].flicker_periph);
    }
}

/* Saccades with a tracker latency: for `latency` after each jump the fovea
 * is still at the last fixation, so the region around the true gaze is
 * served by the periphery and its FLIP rises. */
static void test_latency_moves_the_fovea(void **state)
{
    (void)state;
    static const char *const m[] = {"fov"};
    tdc_sim_result_t r0, r1;
    tdc_sim_config_t cfg;
    config(&cfg, 63); /* 0.7 s: two jumps */
    cfg.gaze = TDC_GAZE_SACCADE;
    cfg.fov_disk = 0.25;
    assert_int_equal(run(&cfg, m, 1, &r0), 0);
    cfg.gaze_latency_ms = 100.0;
    assert_int_equal(run(&cfg, m, 1, &r1), 0);
    print(&r0, 1);
    print(&r1, 1);
    assert_true(r1.flip_fovea > r0.flip_fovea + 0.02);
    assert_int_equal(r1.rays > 0, 1);
}

/* A configuration the stage refuses is not run (refused, noted). */
static void test_refused(void **state)
{
    (void)state;
    static const char *const m[] = {"full", "fov-taa"};
    tdc_sim_result_t r[2];
    tdc_sim_config_t cfg;
    config(&cfg, 6);
    cfg.fov_delta = 1.5;
    assert_int_equal(run(&cfg, m, 2, r), 0);
    assert_true(r[0].available);
    assert_false(r[1].available);
    assert_true(r[1].refused != 0);
    cfg.strict = 1;
    assert_int_equal(run(&cfg, m, 2, r), -1);
}

/* ---- fov-trm (sim/simulator/tdc_sim_mode_fovtrm.c): a TRM stream whose
 * full and reduced frames are both foveated, end to end (samples ->
 * FOVEATED packets in both slots through the firmware decoder ->
 * tdc_fov_trm -> TRM -> panel -> eye -> metrics), mono and stereo.  Rays and
 * link bytes are exactly the two grids' geometry per slot (TRM's schedule:
 * mono even frames full; stereo one eye full, one reduced); no link error,
 * no reduced frame missing; the fovea is perceived better than the
 * periphery; it costs less than fov; a panel whose reduced grid is too
 * small for the buffer, or a delta the stage refuses, is refused at init
 * (not run, and -1 with --strict). ---- */

/* The geometry of a slot's grid with the gaze fixed at the screen centre. */
static tdc_fov_geom_t trm_grid(uint16_t gw, uint16_t gh)
{
    const tdc_fov_params_t p = {gw * 128, gh * 128, 1024, 4077, tdc_fov_lp_size(18187, gw), tdc_fov_lp_size(18187, gh),
                                {0, 0}, 0, 0};
    tdc_fov_geom_t g;
    assert_int_equal(tdc_fov_geom(&g, gw, gh, &p), TDC_OK);
    return g;
}

static void test_fov_trm_exact_costs(void **state)
{
    (void)state;
    const uint16_t rw = (uint16_t)TDC_REDUCED_DIM(W, 1, 2), rh = (uint16_t)TDC_REDUCED_DIM(H, 1, 2);
    const tdc_fov_geom_t gf = trm_grid(W, H), gr = trm_grid(rw, rh);
    const uint64_t nf = (uint64_t)(gf.lp_w - gf.u0) * gf.lp_h + tdc_fov_disk_pixels(&gf);
    const uint64_t nr = (uint64_t)(gr.lp_w - gr.u0) * gr.lp_h + tdc_fov_disk_pixels(&gr);
    printf("  full grid %dx%d: %llu samples, reduced grid %ux%u: %llu samples\n", W, H, (unsigned long long)nf, rw, rh,
           (unsigned long long)nr);
    assert_true(nr > 0 && nr < nf);
    for (int eyes = 1; eyes <= 2; eyes++) {
        tdc_sim_config_t cfg;
        config(&cfg, 13);
        cfg.eyes = eyes;
        cfg.gaze = TDC_GAZE_FIXED;
        static const char *const m[] = {"full", "trm50", "fov", "fov-trm"};
        tdc_sim_result_t r[4];
        assert_int_equal(run(&cfg, m, 4, r), 0);
        print(r, 4);
        for (int i = 0; i < 4; i++) {
            assert_true(r[i].available);
            assert_int_equal(r[i].link_errors, 0); /* every packet accepted, none missing */
            assert_false(r[i].nonfinite);
            assert_true(r[i].flip > 0 && r[i].flip < 1);
        }
        assert_int_equal(r[3].foveated, 1);
        /* TRM's schedule: mono even refreshes full; stereo one eye of each */
        const uint64_t frames = r[3].frames;
        const uint64_t n_full = eyes == 2 ? frames : (frames + 1u) / 2u, n_red = eyes == 2 ? frames : frames / 2u;
        assert_int_equal(r[3].rays, (n_full * nf + n_red * nr) * 4u); /* spp 4 below 200 Hz, like full */
        const uint64_t stream = 32u + 16u;
        assert_int_equal(r[3].link_bytes,
                         stream + n_full * (32u + TDC_FOV_HDR_BYTES + tdc_fov_payload_bytes(&gf, 0)) +
                             n_red * (32u + TDC_FOV_HDR_BYTES + tdc_fov_payload_bytes(&gr, 0)));
        /* cheaper than fov, whose every picture is the full grid's */
        assert_int_equal(r[2].rays, frames * (uint64_t)eyes * nf * 4u);
        assert_true(r[3].rays < r[2].rays && r[3].link_bytes < r[2].link_bytes);
        /* the disk is traced densely, the periphery is not */
        assert_true(r[3].flip_fovea < r[3].flip_periph);
        assert_true(r[3].flip_periph > r[0].flip_periph);
    }
}

/* A reduced grid too small for the buffer (16 x 12: the 8 x 6 grid's
 * buffer would be 4 x 3, below the stage's minimum side), and a delta the
 * stage refuses: fov-trm is refused at init while fov runs. */
static void test_fov_trm_refused(void **state)
{
    (void)state;
    static const char *const m[] = {"fov", "fov-trm"};
    tdc_sim_result_t r[2];
    tdc_sim_config_t cfg;
    config(&cfg, 4);
    cfg.width = cfg.scene.width = 16;
    cfg.height = cfg.scene.height = 12;
    assert_int_equal(run(&cfg, m, 2, r), 0);
    print(r, 2);
    assert_true(r[0].available);
    assert_false(r[1].available);
    assert_true(r[1].refused != 0);
    assert_int_equal(r[1].rays, 0);
    cfg.strict = 1;
    assert_int_equal(run(&cfg, m, 2, r), -1);
    config(&cfg, 4);
    cfg.fov_delta = 1.5;
    assert_int_equal(run(&cfg, m + 1, 1, r), 0);
    assert_false(r[0].available);
    assert_true(r[0].refused != 0);
}

/* ---- the gaze schedules and the tracker ---- */
static void const_pursuit(tdc_source_t *s, double t, double v[2])
{
    (void)s;
    (void)t;
    v[0] = 100.0;
    v[1] = -50.0;
}

static void test_gaze_schedules(void **state)
{
    (void)state;
    tdc_source_t src;
    memset(&src, 0, sizeof src);
    src.pursuit = const_pursuit;
    tdc_sim_gaze_t g;
    memset(&g, 0, sizeof g);
    g.schedule = TDC_GAZE_PURSUIT;
    g.ppd = 10.0;
    assert_int_equal(tdc_sim_gaze_init(&g, &src, 400, 300, 100.0, 2.0), 0);
    double a[2], b[2];
    /* pursuit: centre + v t while in the central half (100 px / 100 px/s = 1 s in x) */
    tdc_sim_gaze_true(&g, 0.5, a);
    assert_true(fabs(a[0] - (200.0 + 50.0)) < 0.6 && fabs(a[1] - (150.0 - 25.0)) < 0.6);
    /* y leaves the central half (75 px) after 1.5 s, x (100 px) after 1 s: a saccade to the centre at 1 s */
    tdc_sim_gaze_true(&g, 1.01, a);
    assert_true(fabs(a[0] - 200.0) < 2.0 && fabs(a[1] - 150.0) < 2.0);
    /* latency: the tracked gaze is the true gaze of t - latency */
    g.latency_ms = 40.0;
    tdc_sim_gaze_tracked(&g, 0.7, 3, 0, a);
    tdc_sim_gaze_true(&g, 0.66, b);
    assert_true(a[0] == b[0] && a[1] == b[1]);
    /* noise: zero mean, sigma = noise deg x ppd per axis, per frame and eye */
    g.latency_ms = 0.0;
    g.noise_deg = 0.5;
    g.seed = 7;
    tdc_sim_gaze_true(&g, 0.3, b);
    double sx = 0, sy = 0, sxx = 0, syy = 0;
    const int n = 20000;
    for (int k = 0; k < n; k++) {
        tdc_sim_gaze_tracked(&g, 0.3, (uint32_t)k, k & 1, a);
        const double dx = a[0] - b[0], dy = a[1] - b[1];
        sx += dx;
        sy += dy;
        sxx += dx * dx;
        syy += dy * dy;
    }
    printf("  noise: mean %.3f %.3f sd %.3f %.3f (want 0, 5)\n", sx / n, sy / n, sqrt(sxx / n), sqrt(syy / n));
    assert_true(fabs(sx / n) < 0.15 && fabs(sy / n) < 0.15);
    assert_true(fabs(sqrt(sxx / n) - 5.0) < 0.15 && fabs(sqrt(syy / n) - 5.0) < 0.15);
    tdc_sim_gaze_tracked(&g, 0.3, 11, 0, a);
    tdc_sim_gaze_tracked(&g, 0.3, 11, 1, b);
    assert_true(a[0] != b[0]); /* the eyes' trackers are independent */
    tdc_sim_gaze_free(&g);
    /* fixed, saccade */
    memset(&g, 0, sizeof g);
    g.schedule = TDC_GAZE_FIXED;
    g.at_x = 30;
    g.at_y = 40;
    assert_int_equal(tdc_sim_gaze_init(&g, NULL, 400, 300, 90.0, 1.0), 0);
    tdc_sim_gaze_true(&g, 0.9, a);
    assert_true(a[0] == 30 && a[1] == 40);
    assert_true(fabs(tdc_sim_gaze_rmax(&g, a) - hypot(370, 260)) < 1e-9);
    tdc_sim_gaze_free(&g);
    memset(&g, 0, sizeof g);
    g.schedule = TDC_GAZE_SACCADE;
    assert_int_equal(tdc_sim_gaze_init(&g, NULL, 400, 300, 90.0, 1.0), 0);
    double prev[2] = {-1, -1};
    int jumps = 0;
    for (double t = 0; t < 1.0; t += 0.01) {
        tdc_sim_gaze_true(&g, t, a);
        if (prev[0] >= 0 && (a[0] != prev[0] || a[1] != prev[1])) {
            jumps++;
            assert_true(hypot(a[0] - prev[0], a[1] - prev[1]) > 50.0);
        }
        prev[0] = a[0];
        prev[1] = a[1];
    }
    assert_int_equal(jumps, 3); /* 250 ms fixations */
    tdc_sim_gaze_free(&g);
    assert_int_equal(tdc_sim_gaze_from_name("saccade"), TDC_GAZE_SACCADE);
    assert_int_equal(tdc_sim_gaze_from_name("blink"), -1);
}

TDC_TEST_MAIN(
    cmocka_unit_test(test_modes_exact_costs),
    cmocka_unit_test(test_lr_modes),
    cmocka_unit_test(test_prefilter),
    cmocka_unit_test(test_latency_moves_the_fovea),
    cmocka_unit_test(test_refused),
    cmocka_unit_test(test_fov_trm_exact_costs),
    cmocka_unit_test(test_fov_trm_refused),
    cmocka_unit_test(test_gaze_schedules),
)
