/*
 * test_sim_fov_trm.c - the simulator's fov-trm mode (issue 14 item 5):
 * a TRM stream whose full and reduced frames are both foveated, end to end
 * (samples -> FOVEATED packets in both slots through the firmware decoder ->
 * tdc_fov_trm -> TRM -> panel -> eye -> metrics), mono and stereo.  Rays
 * and link bytes are exactly the two grids' geometry per slot (TRM's
 * schedule: mono even frames full; stereo one eye full, one reduced); no
 * link error, no reduced frame missing; the fovea is perceived better than
 * the periphery; it costs less than fov; a panel whose reduced grid is too
 * small for the buffer, or a delta the stage refuses, is refused at init
 * (not run, and -1 with --strict).
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

#include "simulator/tdc_sim.h"
#include "simulator/tdc_sim_gaze.h"
#include "tdc_fov.h"
#include "tdc_fov_link.h"
#include "tdc_geom.h"
#include "tdc_sim_features.h"

#define W 96
#define H 72

static void config(tdc_sim_config_t *cfg, int w, int h, int frames)
{
    tdc_sim_default_config(cfg);
    cfg->scene.kind = TDC_SCENE_PAN;
    cfg->width = cfg->scene.width = w;
    cfg->height = cfg->scene.height = h;
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
    const int rc = tdc_sim_run(cfg, src, modes, n, res, NULL);
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
               "bytes %llu frames %llu %s\n",
               r[i].desc->name, r[i].available, r[i].flip, r[i].flip_fovea, r[i].flip_periph, r[i].flip_ecc,
               r[i].flip_wmedian, r[i].flicker, r[i].flicker_periph, (unsigned long long)r[i].rays,
               (unsigned long long)r[i].link_bytes, (unsigned long long)r[i].frames, r[i].note);
    }
}

/* The geometry of a slot's grid with the gaze fixed at the screen centre. */
static tdc_fov_geom_t grid(uint16_t gw, uint16_t gh)
{
    const tdc_fov_params_t p = {gw * 128, gh * 128, 1024, 4077, tdc_fov_lp_size(18187, gw), tdc_fov_lp_size(18187, gh),
                                {0, 0}, 0, 0};
    tdc_fov_geom_t g;
    assert_int_equal(tdc_fov_geom(&g, gw, gh, &p), TDC_OK);
    return g;
}

static void test_exact_costs(void **state)
{
    (void)state;
    if (!TDC_SIM_HAVE_LINK || !TDC_SIM_HAVE_TRM) {
        skip();
    }
    const uint16_t rw = (uint16_t)TDC_REDUCED_DIM(W, 1, 2), rh = (uint16_t)TDC_REDUCED_DIM(H, 1, 2);
    const tdc_fov_geom_t gf = grid(W, H), gr = grid(rw, rh);
    const uint64_t nf = (uint64_t)(gf.lp_w - gf.u0) * gf.lp_h + tdc_fov_disk_pixels(&gf);
    const uint64_t nr = (uint64_t)(gr.lp_w - gr.u0) * gr.lp_h + tdc_fov_disk_pixels(&gr);
    printf("  full grid %dx%d: %llu samples, reduced grid %ux%u: %llu samples\n", W, H, (unsigned long long)nf, rw, rh,
           (unsigned long long)nr);
    assert_true(nr > 0 && nr < nf);
    for (int eyes = 1; eyes <= 2; eyes++) {
        tdc_sim_config_t cfg;
        config(&cfg, W, H, 13);
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
static void test_refused(void **state)
{
    (void)state;
    if (!TDC_SIM_HAVE_LINK || !TDC_SIM_HAVE_TRM) {
        skip();
    }
    static const char *const m[] = {"fov", "fov-trm"};
    tdc_sim_result_t r[2];
    tdc_sim_config_t cfg;
    config(&cfg, 16, 12, 4);
    assert_int_equal(run(&cfg, m, 2, r), 0);
    print(r, 2);
    assert_true(r[0].available);
    assert_false(r[1].available);
    assert_true(r[1].refused != 0);
    assert_int_equal(r[1].rays, 0);
    cfg.strict = 1;
    assert_int_equal(run(&cfg, m, 2, r), -1);
    config(&cfg, W, H, 4);
    cfg.fov_delta = 1.5;
    assert_int_equal(run(&cfg, m + 1, 1, r), 0);
    assert_false(r[0].available);
    assert_true(r[0].refused != 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exact_costs),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
