/*
 * tdc_sim_mode_trm.c - temporal resolution multiplexing (TRM paper) and its
 * NCSFI baseline through the firmware's TRM stage (firmware/tdc_trm.h).
 *
 *   trmXX  even frames full resolution (tdc_trm_full: sharpened frame +
 *          residual), odd frames rendered full-res, prefiltered by D to the
 *          reduced size r (TRM §4.3), sent as REDUCED packets and upsampled
 *          + residual-corrected by tdc_trm_reduced.
 *   ncsfi  half rate; the sharpened + blurred pair comes from one rendered
 *          frame, the residual always added (s = 0: w = 1).
 *   reduced50  the same stream as trm50 without TRM's compensation: full
 *          frames shown as rendered, reduced frames as U(i) alone (the
 *          firmware's unpaired path, tdc_trm_reduced_seq) - what TRM's
 *          sharpening and residual are measured against (issue 15).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "simulator/tdc_sim_mode.h"

#include "tdc_trm.h"
#include "tdc_trm_gaze.h"
#include "tdc_free.h"

enum { TRM_TRM, TRM_NCSFI, TRM_REDUCED_ONLY, TRM_GAZE, TRM_RENDER_PRE, TRM_RENDER_POINT };

#define F &tdc_sim_family_trm
#define R TDC_SIM_LINK_REDUCED
static const tdc_mode_desc_t k_modes[] = {
    {"ncsfi", F, TRM_NCSFI, 0, 1, 2, 0, 0, 0,
     "half rate; sharpened + blurred frame pair from one frame, residual always added"},
    {"trm50", F, TRM_TRM, R, 1, 2, 0, 0, 0, "TRM, every other frame at r = 1/2"},
    {"trm40", F, TRM_TRM, R, 2, 5, 0, 0, 0, "TRM, every other frame at r = 0.4"},
    {"trm25", F, TRM_TRM, R, 1, 4, 0, 0, 0, "TRM, every other frame at r = 1/4"},
    {"trm60", F, TRM_TRM, R, 3, 5, 0, 0, 0, "TRM, every other frame at r = 0.6"},
    {"trm75", F, TRM_TRM, R, 3, 4, 0, 0, 0, "TRM, every other frame at r = 3/4"},
    {"reduced50", F, TRM_REDUCED_ONLY, R, 1, 2, 0, 0, 0,
     "every other frame at r = 1/2, upsampled, no compensation (full frames unsharpened, no residual)"},
    {"trm50r", F, TRM_RENDER_PRE, R, 1, 2, 0, 0, 0,
     "TRM r = 1/2, reduced frames traced by the renderer (REDUCED: 2x2 rays per pixel, Gaussian resolve; -R only)"},
    {"trm25r", F, TRM_RENDER_PRE, R, 1, 4, 0, 0, 0,
     "TRM r = 1/4, reduced frames traced by the renderer (REDUCED: 2x2 rays per pixel, Gaussian resolve; -R only)"},
    {"trm50p", F, TRM_RENDER_POINT, R, 1, 2, 0, 0, 0,
     "TRM r = 1/2, reduced frames point-sampled by the renderer (1 ray per reduced pixel, no prefilter; -R only)"},
    {"trm50g", F, TRM_GAZE, R, 1, 2, 0, 0, 0,
     "gaze-aware TRM r = 1/2: compensation falls where retinal motion (MV - gaze) is large (tdc_trm_gaze.h)"},
};
#undef F
#undef R

typedef struct {
    tdc_trm_t trm;   /* the controller's TRM stage */
    tdc_trm_t trm_r; /* the renderer's prefilter D (same configuration) */
    void *mem, *mem_r;
    uint8_t *reduced; /* the renderer's reduced frame */
    /* trm50g: the gaze stage, the renderer's per-pixel MVs and their tile means */
    tdc_trm_gaze_t gaze;
    void *mem_g;
    int16_t *mv, *tile_mv;
    double pursuit_gain; /* the eye model's, for the eye tracker's velocity */
    int red_open;        /* trm50r/p: the renderer's reduced-frame instance is open */
} trm_state_t;

static int32_t *trm_residual(sim_mode_t *m)
{
    return tdc_trm_residual(&((trm_state_t *)m->fam)->trm);
}

static int trm_init(sim_mode_t *m, const tdc_sim_setup_t *s)
{
    trm_state_t *st = calloc(1, sizeof(*st));
    if (!st) {
        return -1;
    }
    m->fam = st;
    tdc_trm_config_t tc;
    tdc_trm_default_config(&tc, (uint16_t)m->w, (uint16_t)m->h, (uint16_t)m->hz);
    tc.r_num = m->d->r_num;
    tc.r_den = m->d->r_den;
    if (s->cfg->trm_s > 0) {
        tc.s_q8 = (uint32_t)s->cfg->trm_s * 256u;
    }
    if (s->cfg->trm_sigma != 0) {
        double sg = s->cfg->trm_sigma > 0 ? s->cfg->trm_sigma : 1.25 * m->d->r_den / m->d->r_num;
        if (sg * 256.0 > TDC_TRM_MAX_SIGMA_Q8) {
            fprintf(stderr, "tdc-sim: %s: --trm-sigma scaled: sigma %.2f px at r = %d/%d is above the firmware "
                            "D's largest, %.1f px\n", m->d->name, sg, m->d->r_num, m->d->r_den,
                    TDC_TRM_MAX_SIGMA_Q8 / 256.0);
            return -2; /* refused (reported), not out of memory */
        }
        tc.sigma_q8 = (uint16_t)(sg * 256.0 + 0.5);
    }
    if (m->d->variant == TRM_NCSFI) {
        tc.s_q8 = 0; /* w = exp(0) = 1: residual added regardless of motion */
    }
    /* the LCD inverse adds the light it could not reach to rho: the
     * simulator keeps rho stored for it (boards recompute rho and drop
     * that light, counted: docs/boards.md) */
    tc.keep_residual = 1;
    size_t n = tdc_trm_get_size(&tc);
    st->mem = n ? malloc(n) : NULL;
    st->mem_r = n ? malloc(n) : NULL;
    st->reduced = calloc(m->npx * 3, 1);
    if (!st->reduced || (n && (!st->mem || !st->mem_r))) {
        return -1;
    }
    tdc_status_t s1 = st->mem ? tdc_trm_init(&st->trm, &tc, s->fw_panel, st->mem, n) : TDC_ERR_SIZE;
    tdc_status_t s2 = st->mem_r ? tdc_trm_init(&st->trm_r, &tc, s->fw_panel, st->mem_r, n) : TDC_ERR_SIZE;
    if (s1 != TDC_OK || s2 != TDC_OK) {
        tdc_sim_refuse(m, "TRM firmware", s1 != TDC_OK ? s1 : s2);
        return 0;
    }
    m->residual = trm_residual;
    if ((m->d->variant == TRM_RENDER_PRE || m->d->variant == TRM_RENDER_POINT) && !s->src_full_frame) {
        tdc_sim_note(m, "needs a renderer that traces reduced frames (-R SCENE)");
        m->res->available = 0;
        return 0;
    }
    if (m->d->variant == TRM_GAZE) {
        st->pursuit_gain = s->cfg->pursuit_gain;
        tdc_trm_gaze_config_t gc;
        tdc_trm_gaze_default_config(&gc, (uint16_t)m->w, (uint16_t)m->h);
        size_t ng = tdc_trm_gaze_get_size(&gc);
        st->mem_g = malloc(ng);
        st->mv = malloc(sizeof(int16_t) * 2 * m->npx);
        st->tile_mv = malloc(sizeof(int16_t) * 2 * (size_t)TDC_TRM_GAZE_TILES_X(m->w, gc.tile) *
                             TDC_TRM_GAZE_TILES_Y(m->h, gc.tile));
        if (!st->mem_g || !st->mv || !st->tile_mv) {
            return -1;
        }
        tdc_status_t sg = tdc_trm_gaze_init(&st->gaze, &gc, st->mem_g, ng);
        if (sg == TDC_OK) {
            sg = tdc_trm_set_gaze(&st->trm, &st->gaze);
        }
        if (sg != TDC_OK) {
            tdc_sim_refuse(m, "TRM gaze stage", sg);
        }
    }
    return 0;
}

/* trm50g: the tile motion vectors (content motion over one frame, Q4: the
 * renderer's backward MVs negated, averaged per tile) and the eye tracker's
 * gaze velocity (the pursuit the eye model applies), into the gaze stage
 * before the full frame; the MOTION packet's bytes are counted on the link. */
static int trm_gaze_update(sim_mode_t *m, trm_state_t *st, tdc_source_t *src, double t)
{
    const uint32_t tile = st->gaze.cfg.tile, tx = st->gaze.tx, ty = st->gaze.ty;
    for (uint32_t j = 0; j < ty; j++) {
        for (uint32_t i = 0; i < tx; i++) {
            double sx = 0.0, sy = 0.0;
            int n = 0;
            for (uint32_t y = j * tile; y < (j + 1) * tile && y < (uint32_t)m->h; y++) {
                for (uint32_t x = i * tile; x < (i + 1) * tile && x < (uint32_t)m->w; x++) {
                    sx -= st->mv[2 * ((size_t)y * m->w + x)];
                    sy -= st->mv[2 * ((size_t)y * m->w + x) + 1];
                    n++;
                }
            }
            st->tile_mv[2 * (j * tx + i)] = (int16_t)lround(sx / n);
            st->tile_mv[2 * (j * tx + i) + 1] = (int16_t)lround(sy / n);
        }
    }
    tdc_sim_link_count_raw(m->link, (size_t)tx * ty * 4);
    double v[2];
    src->pursuit(src, t, v);
    double g[2] = {16.0 * v[0] * st->pursuit_gain * m->fs, 16.0 * v[1] * st->pursuit_gain * m->fs};
    for (int c = 0; c < 2; c++) {
        g[c] = g[c] > 32767.0 ? 32767.0 : (g[c] < -32767.0 ? -32767.0 : g[c]);
    }
    return tdc_sim_stage(
        m, "tdc_trm_gaze_update",
        tdc_trm_gaze_update(&st->gaze, st->tile_mv, tx * ty, (int16_t)lround(g[0]), (int16_t)lround(g[1])));
}

/* The full-resolution frame of a pair: render, send over the link, run the
 * firmware's full-frame step on what the decoder got. */
static int trm_full_frame(sim_mode_t *m, trm_state_t *st, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    int gz = m->d->variant == TRM_GAZE;
    tdc_sim_render_full(m, src, t, spp, 0, 0, gz ? st->mv : NULL, gz ? m->fs : 0, TDC_MV_SURFACE);
    if (gz && trm_gaze_update(m, st, src, t)) {
        return -1;
    }
    int rc = tdc_sim_stage(m, "link FULL packet", tdc_sim_link_full(m->link, m->eye, lf, m->render));
    if (rc) {
        return rc;
    }
    double t0 = tdc_sim_now();
    /* frames tied by the link's frame index, as the boards' frame loop does
     * (firmware/board/tdc_main.c) */
    rc = tdc_trm_full_seq(&st->trm, TDC_SIM_LINK_FULL(m), (uint32_t)m->w * 3u, m->wanted, (uint32_t)m->w * 3u, lf);
    m->res->fw_s += tdc_sim_now() - t0;
    return tdc_sim_stage(m, "tdc_trm_full_seq", rc);
}

static int trm_frame(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    trm_state_t *st = m->fam;
    tdc_sim_result_t *r = m->res;
    uint32_t rw3 = (uint32_t)st->trm.rw * 3u, w3 = (uint32_t)m->w * 3u;
    /* mono: even frames full; stereo (TRM §7.2): eye e full on frames with
     * f + e even, i.e. one eye full and the other reduced, swapped every
     * frame (the firmware's and the link's rule) */
    int full = m->d->variant == TRM_NCSFI ? (lf & 1u) == 0u : tdc_trm_stereo_eye_is_full(lf, m->eye);
    if (full && m->d->variant == TRM_REDUCED_ONLY) {
        tdc_sim_render_full(m, src, t, spp, 0, 0, NULL, 0, TDC_MV_SURFACE);
        int rc = tdc_sim_stage(m, "link FULL packet", tdc_sim_link_full(m->link, m->eye, lf, m->render));
        if (rc == 0) {
            memcpy(m->wanted, TDC_SIM_LINK_FULL(m), m->npx * 3); /* shown as rendered */
        }
        return rc;
    }
    if (full) {
        return trm_full_frame(m, st, src, t, spp, lf);
    }
    double t0;
    int rc;
    if (m->d->variant == TRM_NCSFI) {
        /* the blurred frame comes from the same rendered frame */
        t0 = tdc_sim_now();
        rc = tdc_sim_stage(m, "tdc_trm_downsample",
                           tdc_trm_downsample(&st->trm, TDC_SIM_LINK_FULL(m), w3, st->reduced, rw3));
        if (rc == 0) {
            rc = tdc_sim_stage(m, "tdc_trm_reduced", tdc_trm_reduced(&st->trm, st->reduced, rw3, m->wanted, w3));
        }
        r->fw_s += tdc_sim_now() - t0;
        return rc;
    }
    if (m->d->variant == TRM_RENDER_PRE || m->d->variant == TRM_RENDER_POINT) {
        /* the renderer's own reduced frame (TRM §4.3): supersampled and
         * Gaussian-resolved (TRM's sigma 2.5 full-res px), or point-sampled
         * (one ray per reduced pixel, a resolve too narrow to reach a
         * neighbour: the naive, aliased frame §4.3 warns of) */
        int pre = m->d->variant == TRM_RENDER_PRE;
        uint64_t rays = 0;
        const double rr = (double)m->d->r_num / m->d->r_den, sig = pre ? 2.5 : 0.05;
        if (src->reduced_frame && !st->red_open) {
            /* open the renderer instance untimed: its set-up (a BVH build:
             * seconds on bigmesh) is not a frame's cost */
            st->red_open = src->reduced_frame(src, m->slot, t, rr, pre ? 2 : 1, sig, st->trm.rw, st->trm.rh, NULL, &rays) == 0;
        }
        t0 = tdc_sim_now();
        rc = src->reduced_frame ? src->reduced_frame(src, m->slot, t, rr, pre ? 2 : 1, sig, st->trm.rw, st->trm.rh,
                                                     st->reduced, &rays)
                                : -1;
        r->render_s += tdc_sim_now() - t0;
        r->rays += rays;
        r->rendered++;
        rc = tdc_sim_stage(m, "renderer REDUCED frame", rc ? TDC_ERR_SIZE : 0);
    } else {
        /* Renderer: full-res render prefiltered by D (TRM §4.3); its cost is
     * counted as the reduced frame's rays (a renderer traces the reduced
     * target with MSAA). */
        uint64_t rays0 = r->rays;
        tdc_sim_render_full(m, src, t, spp, 0, 0, NULL, 0, TDC_MV_SURFACE);
        uint64_t traced = r->rays - rays0;
        r->rays = rays0 + traced * ((uint64_t)st->trm.rw * st->trm.rh) / m->npx;
        t0 = tdc_sim_now();
        rc = tdc_sim_stage(m, "renderer prefilter (tdc_trm_downsample)",
                           tdc_trm_downsample(&st->trm_r, m->render, w3, st->reduced, (uint32_t)st->trm_r.rw * 3u));
        r->render_s += tdc_sim_now() - t0;
    }
    if (rc == 0) {
        rc = tdc_sim_stage(m, "link REDUCED packet", tdc_sim_link_reduced(m->link, m->eye, lf, st->reduced));
    }
    if (rc == 0) {
        t0 = tdc_sim_now();
        /* Stereo stream start: eye 1's first frame is reduced (the link's
         * rule, tdc_link_trm_kind) with no full frame before it.  The
         * boards' path shows it upsampled without residual (counted as
         * unpaired); tdc_trm_reduced refused it and left the eye black for
         * a frame: on a 12-frame 48x40 pan the right eye scored 0.86 dB PSNR
         * below the left and 1.3x its flicker (test_stereo_symmetric).
         * reduced50 never gives the stage a full frame: every reduced
         * frame takes that unpaired path, alpha = lin(U(i)) alone. */
        rc = tdc_trm_reduced_seq(&st->trm, TDC_SIM_LINK_REDUCED_BUF(m), rw3, m->wanted, w3, lf);
        r->fw_s += tdc_sim_now() - t0;
        rc = tdc_sim_stage(m, "tdc_trm_reduced_seq", rc);
    }
    return rc;
}

static void trm_reset(sim_mode_t *m)
{
    trm_state_t *st = m->fam;
    if (st && m->res->available) {
        tdc_trm_reset(&st->trm);
        tdc_trm_reset(&st->trm_r);
    }
}

static void trm_free(sim_mode_t *m)
{
    trm_state_t *st = m->fam;
    if (st) {
        TDC_FREE_ALL(st->mem, st->mem_r, st->reduced, st->mem_g, st->mv, st->tile_mv, st);
    }
    m->fam = NULL;
}

const tdc_sim_family_t tdc_sim_family_trm = {
    "trm", k_modes, (int)(sizeof(k_modes) / sizeof(k_modes[0])), trm_init, trm_frame, trm_reset, trm_free,
};
