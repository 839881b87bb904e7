/*
 * golden_trm.c - bit-exact golden vectors of the TRM stage: contents x odd
 * and even sizes x ratios x panels, full/reduced pairs, one checksum per
 * output frame (FNV-1a 64 over the drive codes; reduced outputs also fold
 * in the residual so rho is pinned too).  Freestanding, static buffers.
 */
#include "golden.h"
#include "golden_trm.h"
#include "tdc_content.h"
#include "tdc_panels.h"
#include "tdc_trm.h"

#define GW_MAX 64
#define GH_MAX 48

static uint64_t g_arena[TDC_TRM_MEM_BYTES(GW_MAX, GH_MAX, 1, 1) / 8u + 1u];
static uint8_t g_in[GW_MAX * GH_MAX * 3];
static uint8_t g_out[GW_MAX * GH_MAX * 3];
static uint8_t g_red[GW_MAX * GH_MAX * 3];
static tdc_res_t g_rho_row[GW_MAX * 3];

typedef struct {
    tdc_content_t content;
    uint16_t w, h, rn, rd;
    uint32_t s_q8;
    const tdc_panel_t *panel;
} trm_vector_t;

void tdc_golden_trm_config(tdc_trm_config_t *cfg, uint32_t w, uint32_t h, uint32_t rn, uint32_t rd)
{
    tdc_trm_default_config(cfg, (uint16_t)w, (uint16_t)h, 90);
    cfg->r_num = (uint16_t)rn;
    cfg->r_den = (uint16_t)rd;
}

/* One frame of a full/reduced pair through a TRM stage, hashed: a full frame
 * (t even) folds in the drive codes and the recomputed rho, a reduced frame
 * the renderer's reduced input and the drive codes.  *ok &= every call
 * succeeded.  Shared with golden_trmgaze.c. */
uint64_t tdc_golden_trm_step(tdc_trm_t *trm, uint32_t t, const uint8_t *in, uint8_t *out, uint8_t *red, tdc_res_t *rho_row,
                             uint32_t w, uint32_t h, int *ok)
{
    const uint32_t stride = 3u * w;
    uint64_t hh = TDC_FNV64_INIT;
    if ((t & 1u) == 0u) {
        *ok &= tdc_trm_full(trm, in, stride, out, stride) == TDC_OK;
        hh = tdc_fnv1a64(hh, out, (size_t)stride * h);
        /* rho as the reduced frame will use it: recomputed from the kept
         * codes row by row (the stage stores no rho), hashed in the same
         * byte order as the stored buffer was */
        for (uint32_t y = 0; y < h; y++) {
            if (tdc_trm_residual_row(trm, y, rho_row) != TDC_OK) {
                hh = 0; /* shows as a mismatch */
            }
            hh = tdc_fnv1a64(hh, rho_row, sizeof(tdc_res_t) * stride);
        }
    } else {
        *ok &= tdc_trm_downsample(trm, in, stride, red, 3u * trm->rw) == TDC_OK;
        hh = tdc_fnv1a64(hh, red, (size_t)3u * trm->rw * trm->rh);
        *ok &= tdc_trm_reduced(trm, red, 3u * trm->rw, out, stride) == TDC_OK;
        hh = tdc_fnv1a64(hh, out, (size_t)stride * h);
    }
    return hh;
}

static void run_vector(tdc_golden_ctx_t *ctx, const trm_vector_t *v)
{
    char name[64];
    char *o = tdc_golden_put_head(name, tdc_content_name(v->content), v->w, v->h, v->rn, v->rd);
    o = tdc_golden_put_str(o, "-s");
    o = tdc_golden_put_u32(o, v->s_q8);
    tdc_golden_put_panel(o, v->panel->name);

    tdc_trm_config_t cfg;
    tdc_golden_trm_config(&cfg, v->w, v->h, v->rn, v->rd);
    cfg.s_q8 = v->s_q8;
    tdc_trm_t trm;
    if (tdc_trm_init(&trm, &cfg, v->panel, g_arena, sizeof g_arena) != TDC_OK) {
        tdc_golden_emit(ctx, "trm", name, 0, 0); /* a failing init shows as a mismatch */
        return;
    }
    const uint32_t stride = 3u * v->w;
    for (uint32_t t = 0; t < 6u; t++) {
        tdc_content_frame(v->content, t, 11u, g_in, v->w, v->h, (int)stride);
        int ok = 1;
        const uint64_t h = tdc_golden_trm_step(&trm, t, g_in, g_out, g_red, g_rho_row, v->w, v->h, &ok);
        tdc_golden_emit(ctx, "trm", name, t, ok ? h : TDC_GOLDEN_FAILED);
    }
}

void tdc_golden_trm(tdc_golden_ctx_t *ctx);

void tdc_golden_trm(tdc_golden_ctx_t *ctx)
{
    static const tdc_content_t contents[] = {TDC_CONTENT_EDGE,      TDC_CONTENT_TEXT,    TDC_CONTENT_NOISE,
                                             TDC_CONTENT_PRIMARIES, TDC_CONTENT_CHECKER, TDC_CONTENT_GRADIENT,
                                             TDC_CONTENT_FLASH};
    static const uint16_t sizes[][2] = {{33, 21}, {64, 48}, {17, 9}};
    static const uint16_t ratios[][2] = {{1, 2}, {2, 5}, {1, 4}};
    for (unsigned c = 0; c < sizeof contents / sizeof contents[0]; c++) {
        for (unsigned s = 0; s < 3u; s++) {
            for (unsigned r = 0; r < 3u; r++) {
                trm_vector_t v = {contents[c],
                                  sizes[s][0],
                                  sizes[s][1],
                                  ratios[r][0],
                                  ratios[r][1],
                                  2560u,
                                  ((c + s + r) & 1u) ? &tdc_panel_rift_cv1 : &tdc_panel_htc_vive};
                run_vector(ctx, &v);
            }
        }
    }
    /* s at its limits, r = 1 pass-through */
    trm_vector_t extra[] = {
        {TDC_CONTENT_EDGE, 33, 21, 1, 2, 0u, &tdc_panel_htc_vive},
        {TDC_CONTENT_EDGE, 33, 21, 1, 2, 0xffffffffu, &tdc_panel_htc_vive},
        {TDC_CONTENT_NOISE, 33, 21, 1, 1, 2560u, &tdc_panel_rift_cv1},
    };
    for (unsigned i = 0; i < sizeof extra / sizeof extra[0]; i++) {
        if (extra[i].rn == extra[i].rd) {
            /* pass-through has no reduced frames: full frames only */
            tdc_trm_config_t cfg;
            tdc_trm_default_config(&cfg, extra[i].w, extra[i].h, 90);
            cfg.r_num = cfg.r_den = 1;
            tdc_trm_t trm;
            const int init_ok = tdc_trm_init(&trm, &cfg, extra[i].panel, g_arena, sizeof g_arena) == TDC_OK;
            for (uint32_t t = 0; t < 3u; t++) {
                tdc_content_frame(extra[i].content, t, 11u, g_in, extra[i].w, extra[i].h, 3 * extra[i].w);
                const int ok = init_ok && tdc_trm_full(&trm, g_in, 3u * extra[i].w, g_out, 3u * extra[i].w) == TDC_OK;
                tdc_golden_emit(ctx, "trm", "noise-33x21-r1_1-passthrough", t,
                                ok ? tdc_fnv1a64(TDC_FNV64_INIT, g_out, 3u * extra[i].w * extra[i].h)
                                   : TDC_GOLDEN_FAILED);
            }
        } else {
            run_vector(ctx, &extra[i]);
        }
    }
}
