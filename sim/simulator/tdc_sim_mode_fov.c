/*
 * tdc_sim_mode_fov.c - foveated streams (issue 14, docs/design.md §4.5): the
 * renderer traces the kernel log-polar buffer (alpha, delta) and the
 * uniformly sampled foveal disk (a fraction of the distance to the farthest
 * corner) around the gaze the eye tracker reports; the packet goes over the
 * link as a FOVEATED packet (encoder -> firmware decoder); the controller
 * rebuilds the frame with the firmware stage tdc_fov (remap, radial blur,
 * disk blend) and, in fov-taa, peripheral TAA (thesis eqs. 4.7-4.10,
 * Halton(2,3) jitter of the log-polar samples, motion vectors sent).
 *
 * Parameters: tdc-sim --fov-alpha (4), --fov-delta (0.555), --fov-disk
 * (0.12443, the thesis's measured optimum); gaze and tracker:
 * tdc_sim_gaze.h (--gaze, --gaze-latency, --gaze-noise).
 *
 * Samples: a source with its own foveated mode (the Embree renderer) traces
 * them itself; the others (procedural scenes, photographs) are sampled at
 * the positions of the exact inverse of eq. 2.2 (ref/ref_fov.c) and the
 * disk pixel centres, spp rays each like the full-rate modes.  Rays are
 * counted exactly (samples x spp, or the renderer's count).
 *
 * fovlr / fovlr-taa: the log-rectilinear kind (firmware/tdc_fov_lr.h, Li et
 * al.), the same disk, link kind, stage entry and TAA.  The source renders
 * the whole frame at display resolution (spp rays per pixel, or the
 * renderer's full frame), the sender builds its summed-area table and
 * sends each texel as the area average of its footprint (in linear light,
 * encoded back with the source's gamma), the disk pixels from the same frame,
 * and with TAA each texel's vector is the one of the pixel under its
 * centre.  Foveal scale per axis: the default rule (k S(k) = n, one texel
 * per pixel at the gaze, ref/ref_fov_lr.c).  Rays: the full frame's.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_fov.h"
#include "simulator/tdc_sim_mode.h"
#include "tdc_fov.h"
#include "tdc_fov_link.h"
#include "tdc_fov_lr.h"
#include "tdc_sim_codes.h"
#include "tdc_free.h"

enum { FOV_PLAIN, FOV_TAA, FOVLR_PLAIN, FOVLR_TAA };
#define IS_LR(v) ((v) == FOVLR_PLAIN || (v) == FOVLR_TAA)
#define IS_TAA(v) ((v) == FOV_TAA || (v) == FOVLR_TAA)

#define F &tdc_sim_family_fov
#define L TDC_SIM_LINK_FOVEATED
static const tdc_mode_desc_t k_modes[] = {
    {"fov", F, FOV_PLAIN, L, 1, 1, 0, 0, 0,
     "kernel log-polar foveation (thesis), alpha 4, delta 0.555, 12.443 % disk, FOVEATED packets, firmware remap"},
    {"fov-taa", F, FOV_TAA, L, 1, 1, 0, 0, 0,
     "fov + peripheral TAA (thesis eqs. 4.7-4.10, phased out after the disk border), Halton jitter, vectors sent"},
    {"fovlr", F, FOVLR_PLAIN, L, 1, 1, 0, 0, 0,
     "log-rectilinear foveation (Li et al.): summed-area averages of a full-rate render, delta 0.555, same disk"},
    {"fovlr-taa", F, FOVLR_TAA, L, 1, 1, 0, 0, 0, "fovlr + the same peripheral TAA as fov-taa, vectors sent"},
};
#undef L
#undef F

typedef struct {
    tdc_fov_t st;
    void *arena;
    uint8_t *samp; /* samples in payload order */
    int16_t *smv;
    double *xy;
    tdc_fov_lr_t lr; /* log-rectilinear scratch (fovlr modes) */
    void *lr_arena;
    int16_t *pmv; /* the full frame's vectors (fovlr-taa) */
    double *side; /* the footprint of each log-polar sample, display pixels (ref_fov_lod_cone) */
    tdc_sim_fov_link_t q; /* the link header's parameters */
    double last_t;
    int have_t;
} fov_state_t;

tdc_sim_fov_link_t tdc_sim_fov_link_of(const tdc_sim_config_t *cfg)
{
    const tdc_sim_fov_link_t q = {
        .lod = cfg->fov_lod,
        .jitter = cfg->fov_jitter,
        .alpha_q8 = (uint16_t)lround(cfg->fov_alpha * 256.0),
        .delta_q15 = (uint16_t)ceil(cfg->fov_delta * 32768.0 - 1e-9),
        .disk_q15 = (uint16_t)lround(cfg->fov_disk * 32768.0),
    };
    return q;
}

static int fov_init(sim_mode_t *m, const tdc_sim_setup_t *s)
{
    const tdc_sim_config_t *cfg = s->cfg;
    m->res->foveated = 1;
    fov_state_t *st = calloc(1, sizeof *st);
    if (!st) {
        return -1;
    }
    m->fam = st;
    st->q = tdc_sim_fov_link_of(cfg);
    const tdc_fov_config_t fc = {(uint16_t)m->w, (uint16_t)m->h, (uint8_t)IS_TAA(m->d->variant)};
    const size_t n = tdc_fov_get_size(&fc);
    if (!n || !(cfg->fov_delta > 0 && cfg->fov_delta <= 1)) {
        tdc_sim_refuse(m, "fov init (size or delta)", TDC_ERR_SIZE);
        return 0;
    }
    st->arena = aligned_alloc(8, (n + 7) & ~(size_t)7);
    const size_t lpn = (size_t)tdc_fov_lp_size(st->q.delta_q15, (uint16_t)m->w) *
                       tdc_fov_lp_size(st->q.delta_q15, (uint16_t)m->h);
    st->samp = malloc((lpn + m->npx) * 3);
    st->smv = malloc((lpn + m->npx) * 2 * sizeof(int16_t));
    st->xy = malloc((lpn + m->npx) * 2 * sizeof(double));
    st->side = malloc((lpn ? lpn : 1) * sizeof(double));
    if (!st->arena || !st->samp || !st->smv || !st->xy || !st->side) {
        return -1;
    }
    int rc = tdc_fov_init(&st->st, &fc, st->arena, n);
    if (rc != TDC_OK) {
        tdc_sim_refuse(m, "fov init", rc);
        return 0;
    }
    if (IS_LR(m->d->variant)) {
        const size_t ln = tdc_fov_lr_get_size((uint16_t)m->w);
        st->lr_arena = aligned_alloc(8, (ln + 7) & ~(size_t)7);
        st->pmv = malloc(m->npx * 2 * sizeof(int16_t));
        if (!st->lr_arena || !st->pmv) {
            return -1;
        }
        rc = tdc_fov_lr_init(&st->lr, (uint16_t)m->w, st->lr_arena, ln);
        if (rc == TDC_OK) {
            rc = tdc_fov_lr_attach(&st->st, &st->lr);
        }
        if (rc != TDC_OK) {
            tdc_sim_refuse(m, "fovlr init", rc);
        }
    }
    return 0;
}

/* fovlr: the area-averaged log-rectilinear buffer of a full-rate render and
 * the disk pixels of the same render, in payload order (st->samp, st->smv). */
static void lr_samples(sim_mode_t *m, fov_state_t *st, tdc_source_t *src, const tdc_fov_params_t *p,
                       const tdc_fov_geom_t *g, double t, double dt, int spp, int taa)
{
    tdc_sim_render_full(m, src, t, spp, 0.0, 0.0, taa ? st->pmv : NULL, dt, TDC_MV_SURFACE);
    const double t0 = tdc_sim_now();
    ref_fov_lr_axis_t ax, ay;
    ref_fov_lr_axis(&ax, p->gaze_x_q8 / 256.0, p->lr_k_q4[0] / 16.0, m->w, g->lp_w);
    ref_fov_lr_axis(&ay, p->gaze_y_q8 / 256.0, p->lr_k_q4[1] / 16.0, m->h, g->lp_h);
    double lut[3 * 256]; /* averages in linear light, encoded back as the source encodes */
    ref_fov_lin_lut(src->gamma, lut);
    double *sat = ref_fov_lr_sat(m->render, (size_t)m->w * 3, m->w, m->h, lut);
    if (sat) {
        ref_fov_lr_buffer(sat, m->w, m->h, &ax, &ay, st->samp, (size_t)g->lp_w * 3, NULL, src->gamma);
        free(sat);
    }
    size_t k = (size_t)g->lp_w * g->lp_h;
    if (taa) { /* each texel's vector: the pixel under its centre */
        for (int j = 0; j < g->lp_h; j++) {
            const int y = (int)fmin(fmax(floor(ref_fov_lr_inv(&ay, j + 0.5)), 0), m->h - 1);
            for (int i = 0; i < g->lp_w; i++) {
                const int x = (int)fmin(fmax(floor(ref_fov_lr_inv(&ax, i + 0.5)), 0), m->w - 1);
                memcpy(st->smv + 2 * ((size_t)j * g->lp_w + i), st->pmv + 2 * ((size_t)y * m->w + x),
                       2 * sizeof(int16_t));
            }
        }
    }
    for (int j = 0; j < m->h; j++) {
        int32_t x0;
        const uint32_t span = tdc_fov_disk_span(g, j, &x0);
        memcpy(st->samp + 3 * k, m->render + 3 * ((size_t)j * m->w + (size_t)x0), 3 * (size_t)span);
        k += span;
    }
    m->res->render_s += tdc_sim_now() - t0; /* the sender's summed-area pass */
}

/* The footprint prefilter of the photograph and procedural sources (the
 * Embree renderer's texture LOD does it in its own FOVEATED mode): each of
 * the nlp log-polar samples in samp becomes the mean linear light of the
 * picture over the square of side side[k] display pixels centred on its
 * position xy[2k..] (ref_fov_lr_box_mean: a summed-area table, bilinear inside each
 * pixel, so the box moves continuously with the jittered position), encoded
 * as the source encodes.  The picture: the source at every pixel centre,
 * spp rays each, as full rate renders it.  It stands for a texture's
 * prefiltered pyramid, which a renderer builds once per texture: its time
 * is the render time's, its evaluations are not rays (the primary rays are
 * the samples' own, counted by the caller).  Disk samples are left alone.
 * Shared with fov-trm (tdc_sim_mode.h). */
int tdc_sim_fov_prefilter(sim_mode_t *m, tdc_source_t *src, double t, int spp, const double *xy, const double *side,
                          size_t nlp, uint8_t *samp)
{
    if (!(src->frame && src->frame(src, t, 0.0, 0.0, spp, m->render, m->scratch) == 0)) {
        for (int y = 0; y < m->h; y++) {
            for (int x = 0; x < m->w; x++) {
                m->xy[2 * ((size_t)y * m->w + x)] = x + 0.5;
                m->xy[2 * ((size_t)y * m->w + x) + 1] = y + 0.5;
            }
        }
        src->samples(src, t, (int)m->npx, m->xy, spp, m->render, NULL, 0.0, TDC_MV_SURFACE);
    }
    double lut[3 * 256];
    ref_fov_lin_lut(src->gamma, lut);
    double *sat = ref_fov_lr_sat(m->render, (size_t)m->w * 3, m->w, m->h, lut);
    if (!sat) {
        return -1;
    }
    for (size_t k = 0; k < nlp; k++) {
        double c[3];
        ref_fov_lr_box_mean(sat, m->w, m->h, xy[2 * k], xy[2 * k + 1], side[k], c);
        for (int ch = 0; ch < 3; ch++) {
            samp[3 * k + ch] = tdc_sim_encode_code(c[ch], src->gamma[ch]);
        }
    }
    free(sat);
    return 0;
}

static int fov_frame(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    fov_state_t *st = m->fam;
    const int taa = IS_TAA(m->d->variant), lr = IS_LR(m->d->variant);
    const double dt = st->have_t ? t - st->last_t : m->fs;
    st->last_t = t;
    st->have_t = 1;
    /* where the tracker says the eye looks (within a screen of it: the link's rule) */
    double gz[2];
    tdc_sim_gaze_tracked(m->gaze, t, m->frame, m->eye, gz);
    gz[0] = fmin(fmax(gz[0], -0.99 * m->w), 1.99 * m->w);
    gz[1] = fmin(fmax(gz[1], -0.99 * m->h), 1.99 * m->h);
    tdc_fov_params_t p = {(int32_t)lround(gz[0] * 256),
                          (int32_t)lround(gz[1] * 256),
                          st->q.alpha_q8,
                          st->q.disk_q15,
                          tdc_fov_lp_size(st->q.delta_q15, (uint16_t)m->w),
                          tdc_fov_lp_size(st->q.delta_q15, (uint16_t)m->h),
                          {0, 0},
                          TDC_FOV_KERNEL_LOG_POLAR,
                          0};
    if (lr) { /* the default foveal scale per axis, Q4 as the header carries it */
        p.alpha_q8 = 256;
        p.transform = TDC_FOV_LOG_RECT;
        p.lr_k_q4[0] = (uint16_t)lround(16 * ref_fov_lr_k(m->w, p.lp_w, p.gaze_x_q8 / 256.0));
        p.lr_k_q4[1] = (uint16_t)lround(16 * ref_fov_lr_k(m->h, p.lp_h, p.gaze_y_q8 / 256.0));
    }
    tdc_fov_geom_t g;
    int rc = tdc_fov_geom(&g, (uint16_t)m->w, (uint16_t)m->h, &p);
    if (tdc_sim_stage(m, "fov geometry", rc)) {
        return rc;
    }
    double jx = 0, jy = 0;
    if (taa && !lr) { /* Halton(2,3) jitter of the log-polar samples (thesis §4.3.2; how far: st->q.jitter) */
        ref_fov_halton(m->frame, &jx, &jy);
    }
    const size_t nlp = (size_t)(g.lp_w - g.u0) * g.lp_h, n = nlp + tdc_fov_disk_pixels(&g);
    double t0 = tdc_sim_now();
    if (lr) {
        lr_samples(m, st, src, &p, &g, t, dt, spp, taa);
    } else if (src->foveated) {
        const tdc_fov_sampling_t fs = {p.gaze_x_q8 / 256.0, p.gaze_y_q8 / 256.0, p.alpha_q8 / 256.0,
                                       st->q.delta_q15 / 32768.0, p.disk_q15 / 32768.0, jx, jy, st->q.jitter};
        uint64_t rays = 0;
        rc = src->foveated(src, &fs, t, dt, st->samp, taa ? st->smv : NULL, &rays);
        if (tdc_sim_stage(m, "renderer (foveated frame)", rc ? TDC_ERR_ARG : TDC_OK)) {
            return TDC_ERR_ARG;
        }
        m->res->rays += rays;
    } else {
        /* the exact inverse of eq. 2.2 for the log-polar samples, then the disk pixel centres */
        const ref_fov_params_t rp = {p.gaze_x_q8 / 256.0, p.gaze_y_q8 / 256.0, p.alpha_q8 / 256.0,
                                     p.disk_q15 / 32768.0, g.lp_w, g.lp_h, 0, 0, 0};
        ref_fov_geom_t rg;
        ref_fov_geom(&rg, m->w, m->h, &rp);
        const int lod = st->q.lod;
        double *side = lod != TDC_FOV_LOD_OFF ? st->side : NULL;
        size_t k = ref_fov_lp_samples(&rg, g.u0, jx, jy, st->q.jitter, lod, st->xy, side);
        for (int j = 0; j < m->h; j++) {
            int32_t x0;
            const uint32_t span = tdc_fov_disk_span(&g, j, &x0);
            for (uint32_t i = 0; i < span; i++, k++) {
                st->xy[2 * k] = x0 + (int32_t)i + 0.5;
                st->xy[2 * k + 1] = j + 0.5;
            }
        }
        src->samples(src, t, (int)n, st->xy, spp, st->samp, taa ? st->smv : NULL, dt, TDC_MV_SURFACE);
        if (lod != TDC_FOV_LOD_OFF && tdc_sim_fov_prefilter(m, src, t, spp, st->xy, st->side, nlp, st->samp) != 0) {
            return tdc_sim_stage(m, "fov prefilter (out of memory)", TDC_ERR_ARG);
        }
        m->res->rays += (uint64_t)n * (uint64_t)(spp > 0 ? spp : 1);
    }
    if (!lr) { /* (tdc_sim_render_full counted the fovlr render) */
        m->res->render_s += tdc_sim_now() - t0;
        m->res->rendered++;
    }
    /* over the link: the decoder checks and unpacks (disk into its full
     * buffer, the rest into the log-polar buffers) */
    tdc_fov_hdr_t h;
    if (tdc_sim_link_foveated(m->link, m->eye, lf, &p, st->q.delta_q15, st->samp, taa ? st->smv : NULL, &h) != 0) {
        return tdc_sim_stage(m, "link FOVEATED packet", TDC_ERR_ARG);
    }
    t0 = tdc_sim_now();
    const int e = m->eye;
    rc = tdc_fov_frame(&st->st, &h.p, m->link->fov_lp[e], (size_t)h.p.lp_w * 3, taa ? m->link->fov_mv[e] : NULL,
                       (size_t)h.p.lp_w * 2, m->link->full[e], (size_t)m->w * 3, (uint32_t)lround(dt * 1e6), m->wanted,
                       (size_t)m->w * 3);
    m->res->fw_s += tdc_sim_now() - t0;
    return tdc_sim_stage(m, "fov frame", rc);
}

static void fov_reset(sim_mode_t *m)
{
    fov_state_t *st = m->fam;
    if (st) {
        tdc_fov_reset(&st->st);
        st->have_t = 0;
    }
}

static void fov_free(sim_mode_t *m)
{
    fov_state_t *st = m->fam;
    if (st) {
        TDC_FREE_ALL(st->arena, st->samp, st->smv, st->xy, st->side, st->lr_arena, st->pmv, st);
    }
    m->fam = NULL;
}

const tdc_sim_family_t tdc_sim_family_fov = {
    "fov", k_modes, (int)(sizeof(k_modes) / sizeof(k_modes[0])), fov_init, fov_frame, fov_reset, fov_free,
};
