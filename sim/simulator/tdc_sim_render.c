/* tdc_sim_render.c - Embree renderer behind the simulator's source interface. */
#include "simulator/tdc_sim_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


#include "render/tdc_render.h"
#include "render/tdc_scene.h"
#include "tdc_layer_link.h"
#include "tdc_free.h"

#define RS_SLOTS 64 /* one per mode of a run (tdc-sim takes up to 64) */

typedef struct {
    tdc_render_t *r;
    tdc_scene_t *scene; /* kept to open per-mode subframe renderers */
    tdc_render_config_t cfg;
    tdc_render_t *sub[RS_SLOTS]; /* subframe renderers (own MV history, orderings) */
    tdc_render_t *red[RS_SLOTS]; /* reduced-frame renderers (own r, supersampling, resolve) */
    float *sub_lin;
    int16_t *sub_mv, *sub_mvs, *sub_mvd;
    /* layer outputs of a subframe (rs_layered) */
    float *l_shade, *l_vis, *l_refl, *l_w;
    int16_t *l_mvsurf, *l_mvrefl;
    uint8_t *l_src;
    tdc_render_t *fov;  /* the FOVEATED renderer (samples, not pixels: its own instance) */
    float *fov_lin;     /* up to 2 W H samples (the log-polar buffer + the disk) */
    int16_t *fov_mv;
    int clock_hz;
    float *lin; /* W*H*3 */
    int16_t *mv;
    double *gt; /* cached ground truth */
    long gt_frame;
    long v_frame;
    double v[2];
    long f0; /* scene frame of run time 0 (tdc_sim_render_options) */
} rsrc_t;

/* A renderer vector (in pixels per renderer frame) scaled by k to the
 * source's time step, rounded and clamped to the link's int16 range; a
 * linear renderer value coded with the source gamma (clamped to [0, 1]).
 * Every output path of this source uses these two. */
static int16_t rs_scale_mv(int16_t v, double k)
{
    double q = floor(v * k + 0.5);
    return (int16_t)(q > 32767 ? 32767 : (q < -32767 ? -32767 : q));
}

static uint8_t rs_code(float v, double gamma)
{
    double l = v < 0.0f ? 0.0 : (v > 1.0f ? 1.0 : (double)v);
    return (uint8_t)(255.0 * pow(l, 1.0 / gamma) + 0.5);
}

/* A render output with the colour (and, when mv is not NULL, motion-vector)
 * buffers set and every other output off. */
static tdc_render_out_t rs_out(float *rgb, int16_t *mv)
{
    tdc_render_out_t out;
    memset(&out, 0, sizeof(out));
    out.rgb = rgb;
    out.mv = mv;
    return out;
}

static long frame_of(const rsrc_t *c, double t)
{
    double f = floor(t * c->clock_hz + 1e-9);
    return (f < 0 ? 0 : (long)f) + c->f0;
}

static void rs_pursuit(tdc_source_t *s, double t, double v[2])
{
    rsrc_t *c = s->ctx;
    long f = frame_of(c, t);
    if (f != c->v_frame) {
        tdc_render_probe_t p;
        memset(&p, 0, sizeof(p));
        c->v[0] = c->v[1] = 0.0;
        if (tdc_render_probe(c->r, (uint32_t)(f < 1 ? 1 : f), s->width * 0.5, s->height * 0.5, &p) == 0 && p.hit) {
            /* a glossy hit's MV is one stochastic sample of eq. 5 (a
             * different one per seed, up to tens of px): the eye follows
             * its centre, the previous virtual image (= the MV at mirrors) */
            const int gl = p.refl_mv_ok && p.mv[0] == p.refl_mv[0] && p.mv[1] == p.refl_mv[1];
            c->v[0] = -(gl ? p.refl_mu[0] : p.mv[0]) * c->clock_hz;
            c->v[1] = -(gl ? p.refl_mu[1] : p.mv[1]) * c->clock_hz;
        }
        c->v_frame = f;
    }
    v[0] = c->v[0];
    v[1] = c->v[1];
}

static int rs_full(tdc_source_t *s, double t, double dt, uint8_t *rgb, int16_t *mv, uint64_t *rays, double *ms)
{
    rsrc_t *c = s->ctx;
    long f = frame_of(c, t);
    tdc_render_out_t out = rs_out(c->lin, mv ? c->mv : NULL);
    tdc_render_stats_t st;
    if (tdc_render_frame(c->r, (uint32_t)f, TDC_RENDER_FULL, &out, &st) != 0) {
        return -1;
    }
    size_t n = (size_t)s->width * s->height;
    for (size_t i = 0; i < 3 * n; i++) {
        rgb[i] = rs_code(c->lin[i], s->gamma[i % 3]);
    }
    if (mv) {
        /* renderer MVs span one clock frame; scale to dt */
        double k = dt * c->clock_hz;
        for (size_t i = 0; i < 2 * n; i++) {
            mv[i] = rs_scale_mv(c->mv[i], k);
        }
    }
    *rays = st.rays[TDC_RAY_PRIMARY];
    *ms = st.wall_ms;
    return 0;
}

void tdc_sim_render_options(tdc_source_t *s, long start_frame, int reflect_mv, int fov_lod, uint32_t seed)
{
    rsrc_t *c = s->ctx;
    c->f0 = start_frame;
    c->cfg.reflect_mv = reflect_mv ? 1 : 0;
    tdc_render_set_reflect_mv(c->r, c->cfg.reflect_mv);
    c->cfg.fov_lod = fov_lod;
    tdc_render_set_fov_lod(c->r, fov_lod);
    /* the per-mode renderers (rs_slot) open later from c->cfg */
    c->cfg.seed = seed;
    tdc_render_set_seed(c->r, seed);
    c->gt_frame = -1;
}

static void rs_jitter(tdc_source_t *s, double jx, double jy)
{
    tdc_render_set_jitter(((rsrc_t *)s->ctx)->r, jx, jy);
}

static void rs_ground_truth(tdc_source_t *s, double t, double ox, double oy, double *lin)
{
    rsrc_t *c = s->ctx;
    long f = frame_of(c, t);
    int w = s->width, h = s->height;
    if (f != c->gt_frame) {
        tdc_render_out_t out = rs_out(c->lin, NULL);
        tdc_render_stats_t st;
        tdc_render_frame(c->r, (uint32_t)f, TDC_RENDER_GROUND_TRUTH, &out, &st);
        for (size_t i = 0; i < 3 * (size_t)w * h; i++) {
            c->gt[i] = c->lin[i] < 0.0f ? 0.0 : (c->lin[i] > 1.0f ? 1.0 : (double)c->lin[i]);
        }
        c->gt_frame = f;
    }
    /* the frame shows time f / clock: content tracked at v moved by
     * v (t - f/clock) since */
    double v[2];
    rs_pursuit(s, t, v);
    double dtf = t - (double)(f - c->f0) / c->clock_hz;
    ox -= v[0] * dtf;
    oy -= v[1] * dtf;
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double sx = x + ox, sy = y + oy;
            sx = sx < 0 ? 0 : (sx > w - 1 ? w - 1 : sx);
            sy = sy < 0 ? 0 : (sy > h - 1 ? h - 1 : sy);
            int x0 = (int)sx, y0 = (int)sy, x1 = x0 + 1 < w ? x0 + 1 : x0, y1 = y0 + 1 < h ? y0 + 1 : y0;
            double fx = sx - x0, fy = sy - y0;
            for (int k = 0; k < 3; k++) {
                double a = c->gt[3 * ((size_t)y0 * w + x0) + k], b = c->gt[3 * ((size_t)y0 * w + x1) + k];
                double d = c->gt[3 * ((size_t)y1 * w + x0) + k], e = c->gt[3 * ((size_t)y1 * w + x1) + k];
                lin[3 * ((size_t)y * w + x) + k] = (a + (b - a) * fx) * (1 - fy) + (d + (e - d) * fx) * fy;
            }
        }
    }
}

/* Pixel-centre samples from full frames (used only where a mode needs
 * arbitrary positions; the frame path is preferred). */
static void rs_samples(tdc_source_t *s, double t, int n, const double *xy, int spp, uint8_t *rgb, int16_t *mv,
                       double dt, tdc_mv_kind_t kind)
{
    (void)spp;
    (void)kind;
    rsrc_t *c = s->ctx;
    size_t np = (size_t)s->width * s->height;
    uint8_t *full = malloc(np * 3);
    int16_t *fmv = malloc(np * 2 * sizeof(int16_t));
    uint64_t rays;
    double ms;
    if (!full || !fmv || rs_full(s, t, dt, full, fmv, &rays, &ms) != 0) {
        memset(rgb, 0, (size_t)n * 3);
    } else {
        for (int i = 0; i < n; i++) {
            int x = (int)xy[2 * i], y = (int)xy[2 * i + 1];
            x = x < 0 ? 0 : (x >= s->width ? s->width - 1 : x);
            y = y < 0 ? 0 : (y >= s->height ? s->height - 1 : y);
            size_t p = (size_t)y * s->width + x;
            memcpy(rgb + 3 * i, full + 3 * p, 3);
            if (mv) {
                mv[2 * i] = fmv[2 * p];
                mv[2 * i + 1] = fmv[2 * p + 1];
            }
        }
    }
    (void)c;
    free(full);
    free(fmv);
}

/* The subframe renderer of one mode's slot, opened on first use with the
 * given vector passes (its MV history and orderings are the mode's own);
 * then the subframe's frame index at t, or -1 (bad slot, open failed, or t
 * not at subframe `frame` of the renderer's 4-cycle). */
/* Renderer `slot` of a per-mode set (set[RS_SLOTS]), opened with cfg on
 * first use; NULL for a bad slot or when the open failed. */
static tdc_render_t *rs_slot(rsrc_t *c, tdc_render_t **set, int slot, const tdc_render_config_t *cfg)
{
    if (slot < 0 || slot >= RS_SLOTS) {
        return NULL;
    }
    if (!set[slot]) {
        char err[256];
        set[slot] = tdc_render_open(c->scene, cfg, err, sizeof(err));
    }
    return set[slot];
}

static long rs_sub_frame(rsrc_t *c, int slot, int shadow_mv, int dual_mv, uint32_t frame, double t)
{
    tdc_render_config_t cfg = c->cfg;
    cfg.shadow_mv = shadow_mv;
    cfg.dual_mv = dual_mv;
    if (!rs_slot(c, c->sub, slot, &cfg)) {
        return -1;
    }
    const long f = frame_of(c, t);
    return (uint32_t)f % 4u == frame % 4u ? f : -1; /* the renderer's cycle follows its frame index */
}

static int rs_subframe(tdc_source_t *s, int slot, int shadow, uint32_t frame, double t, double dt, uint8_t *samples,
                       int16_t *mv, uint8_t *pattern, uint64_t *rays)
{
    rsrc_t *c = s->ctx;
    const long f = rs_sub_frame(c, slot, shadow ? 1 : 0, shadow ? 1 : 0, frame, t);
    if (f < 0) {
        return -1;
    }
    tdc_render_out_t out = rs_out(c->sub_lin, c->sub_mv);
    if (shadow) {
        out.mv_shadow = c->sub_mvs;
        out.mv_dual = c->sub_mvd;
    }
    tdc_render_stats_t st;
    if (tdc_render_frame(c->sub[slot], (uint32_t)f, TDC_RENDER_SUBFRAME, &out, &st) != 0) {
        return -1;
    }
    size_t n = (size_t)st.out_w * st.out_h;
    for (size_t i = 0; i < 3 * n; i++) {
        samples[i] = rs_code(c->sub_lin[i], s->gamma[i % 3]);
    }
    double k = dt * c->clock_hz;
    for (size_t i = 0; i < n; i++) {
        const int16_t *src = c->sub_mv + 2 * i;
        if (shadow) {
            /* shadow MV where the sample is in a tracked shadow, else the
             * dual MV where it was disoccluded, else the surface MV */
            if (c->sub_mvs[2 * i] != src[0] || c->sub_mvs[2 * i + 1] != src[1]) {
                src = c->sub_mvs + 2 * i;
            } else if (c->sub_mvd[2 * i] != src[0] || c->sub_mvd[2 * i + 1] != src[1]) {
                src = c->sub_mvd + 2 * i;
            }
        }
        for (int j = 0; j < 2; j++) {
            mv[2 * i + j] = rs_scale_mv(src[j], k);
        }
    }
    memcpy(pattern, tdc_render_pattern_bits(c->sub[slot]), ((size_t)n + 7) / 8);
    *rays = st.rays[TDC_RAY_PRIMARY];
    return 0;
}

static int rs_reduced(tdc_source_t *s, int slot, double t, double r, int ss, double sigma, int rw, int rh, uint8_t *rgb,
                      uint64_t *rays)
{
    rsrc_t *c = s->ctx;
    tdc_render_config_t cfg = c->cfg;
    cfg.reduced_factor = r;
    cfg.reduced_ss = ss;
    cfg.reduced_sigma = sigma;
    for (int k = 0; k < 3; k++) {
        cfg.reduced_gamma[k] = s->gamma[k]; /* resolve the codes the link carries, as D does */
    }
    if (!rs_slot(c, c->red, slot, &cfg)) {
        return -1;
    }
    int ow, oh;
    tdc_render_output_size(c->red[slot], TDC_RENDER_REDUCED, &ow, &oh);
    if (ow != rw || oh != rh) {
        return -1; /* the link's reduced size (TDC_REDUCED_DIM) rounds otherwise */
    }
    if (!rgb) {
        return 0; /* prepared: the renderer is open (its BVH build is not a frame's cost) */
    }
    tdc_render_out_t out = rs_out(c->lin, NULL); /* W x H floats: room for the reduced frame */
    tdc_render_stats_t st;
    if (tdc_render_frame(c->red[slot], (uint32_t)frame_of(c, t), TDC_RENDER_REDUCED, &out, &st) != 0) {
        return -1;
    }
    for (size_t i = 0; i < 3 * (size_t)rw * rh; i++) {
        rgb[i] = rs_code(c->lin[i], s->gamma[i % 3]);
    }
    *rays = st.rays[TDC_RAY_PRIMARY];
    return 0;
}

static int rs_foveated(tdc_source_t *s, const tdc_fov_sampling_t *f, double t, double dt, uint8_t *rgb, int16_t *mv,
                       uint64_t *rays)
{
    rsrc_t *c = s->ctx;
    const size_t cap = 2 * (size_t)s->width * s->height;
    if (!c->fov) {
        char err[256];
        c->fov = tdc_render_open(c->scene, &c->cfg, err, sizeof(err));
        c->fov_lin = malloc(sizeof(float) * 3 * cap);
        c->fov_mv = malloc(sizeof(int16_t) * 2 * cap);
        if (!c->fov || !c->fov_lin || !c->fov_mv) {
            return -1;
        }
    }
    const tdc_render_fov_t rf = {f->gaze_x, f->gaze_y, f->alpha, f->delta, f->disk, f->jx, f->jy, f->jitter};
    int nlp = 0, nd = 0;
    if (tdc_render_set_foveation(c->fov, &rf, &nlp, &nd) != 0 || (size_t)nlp + (size_t)nd > cap) {
        return -1;
    }
    tdc_render_out_t out = rs_out(c->fov_lin, mv ? c->fov_mv : NULL);
    tdc_render_stats_t st;
    if (tdc_render_frame(c->fov, (uint32_t)frame_of(c, t), TDC_RENDER_FOVEATED, &out, &st) != 0) {
        return -1;
    }
    const size_t n = (size_t)nlp + (size_t)nd;
    for (size_t i = 0; i < 3 * n; i++) {
        rgb[i] = rs_code(c->fov_lin[i], s->gamma[i % 3]);
    }
    if (mv) {
        double k = dt * c->clock_hz; /* renderer MVs span one clock frame */
        for (size_t i = 0; i < 2 * n; i++) {
            mv[i] = rs_scale_mv(c->fov_mv[i], k);
        }
    }
    *rays = st.rays[TDC_RAY_PRIMARY];
    return 0;
}

static int rs_cut(tdc_source_t *s, double t0, double t1)
{
    (void)s;
    (void)t0;
    (void)t1;
    return 0;
}

/* Layered subframe (tdc_source_t.layered_subframe, issue 16): the
 * renderer's layer outputs of a SUBFRAME (its own adaptive orderings) as
 * SHADING (shade, mv_surf), VISIBILITY (vis; zeng: mv_shadow, which is the
 * surface vector outside tracked shadows, and the eq. 4 weight as falloff)
 * and GLOSSY (refl; zeng: mv_refl, the mirror / stochastic glossy vector)
 * planes.  Codes with the source gamma; vectors scaled from the renderer's
 * frame to dt like rs_subframe. */
static int rs_layered(tdc_source_t *s, int slot, int zeng, uint32_t frame, double t, double dt,
                      struct tdc_layer_frame *lf, uint8_t *pattern, uint64_t *rays)
{
    rsrc_t *c = s->ctx;
    /* the layers need the shadow vectors and weights either way */
    const long f = rs_sub_frame(c, slot, 1, 0, frame, t);
    if (f < 0) {
        return -1;
    }
    tdc_render_out_t out = rs_out(c->sub_lin, c->sub_mv);
    out.mv_shadow = c->sub_mvs;
    out.shadow_weight = c->l_w;
    out.shade = c->l_shade;
    out.vis = c->l_vis;
    out.refl = c->l_refl;
    out.mv_surf = c->l_mvsurf;
    out.mv_refl = c->l_mvrefl;
    out.shadow_src = c->l_src;
    tdc_render_stats_t st;
    if (tdc_render_frame(c->sub[slot], (uint32_t)f, TDC_RENDER_SUBFRAME, &out, &st) != 0) {
        return -1;
    }
    const size_t n = (size_t)st.out_w * st.out_h;
    const double k = dt * c->clock_hz;
    int glossy = 0;
    for (size_t i = 0; i < 3 * n && !glossy; i++) {
        glossy = c->l_refl[i] > 0.0f;
    }
    for (size_t i = 0; i < n; i++) {
        for (int j = 0; j < 3; j++) {
            lf->value[0][3 * i + j] = rs_code(c->l_shade[3 * i + j], s->gamma[j]);
            lf->value[2][3 * i + j] = rs_code(c->l_refl[3 * i + j], s->gamma[j]);
        }
        const double v = c->l_vis[i] < 0.0f ? 0.0 : (c->l_vis[i] > 1.0f ? 1.0 : (double)c->l_vis[i]);
        lf->value[1][i] = (uint8_t)(255.0 * v + 0.5);
        const int16_t *vs = zeng ? c->sub_mvs + 2 * i : c->l_mvsurf + 2 * i;
        const int16_t *vg = zeng ? c->l_mvrefl + 2 * i : c->l_mvsurf + 2 * i;
        for (int j = 0; j < 2; j++) {
            lf->mv[0][2 * i + j] = rs_scale_mv(c->l_mvsurf[2 * i + j], k);
            lf->mv[1][2 * i + j] = rs_scale_mv(vs[j], k);
            lf->mv[2][2 * i + j] = rs_scale_mv(vg[j], k);
        }
        const double g = c->l_src[i] ? (double)c->l_w[i] : 1.0;
        lf->falloff[i] = (uint16_t)(g <= 0.0 ? 0 : (g >= 1.0 ? 32768 : (int)(g * 32768.0 + 0.5)));
    }
    lf->present = (uint16_t)(TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING) | TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY) |
                             TDC_LAYER_PKT_FALLOFF | (glossy ? TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY) : 0u));
    memset(&lf->hdr, 0, sizeof(lf->hdr));
    lf->hdr.version = TDC_LAYER_LAYOUT_VERSION;
    lf->hdr.count = (uint8_t)(glossy ? 3 : 2);
    lf->hdr.type[0] = TDC_LAYER_SHADING;
    lf->hdr.mv_kind[0] = TDC_LAYER_MV_SURFACE;
    lf->hdr.type[1] = TDC_LAYER_VISIBILITY;
    lf->hdr.mv_kind[1] = zeng ? TDC_LAYER_MV_SHADOW : TDC_LAYER_MV_SURFACE;
    if (glossy) {
        lf->hdr.type[2] = TDC_LAYER_GLOSSY;
        lf->hdr.mv_kind[2] = zeng ? TDC_LAYER_MV_GLOSSY : TDC_LAYER_MV_SURFACE;
    }
    lf->hdr.flags = 1;
    lf->hdr.tiles_x = (uint16_t)((s->width + 1) / 2);
    lf->hdr.tiles_y = (uint16_t)((s->height + 1) / 2);
    memcpy(pattern, tdc_render_pattern_bits(c->sub[slot]), ((size_t)n + 7) / 8);
    *rays = st.rays[TDC_RAY_PRIMARY];
    return 0;
}

static void rs_destroy(tdc_source_t *s)
{
    if (!s) {
        return;
    }
    rsrc_t *c = s->ctx;
    if (c) {
        tdc_render_close(c->r);
        if (c->fov) {
            tdc_render_close(c->fov);
        }
        free(c->fov_lin);
        free(c->fov_mv);
        for (int i = 0; i < RS_SLOTS; i++) {
            if (c->sub[i]) {
                tdc_render_close(c->sub[i]);
            }
            if (c->red[i]) {
                tdc_render_close(c->red[i]);
            }
        }
        TDC_FREE_ALL(c->scene, c->sub_lin, c->sub_mv, c->sub_mvs, c->sub_mvd, c->l_shade, c->l_vis, c->l_refl,
                     c->l_w, c->l_mvsurf, c->l_mvrefl, c->l_src, c->lin, c->mv, c->gt, c);
    }
    free(s);
}

tdc_source_t *tdc_sim_render_source(const char *name, int w, int h, int clock_hz, int gt_samples, int threads,
                                    double eye_x, char *err, size_t errlen)
{
    tdc_scene_t *sc = malloc(sizeof(*sc));
    if (!sc) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    tdc_scene_status_t st = tdc_scene_builtin(name, sc, err, errlen);
    if (st == TDC_SCENE_ERR_UNKNOWN) {
        st = tdc_scene_load(name, sc, err, errlen);
    }
    if (st != TDC_SCENE_OK) {
        free(sc);
        return NULL;
    }
    sc->fps = clock_hz;
    /* this eye's camera: every key moved by eye_x along the camera's right
     * vector (yaw 0 looks along -Z, +yaw turns toward +X: right = (cos yaw,
     * 0, sin yaw)); the stereo pair's interpupillary offset */
    for (int k = 0; k < sc->ncamkeys; k++) {
        sc->cam[k].pos[0] += eye_x * cos(sc->cam[k].yaw);
        sc->cam[k].pos[2] += eye_x * sin(sc->cam[k].yaw);
    }
    tdc_render_config_t cfg;
    tdc_render_default_config(&cfg);
    cfg.width = w;
    cfg.height = h;
    cfg.threads = threads > 0 ? threads : 2;
    cfg.gt_samples = gt_samples > 0 ? gt_samples : 16;
    tdc_source_t *s = calloc(1, sizeof(*s));
    rsrc_t *c = calloc(1, sizeof(*c));
    if (!s || !c) {
        free(sc);
        free(s);
        free(c);
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    c->r = tdc_render_open(sc, &cfg, err, errlen);
    if (!c->r) {
        free(sc);
        free(s);
        free(c);
        return NULL;
    }
    c->scene = sc;
    c->cfg = cfg;
    size_t tiles = (size_t)((w + 1) / 2) * ((h + 1) / 2);
    c->sub_lin = malloc(sizeof(float) * 3 * tiles);
    c->sub_mv = malloc(sizeof(int16_t) * 2 * tiles);
    c->sub_mvs = malloc(sizeof(int16_t) * 2 * tiles);
    c->sub_mvd = malloc(sizeof(int16_t) * 2 * tiles);
    c->l_shade = malloc(sizeof(float) * 3 * tiles);
    c->l_vis = malloc(sizeof(float) * tiles);
    c->l_refl = malloc(sizeof(float) * 3 * tiles);
    c->l_w = malloc(sizeof(float) * tiles);
    c->l_mvsurf = malloc(sizeof(int16_t) * 2 * tiles);
    c->l_mvrefl = malloc(sizeof(int16_t) * 2 * tiles);
    c->l_src = malloc(tiles);
    c->clock_hz = clock_hz;
    c->lin = malloc(sizeof(float) * 3 * (size_t)w * h);
    c->mv = malloc(sizeof(int16_t) * 2 * (size_t)w * h);
    c->gt = malloc(sizeof(double) * 3 * (size_t)w * h);
    c->gt_frame = -1;
    c->v_frame = -1;
    s->ctx = c;
    if (!c->lin || !c->mv || !c->gt || !c->sub_lin || !c->sub_mv || !c->sub_mvs || !c->sub_mvd || !c->l_shade ||
        !c->l_vis || !c->l_refl || !c->l_w || !c->l_mvsurf || !c->l_mvrefl || !c->l_src) {
        rs_destroy(s);
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    s->name = "embree";
    s->width = w;
    s->height = h;
    s->gamma[0] = s->gamma[1] = s->gamma[2] = 2.2;
    s->gt_ss = 1;
    s->rigid = 1; /* ground truth rendered at clock frames, moved along pursuit */
    s->samples = rs_samples;
    s->ground_truth = rs_ground_truth;
    s->pursuit = rs_pursuit;
    s->cut = rs_cut;
    s->destroy = rs_destroy;
    s->full_frame = rs_full;
    s->jitter = rs_jitter;
    s->subframe = rs_subframe;
    s->reduced_frame = rs_reduced;
    s->layered_subframe = rs_layered;
    s->foveated = rs_foveated;
    s->note = "Embree renderer: full frames at 1 ray per pixel centre (TAA: + its jitter); reduced frames are full renders prefiltered "
              "by the TRM stage's D (trmXXr/trm50p: the renderer's own REDUCED frames); subframes traced by the "
              "renderer with its own adaptive orderings; foveated frames traced by its FOVEATED mode";
    return s;
}
