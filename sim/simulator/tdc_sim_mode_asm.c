/*
 * tdc_sim_mode_asm.c - tile-ordered frame assembly (firmware/tdc_assemble.h):
 * one sample per 2x2 tile per refresh in hourglass / bowtie orderings, fixed
 * or chosen from motion (the firmware's own tdc_ordering_update, linked by
 * the renderer side), optionally with shadow + dual motion vectors.  The
 * link carries SUBFRAME, PATTERN (every 4th frame) and MOTION packets.
 * The asm-ref-* modes assemble the same packets with the double reference
 * (ref/ref_asm.h) instead of the firmware, with the variance-sampling
 * neighbourhood TDRT Fig. 7 compares (the firmware has only the paper's):
 * asm-ref is the paper's box, the other two are the alternatives it rejects.
 */
#include <stdlib.h>
#include <string.h>

#include "simulator/tdc_sim_mode.h"

#include "tdc_assemble.h"
#include "tdc_ordering.h"
#include "tdc_free.h"
#include "ref_asm.h"

#define F &tdc_sim_family_asm
#define L (TDC_SIM_LINK_SUBFRAMES | TDC_SIM_LINK_SAMPLE_MV)
static const tdc_mode_desc_t k_modes[] = {
    {"asm-hourglass", F, 0, L, 1, 1, 0, 0, 0, "tile-ordered assembly, hourglass only"},
    {"asm-bowtie", F, 0, L, 1, 1, 0, 1, 0, "tile-ordered assembly, bowtie only"},
    {"asm-adaptive", F, 0, L, 1, 1, 0, -1, 0, "tile-ordered assembly, adaptive orderings"},
    {"asm-hourglass-smv", F, 0, L, 1, 1, 0, 0, 1, "assembly, hourglass, shadow + dual MVs"},
    {"asm-bowtie-smv", F, 0, L, 1, 1, 0, 1, 1, "assembly, bowtie, shadow + dual MVs"},
    {"asm-adaptive-smv", F, 0, L, 1, 1, 0, -1, 1, "assembly, adaptive, shadow + dual MVs"},
    /* variant: 1 + tdc_ref_nbhd_t (the double reference, TDRT Fig. 7) */
    {"asm-ref", F, 1 + TDC_REF_NBHD_NEWEST, L, 1, 1, 0, -1, 0,
     "reference assembly (double), adaptive; box: newest immediate neighbours (the paper's)"},
    {"asm-ref-all", F, 1 + TDC_REF_NBHD_ALL, L, 1, 1, 0, -1, 0,
     "reference assembly, adaptive; box: all 8 neighbours (old ones reprojected)"},
    {"asm-ref-sub3x3", F, 1 + TDC_REF_NBHD_SUB3X3, L, 1, 1, 0, -1, 0,
     "reference assembly, adaptive; box: a 3x3 area of the newest subframe"},
};
#undef F
#undef L

typedef struct {
    tdc_asm_t as;
    void *mem;
    size_t bytes;
    int16_t *mvbuf;   /* the renderer's motion buffer: each pixel keeps its latest sample's MV */
    int16_t *submv;   /* MVs of this subframe's samples */
    uint8_t *sub;     /* samples of this subframe */
    uint8_t *pattern; /* orderings of the current cycle */
    tdc_ref_asm_t *ref; /* asm-ref-* modes: the reference instead of the firmware */
} asm_state_t;

static int asm_ref_new(sim_mode_t *m, asm_state_t *st)
{
    tdc_ref_asm_free(st->ref);
    st->ref = tdc_ref_asm_new(m->w, m->h);
    if (!st->ref) return -1;
    tdc_ref_asm_set_nbhd(st->ref, (tdc_ref_nbhd_t)(m->d->variant - 1));
    return 0;
}

static int asm_init(sim_mode_t *m, const tdc_sim_setup_t *s)
{
    if (s->src_full_frame && (!s->src_subframe || m->d->ordering >= 0)) {
        tdc_sim_note(m, s->src_subframe
                            ? "the renderer chooses its own (adaptive) orderings: fixed orderings not available"
                            : "this source does not trace subframes");
        m->res->available = 0;
        return 0;
    }
    asm_state_t *st = calloc(1, sizeof(*st));
    if (!st) {
        return -1;
    }
    m->fam = st;
    size_t tiles = (size_t)((m->w + 1) / 2) * ((m->h + 1) / 2);
    st->mvbuf = calloc(m->npx * 2, sizeof(int16_t));
    st->submv = calloc(tiles * 2, sizeof(int16_t));
    st->sub = calloc(tiles * 3, 1);
    st->pattern = calloc((tiles + 7) / 8 + 1, 1);
    if (m->d->variant > 0) {
        return st->mvbuf && st->submv && st->sub && st->pattern ? asm_ref_new(m, st) : -1;
    }
    tdc_asm_config_t ac = {(uint16_t)m->w, (uint16_t)m->h};
    st->bytes = tdc_asm_get_size(&ac);
    st->mem = st->bytes ? malloc(st->bytes) : NULL;
    if (!st->mvbuf || !st->submv || !st->sub || !st->pattern || (st->bytes && !st->mem)) {
        return -1;
    }
    tdc_status_t rc = st->mem ? tdc_asm_init(&st->as, &ac, st->mem, st->bytes) : TDC_ERR_SIZE;
    if (rc != TDC_OK) {
        tdc_sim_refuse(m, "assembly firmware", rc);
    }
    return 0;
}

/* Renderer side of one subframe: orderings, sample positions, MVs. */
static void asm_subframe(sim_mode_t *m, asm_state_t *st, tdc_source_t *src, double t, uint32_t lf)
{
    int tx = (m->w + 1) / 2, ty = (m->h + 1) / 2;
    double t0 = tdc_sim_now();
    if ((lf & 3u) == 0u) {
        size_t nb = ((size_t)tx * ty + 7) / 8;
        if (m->d->ordering < 0) {
            /* the firmware's own decision function, linked by the renderer */
            tdc_ordering_update(st->mvbuf, m->w, m->h, st->pattern, lf);
        } else {
            memset(st->pattern, m->d->ordering ? 0xFF : 0x00, nb);
        }
    }
    const int n = tdc_sim_subframe_xy(m, st->mvbuf, st->pattern, lf, 1);
    src->samples(src, t, n, m->xy, 1, st->sub, st->submv, m->fs, m->d->shadow_mv ? TDC_MV_SHADOW : TDC_MV_SURFACE);
    tdc_sim_subframe_keep_mv(m, st->mvbuf, n, st->submv);
    m->res->render_s += tdc_sim_now() - t0;
    m->res->rays += (uint64_t)n;
    m->res->rendered++;
}

static int asm_frame(sim_mode_t *m, tdc_source_t *src, double t, int spp, uint32_t lf)
{
    (void)spp; /* one ray per sample */
    asm_state_t *st = m->fam;
    tdc_sim_result_t *r = m->res;
    int rc;
    if (src->subframe) {
        uint64_t rays = 0;
        double t1 = tdc_sim_now();
        rc = tdc_sim_stage(
            m, "renderer subframe",
            src->subframe(src, m->slot, m->d->shadow_mv, lf, t, m->fs, st->sub, st->submv, st->pattern, &rays));
        r->render_s += tdc_sim_now() - t1;
        r->rays += rays;
        r->rendered++;
        if (rc) {
            return rc;
        }
    } else {
        asm_subframe(m, st, src, t, lf);
    }
    int cycle = (lf & 3u) == 0u;
    rc = tdc_sim_stage(m, "link SUBFRAME/PATTERN/MOTION packets",
                       tdc_sim_link_subframe(m->link, m->eye, lf, st->sub, st->submv, cycle ? st->pattern : NULL));
    if (rc) {
        return rc;
    }
    double t0 = tdc_sim_now();
    if (st->ref) {
        const uint8_t *pat = cycle ? m->link->pattern[m->eye] : NULL;
        if (tdc_ref_asm_ingest(st->ref, lf, m->link->subframe[m->eye], m->link->sample_motion[m->eye], pat) ||
            tdc_ref_asm_assemble(st->ref, lf)) {
            return tdc_sim_stage(m, "reference assembly (ref_assemble)", TDC_ERR_STATE);
        }
        memcpy(m->wanted, tdc_ref_asm_output(st->ref), (size_t)m->w * m->h * 3);
        r->fw_s += tdc_sim_now() - t0;
        return 0;
    }
    rc = tdc_sim_stage(m, "tdc_asm_ingest",
                       tdc_asm_ingest(&st->as, lf, m->link->subframe[m->eye], m->link->sample_motion[m->eye],
                                      cycle ? m->link->pattern[m->eye] : NULL));
    if (rc == 0) {
        rc = tdc_sim_stage(m, "tdc_asm_assemble", tdc_asm_assemble(&st->as, lf));
    }
    if (rc == 0) {
        int stride;
        const uint8_t *o = tdc_asm_output(&st->as, &stride);
        for (int y = 0; y < m->h; y++) {
            memcpy(m->wanted + (size_t)y * m->w * 3, o + (size_t)y * stride, (size_t)m->w * 3);
        }
    }
    r->fw_s += tdc_sim_now() - t0;
    return rc;
}

static void asm_reset(sim_mode_t *m)
{
    asm_state_t *st = m->fam;
    memset(st->mvbuf, 0, m->npx * 2 * sizeof(int16_t));
    if (st->ref) {
        if (asm_ref_new(m, st)) tdc_sim_stage(m, "reference assembly (stream reset): out of memory", TDC_ERR_STATE);
        return;
    }
    tdc_asm_config_t ac = {(uint16_t)m->w, (uint16_t)m->h};
    tdc_sim_stage(m, "tdc_asm_init (stream reset)", tdc_asm_init(&st->as, &ac, st->mem, st->bytes));
}

static void asm_free(sim_mode_t *m)
{
    asm_state_t *st = m->fam;
    if (st) {
        tdc_ref_asm_free(st->ref);
        TDC_FREE_ALL(st->mem, st->mvbuf, st->submv, st->sub, st->pattern, st);
    }
    m->fam = NULL;
}

const tdc_sim_family_t tdc_sim_family_asm = {
    "asm", k_modes, (int)(sizeof(k_modes) / sizeof(k_modes[0])), asm_init, asm_frame, asm_reset, asm_free,
};
