/*
 * tdc_sim_mode_fovtrm.c - foveated TRM (issue 14 item 5, docs/foveation.md
 * "Foveated TRM"): a TRM stream (r = 1/2, full and reduced frames
 * alternating, per eye as the link's schedule says) whose frames are both
 * foveated.  Per refresh the gaze the eye tracker reports (as in the fov
 * modes), then for the slot due:
 *
 *   full     the kernel log-polar buffer and disk of the W x H grid, sent as
 *            a FOVEATED packet, remapped by the firmware into the decoder's
 *            full frame, then tdc_trm_full_seq (sharpened frame + residual);
 *   reduced  the same on the rw x rh reduced grid (gaze, disk and buffer
 *            sizes of that grid; each sample traced at its place on the
 *            screen), a FOVEATED packet with FOV_REDUCED, remapped into the
 *            decoder's reduced frame, then tdc_trm_reduced_seq exactly as
 *            for a plain REDUCED packet.
 *
 * The firmware side is tdc_fov_trm (one tdc_fov instance per grid).  No
 * peripheral TAA (fov-trm-taa is not a mode): the link refuses vectors in a
 * TRM stream, because each grid's remap sees every other frame of its eye
 * (its history would be two frames old while the vectors reach one), and
 * TRM's own temporal step already pairs each reduced frame with the full
 * frame before it (docs/foveation.md).
 *
 * Samples: every source through samples() at the positions of the exact
 * inverse of eq. 2.2 (ref/ref_fov.c, ref_fov_lp_samples as fov, with fov's
 * footprint prefilter --fov-lod) on the slot's grid and the grid's disk
 * pixels, scaled to the screen (W / rw, H / rh), spp rays each; a reduced
 * disk pixel's rays spread over its footprint (g x g point samples, g^2 <=
 * spp; one at its centre at spp 1) and are resolved with TRM's Gaussian
 * D over the neighbouring disk pixels' (as the renderer's trm50r reduced
 * frames), so the reduced frame is the prefiltered picture TRM's residual
 * assumes.  rays = samples x spp, exactly.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_fov.h"
#include "simulator/tdc_sim_mode.h"
#include "tdc_sim_codes.h"
#include "tdc_fov_link.h"

#include "tdc_fov_trm.h"
#include "tdc_trm.h"
#include "tdc_free.h"

#define F &tdc_sim_family_fovtrm
#define L (TDC_SIM_LINK_FOVEATED | TDC_SIM_LINK_REDUCED)
static const tdc_mode_desc_t k_modes[] = {
    {"fov-trm", F, 0, L, 1, 2, 0, 0, 0,
     "foveated TRM: trm50's stream with both frames foveated (fov's alpha, delta, disk; reduced frames on the "
     "r = 1/2 grid), firmware remap into each, then TRM"},
};
#undef L
#undef F

typedef struct {
    tdc_trm_t trm;
    void *trm_mem;
    tdc_fov_trm_t fv;
    void *fv_mem;
    uint8_t *samp; /* samples in payload order */
    double *xy;    /* positions (cap of them) */
    uint8_t *sub;  /* the reduced disk's point samples (cap) */
    double *lin;   /* ... in linear light (cap x 3) */
    int32_t *map;  /* reduced grid: disk index of each pixel, -1 outside */
    double *side;  /* footprint of each log-polar sample, display pixels (fov's prefilter) */
    tdc_sim_fov_link_t q; /* the link header's parameters, as the fov modes */
    size_t cap;
    double last_t;
    int have_t;
} fovtrm_state_t;

/* Position and sample buffers for n positions (grown on demand: the
 * reduced frames' disk needs spp positions per pixel). */
static int fovtrm_reserve(fovtrm_state_t *st, size_t n)
{
    if (n <= st->cap) {
        return 0;
    }
    double *xy = realloc(st->xy, n * 2 * sizeof(double));
    if (xy) {
        st->xy = xy;
    }
    uint8_t *sub = realloc(st->sub, n * 3);
    if (sub) {
        st->sub = sub;
    }
    double *lin = realloc(st->lin, n * 3 * sizeof(double));
    if (lin) {
        st->lin = lin;
    }
    if (!xy || !sub || !lin) {
        return -1;
    }
    st->cap = n;
    return 0;
}

/* The reduced disk pixels from their point samples (st->sub, positions at
 * st->xy + 2 nlp, sub per pixel in disk order): each the Gaussian resolve of
 * the point samples within 3 sigma of its centre (sigma = TRM's D, in
 * full-res px; neighbours outside the disk are missing and the weights
 * renormalised), in linear light -- what the renderer's REDUCED frames do
 * (trm50r: ss x ss rays per reduced pixel, Gaussian resolve), so that the
 * reduced frame is the D-prefiltered picture TRM's residual expects. */
static void resolve_reduced_disk(fovtrm_state_t *st, const tdc_source_t *src, const tdc_fov_geom_t *g, size_t nlp,
                                 size_t nd, int sub, double sx, double sy)
{
    const int gw = g->width, gh = g->height;
    const double sig = st->trm.cfg.sigma_q8 / 256.0, reach = 3.0 * sig;
    /* disk index of every reduced pixel, -1 outside the disk */
    for (size_t i = 0; i < (size_t)gw * gh; i++) {
        st->map[i] = -1;
    }
    int32_t d = 0;
    for (int j = 0; j < gh; j++) {
        int32_t x0;
        const uint32_t span = tdc_fov_disk_span(g, j, &x0);
        for (uint32_t i = 0; i < span; i++) {
            st->map[(size_t)j * gw + (size_t)x0 + i] = d++;
        }
    }
    for (size_t q = 0; q < nd * (size_t)sub * 3u; q++) {
        st->lin[q] = pow(st->sub[q] / 255.0, src->gamma[q % 3u]);
    }
    const int ri = (int)ceil(reach / sx) + 1, rj = (int)ceil(reach / sy) + 1;
    for (int j = 0; j < gh; j++) {
        for (int i = 0; i < gw; i++) {
            const int32_t k = st->map[(size_t)j * gw + (size_t)i];
            if (k < 0) {
                continue;
            }
            const double cx = (i + 0.5) * sx, cy = (j + 0.5) * sy;
            double acc[3] = {0, 0, 0}, wsum = 0.0;
            for (int b = j - rj; b <= j + rj; b++) {
                for (int a = i - ri; a <= i + ri; a++) {
                    const int32_t n = (a < 0 || b < 0 || a >= gw || b >= gh) ? -1 : st->map[(size_t)b * gw + (size_t)a];
                    for (int q = 0; n >= 0 && q < sub; q++) {
                        const size_t o = (size_t)n * (size_t)sub + (size_t)q;
                        const double dx = st->xy[2 * (nlp + o)] - cx, dy = st->xy[2 * (nlp + o) + 1] - cy;
                        const double d2 = dx * dx + dy * dy;
                        if (d2 > reach * reach) {
                            continue;
                        }
                        const double w = exp(-d2 / (2.0 * sig * sig));
                        wsum += w;
                        for (int c = 0; c < 3; c++) {
                            acc[c] += w * st->lin[3 * o + (size_t)c];
                        }
                    }
                }
            }
            for (int c = 0; c < 3; c++) {
                st->samp[3 * (nlp + (size_t)k) + (size_t)c] = tdc_sim_encode_code(acc[c] / wsum, src->gamma[c]);
            }
        }
    }
}

static int32_t *fovtrm_residual(sim_mode_t *m)
{
    return tdc_trm_residual(&((fovtrm_state_t *)m->fam)->trm);
}

static int fovtrm_init(sim_mode_t *m, const tdc_sim_setup_t *s)
{
    const tdc_sim_config_t *cfg = s->cfg;
    m->res->foveated = 1;
    fovtrm_state_t *st = calloc(1, sizeof *st);
    if (!st) {
        return -1;
    }
    m->fam = st;
    st->q = tdc_sim_fov_link_of(cfg);
    tdc_trm_config_t tc;
    tdc_trm_default_config(&tc, (uint16_t)m->w, (uint16_t)m->h, (uint16_t)m->hz);
    tc.r_num = m->d->r_num;
    tc.r_den = m->d->r_den;
    if (cfg->trm_s > 0) {
        tc.s_q8 = (uint32_t)cfg->trm_s * 256u;
    }
    tc.keep_residual = 1; /* for the LCD stage, as the trm modes */
    const size_t nt = tdc_trm_get_size(&tc);
    const uint16_t rw = (uint16_t)m->link->rw, rh = (uint16_t)m->link->rh;
    const size_t nf = tdc_fov_trm_get_size((uint16_t)m->w, (uint16_t)m->h, rw, rh);
    if (!nt || !nf || !(cfg->fov_delta > 0 && cfg->fov_delta <= 1)) {
        tdc_sim_refuse(m, "fov-trm init (size or delta)", TDC_ERR_SIZE);
        return 0;
    }
    const size_t lpn = (size_t)tdc_fov_lp_size(st->q.delta_q15, (uint16_t)m->w) *
                       tdc_fov_lp_size(st->q.delta_q15, (uint16_t)m->h);
    st->trm_mem = malloc(nt);
    st->fv_mem = aligned_alloc(8, (nf + 7) & ~(size_t)7);
    st->samp = malloc((lpn + m->npx) * 3);
    st->map = malloc((size_t)rw * rh * sizeof(int32_t));
    st->side = malloc((lpn ? lpn : 1) * sizeof(double));
    if (!st->map || !st->side || !st->trm_mem || !st->fv_mem || !st->samp || fovtrm_reserve(st, lpn + m->npx) != 0) {
        return -1;
    }
    tdc_status_t rc = tdc_trm_init(&st->trm, &tc, s->fw_panel, st->trm_mem, nt);
    if (rc == TDC_OK) {
        rc = tdc_fov_trm_init(&st->fv, (uint16_t)m->w, (uint16_t)m->h, rw, rh, st->fv_mem, nf);
    }
    /* both grids must take the parameters (a small panel's reduced grid
     * can give a log-polar buffer below the stage's minimum side): refused
     * here rather than on the first reduced frame */
    for (int red = 0; red < 2 && rc == TDC_OK; red++) {
        const uint16_t gw = red ? rw : (uint16_t)m->w, gh = red ? rh : (uint16_t)m->h;
        const tdc_fov_params_t p = {gw * 128, gh * 128, st->q.alpha_q8, st->q.disk_q15, tdc_fov_lp_size(st->q.delta_q15, gw),
                                    tdc_fov_lp_size(st->q.delta_q15, gh), {0, 0}, TDC_FOV_KERNEL_LOG_POLAR, 0};
        tdc_fov_geom_t g;
        rc = tdc_fov_geom(&g, gw, gh, &p);
    }
    if (rc != TDC_OK) {
        tdc_sim_refuse(m, "fov-trm firmware (TRM, remap, grid geometry)", rc);
        return 0;
    }
    m->residual = fovtrm_residual;
    return 0;
}

static int fovtrm_frame(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    fovtrm_state_t *st = m->fam;
    const double dt = st->have_t ? t - st->last_t : m->fs;
    st->last_t = t;
    st->have_t = 1;
    const int e = m->eye, red = !tdc_trm_stereo_eye_is_full(lf, e);
    /* the slot's grid and its scale to the screen */
    const int gw = red ? m->link->rw : m->w, gh = red ? m->link->rh : m->h;
    const double sx = (double)m->w / gw, sy = (double)m->h / gh;
    /* where the tracker says the eye looks, on the grid (within a screen of
     * it: the link's rule) */
    double gz[2];
    tdc_sim_gaze_tracked(m->gaze, t, m->frame, e, gz);
    gz[0] = fmin(fmax(gz[0] / sx, -0.99 * gw), 1.99 * gw);
    gz[1] = fmin(fmax(gz[1] / sy, -0.99 * gh), 1.99 * gh);
    const tdc_fov_params_t p = {(int32_t)lround(gz[0] * 256),
                                (int32_t)lround(gz[1] * 256),
                                st->q.alpha_q8,
                                st->q.disk_q15,
                                tdc_fov_lp_size(st->q.delta_q15, (uint16_t)gw),
                                tdc_fov_lp_size(st->q.delta_q15, (uint16_t)gh),
                                {0, 0},
                                TDC_FOV_KERNEL_LOG_POLAR,
                                0};
    tdc_fov_geom_t g;
    int rc = tdc_fov_geom(&g, (uint16_t)gw, (uint16_t)gh, &p);
    if (tdc_sim_stage(m, "fov-trm geometry", rc)) {
        return rc;
    }
    /* the exact inverse of eq. 2.2 on the grid, then the grid's disk pixel
     * centres, each scaled to the screen */
    const ref_fov_params_t rp = {p.gaze_x_q8 / 256.0, p.gaze_y_q8 / 256.0, p.alpha_q8 / 256.0, p.disk_q15 / 32768.0,
                                 g.lp_w, g.lp_h, 0, 0, 0};
    ref_fov_geom_t rg;
    ref_fov_geom(&rg, gw, gh, &rp);
    /* the log-polar samples as fov places them (no TAA jitter here), with
     * their footprints for fov's prefilter, scaled from the grid to the screen */
    double *side = st->q.lod != TDC_FOV_LOD_OFF ? st->side : NULL;
    size_t k = ref_fov_lp_samples(&rg, g.u0, 0.0, 0.0, st->q.jitter, st->q.lod, st->xy, side);
    for (size_t q = 0; q < k; q++) {
        st->xy[2 * q] *= sx;
        st->xy[2 * q + 1] *= sy;
        if (side) {
            side[q] *= 0.5 * (sx + sy);
        }
    }
    const size_t nlp = k, nd = tdc_fov_disk_pixels(&g);
    /* a reduced disk pixel covers sx x sy screen pixels: its rays spread
     * over that footprint (a gr x gr grid of point samples, then TRM's
     * Gaussian resolve: resolve_reduced_disk), a full one is spp rays
     * within its pixel as in fov */
    const int gr = red ? tdc_sim_spp_grid(spp) : 1, sub = gr * gr;
    if (fovtrm_reserve(st, nlp + nd * (size_t)sub) != 0) {
        return tdc_sim_stage(m, "fov-trm sample buffers", TDC_ERR_SIZE);
    }
    for (int j = 0; j < gh; j++) {
        int32_t x0;
        const uint32_t span = tdc_fov_disk_span(&g, j, &x0);
        for (uint32_t i = 0; i < span; i++) {
            for (int b = 0; b < gr; b++) {
                for (int a = 0; a < gr; a++, k++) {
                    st->xy[2 * k] = (x0 + (int32_t)i + (red ? (a + 0.5) / gr : 0.5)) * sx;
                    st->xy[2 * k + 1] = (j + (red ? (b + 0.5) / gr : 0.5)) * sy;
                }
            }
        }
    }
    double t0 = tdc_sim_now();
    if (!red) {
        src->samples(src, t, (int)k, st->xy, spp, st->samp, NULL, dt, TDC_MV_SURFACE);
    } else {
        src->samples(src, t, (int)nlp, st->xy, spp, st->samp, NULL, dt, TDC_MV_SURFACE);
        src->samples(src, t, (int)(nd * (size_t)sub), st->xy + 2 * nlp, 1, st->sub, NULL, dt, TDC_MV_SURFACE);
        resolve_reduced_disk(st, src, &g, nlp, nd, sub, sx, sy);
    }
    if (side && tdc_sim_fov_prefilter(m, src, t, spp, st->xy, side, nlp, st->samp) != 0) {
        return tdc_sim_stage(m, "fov-trm prefilter (out of memory)", TDC_ERR_ARG);
    }
    m->res->rays += (uint64_t)(nlp + nd) * (uint64_t)(spp > 0 ? spp : 1); /* spp rays each, as every mode counts */
    m->res->render_s += tdc_sim_now() - t0;
    m->res->rendered++;
    /* over the link into the slot's buffers, then the remap over the slot's
     * picture and TRM as for a plain FULL / REDUCED packet */
    tdc_fov_hdr_t h;
    if (tdc_sim_link_foveated_slot(m->link, e, lf, red, &p, st->q.delta_q15, st->samp, NULL, &h) != 0) {
        return tdc_sim_stage(m, red ? "link FOVEATED packet (reduced slot)" : "link FOVEATED packet", TDC_ERR_ARG);
    }
    const uint32_t w3 = (uint32_t)m->w * 3u, gw3 = (uint32_t)gw * 3u;
    uint8_t *pic = red ? TDC_SIM_LINK_REDUCED_BUF(m) : TDC_SIM_LINK_FULL(m);
    t0 = tdc_sim_now();
    rc = tdc_sim_stage(m, "tdc_fov_trm_frame", tdc_fov_trm_frame(&st->fv, &h, red, m->link->fov_lp[e], pic, gw3));
    if (rc == 0) {
        rc = red ? tdc_sim_stage(m, "tdc_trm_reduced_seq", tdc_trm_reduced_seq(&st->trm, pic, gw3, m->wanted, w3, lf))
                 : tdc_sim_stage(m, "tdc_trm_full_seq", tdc_trm_full_seq(&st->trm, pic, gw3, m->wanted, w3, lf));
    }
    m->res->fw_s += tdc_sim_now() - t0;
    return rc;
}

static void fovtrm_reset(sim_mode_t *m)
{
    fovtrm_state_t *st = m->fam;
    if (st && m->res->available) {
        tdc_trm_reset(&st->trm);
        tdc_fov_trm_reset(&st->fv);
        st->have_t = 0;
    }
}

static void fovtrm_free(sim_mode_t *m)
{
    fovtrm_state_t *st = m->fam;
    if (st) {
        TDC_FREE_ALL(st->trm_mem, st->fv_mem, st->samp, st->xy, st->sub, st->lin, st->map, st->side, st);
    }
    m->fam = NULL;
}

const tdc_sim_family_t tdc_sim_family_fovtrm = {
    "fovtrm", k_modes, (int)(sizeof(k_modes) / sizeof(k_modes[0])), fovtrm_init, fovtrm_frame, fovtrm_reset, fovtrm_free,
};
