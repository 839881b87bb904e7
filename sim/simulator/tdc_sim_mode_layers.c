/*
 * tdc_sim_mode_layers.c - layered tile assembly (firmware/tdc_layers.h,
 * issue 16): one sample per 2x2 tile per refresh as the assembly modes, but
 * the source sends the components separately (tdc_source_t.layers: shading,
 * visibility, ...), each with its own vectors, over the link's LAYERS kind;
 * the controller reprojects each layer with its own vector and recombines.
 *
 *   lasm-ordinary    ordinary (surface) vectors for every layer, TDRT 1 sigma
 *   lasm-zeng        Zeng's vectors (shadow vectors, splatted by the
 *                    controller over 5 x 5, §4.1), Zeng's 3 sigma clamp
 *   lasm-zeng-tdrt   Zeng's vectors with TDRT's 1 sigma clamp
 *   lasm-zeng-clean  lasm-zeng + the §5 clean-up filter
 *   lasm-zeng-hist   lasm-zeng-clean + exponential history per layer (eq. 2,
 *                    alpha 0.1; tdc_layers.h "History per layer": what a
 *                    stream with flag LAYER_HIST gets from the frame loop)
 *
 * Orderings are adaptive (tdc_ordering_update over the renderer's motion
 * buffer: each pixel keeps the vector of its latest sample, the visibility
 * layer's where it has one, else the shading layer's) and go over the link
 * as PATTERN packets.
 */
#include <stdlib.h>
#include <string.h>

#include "simulator/tdc_sim_mode.h"

#include "tdc_layers.h"
#include "tdc_ordering.h"
#include "tdc_free.h"

enum { V_ORDINARY = 0, V_ZENG = 1, V_ZENG_TDRT = 2, V_ZENG_CLEAN = 3, V_ZENG_HIST = 4 };

#define F &tdc_sim_family_layers
#define L (TDC_SIM_LINK_SUBFRAMES | TDC_SIM_LINK_LAYERS)
static const tdc_mode_desc_t k_modes[] = {
    {"lasm-ordinary", F, V_ORDINARY, L, 1, 1, 0, -1, 0, "layered assembly, ordinary vectors, 1-sigma clamp"},
    {"lasm-zeng", F, V_ZENG, L, 1, 1, 0, -1, 1, "layered assembly, Zeng vectors (splatted), 3-sigma clamp"},
    {"lasm-zeng-tdrt", F, V_ZENG_TDRT, L, 1, 1, 0, -1, 1, "layered assembly, Zeng vectors, 1-sigma clamp"},
    {"lasm-zeng-clean", F, V_ZENG_CLEAN, L, 1, 1, 0, -1, 1, "layered assembly, Zeng vectors, 3 sigma + clean-up"},
    {"lasm-zeng-hist", F, V_ZENG_HIST, L, 1, 1, 0, -1, 1,
     "layered assembly, Zeng vectors, 3 sigma + clean-up + per-layer history (eq. 2)"},
};
#undef F
#undef L

typedef struct {
    tdc_lasm_t st;
    void *mem;
    size_t bytes;
    int16_t *mvbuf;         /* renderer's motion buffer (orderings, jitter) */
    int16_t *keep;          /* per sample: the vector the motion buffer keeps */
    uint8_t *pattern;       /* orderings of the current cycle */
    tdc_layer_frame_t lf;   /* this subframe's layered samples */
    uint8_t *val[TDC_LAYER_MAX];
    int16_t *mv[TDC_LAYER_MAX];
    uint16_t *falloff;
} lasm_state_t;

static tdc_lasm_config_t lasm_config(const sim_mode_t *m, const tdc_panel_t *panel, int glossy)
{
    const int v = m->d->variant;
    tdc_lasm_config_t c = {(uint16_t)m->w,
                           (uint16_t)m->h,
                           (uint16_t)(TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING) | TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY) |
                                      (glossy ? TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY) : 0u)),
                           (uint8_t)(v == V_ORDINARY || v == V_ZENG_TDRT ? TDC_LASM_CLAMP_TDRT : TDC_LASM_CLAMP_ZENG),
                           (uint8_t)(v == V_ZENG_CLEAN || v == V_ZENG_HIST),
                           (uint8_t)(v == V_ORDINARY ? 0 : 2),
                           (uint8_t)(v == V_ZENG_HIST),
                           3277, /* alpha 0.1 (Zeng §5) */
                           panel};
    return c;
}

static int lasm_init(sim_mode_t *m, const tdc_sim_setup_t *s)
{
    /* the source must hand out layers (the procedural scenes do; a renderer
     * without layer outputs cannot run these modes) */
    if (!s->src_layers && !s->src_layered_subframe) {
        tdc_sim_note(m, "this source has no layer outputs (tdc_source_t.layers)");
        m->res->available = 0;
        return 0;
    }
    lasm_state_t *st = calloc(1, sizeof(*st));
    if (!st) {
        return -1;
    }
    m->fam = st;
    const size_t tiles = (size_t)((m->w + 1) / 2) * ((m->h + 1) / 2);
    st->mvbuf = calloc(m->npx * 2, sizeof(int16_t));
    st->pattern = calloc((tiles + 7) / 8 + 1, 1);
    st->falloff = calloc(tiles, sizeof(uint16_t));
    st->keep = calloc(tiles * 2, sizeof(int16_t));
    int ok = st->mvbuf && st->pattern && st->falloff && st->keep;
    for (int t = 0; t < TDC_LAYER_MAX; t++) {
        st->val[t] = calloc(tiles * 3, 1);
        st->mv[t] = calloc(tiles * 2, sizeof(int16_t));
        st->lf.value[t] = st->val[t];
        st->lf.mv[t] = st->mv[t];
        ok = ok && st->val[t] && st->mv[t];
    }
    st->lf.falloff = st->falloff;
    /* a renderer's layered subframes may carry a glossy layer */
    const tdc_lasm_config_t c = lasm_config(m, s->fw_panel, s->src_layered_subframe);
    st->bytes = tdc_lasm_get_size(&c);
    st->mem = st->bytes ? aligned_alloc(8, (st->bytes + 7) & ~(size_t)7) : NULL;
    if (!ok || (st->bytes && !st->mem)) {
        return -1;
    }
    tdc_status_t rc = st->mem ? tdc_lasm_init(&st->st, &c, st->mem, st->bytes) : TDC_ERR_SIZE;
    if (rc != TDC_OK) {
        tdc_sim_refuse(m, "layered assembly firmware", rc);
    }
    return 0;
}

/* Renderer side of one layered subframe: orderings, sample positions (the
 * assembly's rule: jitter where the controller keeps the pixel static),
 * layers. */
static int lasm_subframe(sim_mode_t *m, lasm_state_t *st, tdc_source_t *src, double t, uint32_t lf)
{
    double t0 = tdc_sim_now();
    if ((lf & 3u) == 0u) {
        tdc_ordering_update(st->mvbuf, m->w, m->h, st->pattern, lf);
    }
    /* jitter as the assembly modes (3x3 of the renderer's motion buffer);
     * widening it by the controller's splatting radius was measured worse
     * (fence 48x32, 24 frames: lasm-zeng 31.17 -> 30.65 dB): the shading
     * layer, static under the shadow, loses its jittered window samples */
    const int n = tdc_sim_subframe_xy(m, st->mvbuf, st->pattern, lf, 1);
    const int zeng = m->d->variant != V_ORDINARY;
    if (src->layers(src, t, n, m->xy, m->fs, zeng, &st->lf) != 0) {
        return tdc_sim_stage(m, "renderer layers", TDC_ERR_STATE);
    }
    const int vis = (st->lf.present & TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY)) != 0;
    for (int i = 0; i < n; i++) {
        const int16_t *sv = st->mv[TDC_LAYER_VISIBILITY - 1] + 2 * i;
        const int16_t *hv = st->mv[TDC_LAYER_SHADING - 1] + 2 * i;
        const int use_vis = vis && (sv[0] || sv[1]);
        st->keep[2 * i] = use_vis ? sv[0] : hv[0];
        st->keep[2 * i + 1] = use_vis ? sv[1] : hv[1];
    }
    tdc_sim_subframe_keep_mv(m, st->mvbuf, n, st->keep);
    /* elision: a falloff plane of ones (planar receivers) is not sent */
    if (st->lf.present & TDC_LAYER_PKT_FALLOFF) {
        int ones = 1;
        for (int i = 0; i < n && ones; i++) {
            ones = st->falloff[i] == TDC_LAYER_W_ONE;
        }
        if (ones) {
            st->lf.present = (uint16_t)(st->lf.present & ~TDC_LAYER_PKT_FALLOFF);
            st->lf.hdr.flags = 0;
        }
    }
    m->res->render_s += tdc_sim_now() - t0;
    /* one primary ray per sample, as the single-layer modes count (the
     * shadow ray belongs to the shading of either) */
    m->res->rays += (uint64_t)n;
    m->res->rendered++;
    return 0;
}

static int lasm_frame(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    (void)spp; /* one ray per sample */
    lasm_state_t *st = m->fam;
    int rc;
    if (src->layered_subframe) {
        uint64_t rays = 0;
        const double t1 = tdc_sim_now();
        rc = tdc_sim_stage(m, "renderer layered subframe",
                           src->layered_subframe(src, m->slot, m->d->variant != V_ORDINARY, lf, t, m->fs, &st->lf,
                                                 st->pattern, &rays));
        m->res->render_s += tdc_sim_now() - t1;
        m->res->rays += rays;
        m->res->rendered++;
    } else {
        rc = lasm_subframe(m, st, src, t, lf);
    }
    if (rc) {
        return rc;
    }
    const int cycle = (lf & 3u) == 0u;
    rc = tdc_sim_stage(m, "link LAYERS/PATTERN packets",
                       tdc_sim_link_layers(m->link, m->eye, lf, &st->lf, cycle ? st->pattern : NULL));
    if (rc) {
        return rc;
    }
    const double t0 = tdc_sim_now();
    rc = tdc_sim_stage(m, "tdc_lasm_ingest",
                       tdc_lasm_ingest(&st->st, lf, m->link->layers[m->eye], cycle ? m->link->pattern[m->eye] : NULL));
    if (rc == 0) {
        rc = tdc_sim_stage(m, "tdc_lasm_assemble", tdc_lasm_assemble(&st->st, lf));
    }
    if (rc == 0) {
        int stride;
        const uint8_t *o = tdc_lasm_output(&st->st, &stride);
        for (int y = 0; y < m->h; y++) {
            memcpy(m->wanted + (size_t)y * m->w * 3, o + (size_t)y * stride, (size_t)m->w * 3);
        }
    }
    m->res->fw_s += tdc_sim_now() - t0;
    return rc;
}

static void lasm_reset(sim_mode_t *m)
{
    lasm_state_t *st = m->fam;
    memset(st->mvbuf, 0, m->npx * 2 * sizeof(int16_t));
    const tdc_lasm_config_t c = st->st.cfg;
    tdc_sim_stage(m, "tdc_lasm_init (stream reset)", tdc_lasm_init(&st->st, &c, st->mem, st->bytes));
}

static void lasm_free(sim_mode_t *m)
{
    lasm_state_t *st = m->fam;
    if (st) {
        TDC_FREE_ALL(st->mem, st->mvbuf, st->pattern, st->falloff, st->keep);
        for (int t = 0; t < TDC_LAYER_MAX; t++) {
            free(st->val[t]);
            free(st->mv[t]);
        }
        free(st);
    }
    m->fam = NULL;
}

const tdc_sim_family_t tdc_sim_family_layers = {
    "layers", k_modes, (int)(sizeof(k_modes) / sizeof(k_modes[0])), lasm_init, lasm_frame, lasm_reset, lasm_free,
};
