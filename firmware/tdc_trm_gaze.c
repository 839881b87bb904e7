/*
 * tdc_trm_gaze.c - gaze-aware TRM: the per-tile compensation strength and
 * the full-resolution row that applies it (see tdc_trm_gaze.h).  tdc_trm.c
 * calls tdc_trm_gaze_full_row() for a row only when a map is attached and
 * one of the row's tiles has k < 1; everything else is TRM's own kernel.
 */
#include "tdc_trm_gaze.h"

#include "tdc_math.h"
#include "tdc_trm_kernels.h"

static int gaze_config_valid(const tdc_trm_gaze_config_t *c)
{
    return c && c->width > 0u && c->height > 0u && c->tile >= TDC_TRM_GAZE_MIN_TILE &&
           c->tile <= TDC_TRM_GAZE_MAX_TILE && c->u1_q4 > c->u0_q4 && c->kmin_q15 <= 32768u;
}

void tdc_trm_gaze_default_config(tdc_trm_gaze_config_t *cfg, uint16_t width, uint16_t height)
{
    cfg->width = width;
    cfg->height = height;
    cfg->tile = 16;
    cfg->u0_q4 = 8;  /* 0.5 px/frame: below, the retinal drift of a tracking eye */
    cfg->u1_q4 = 32; /* 2 px/frame: beyond, sharpening and reduced frame miss each other */
    cfg->kmin_q15 = 0;
}

static void gaze_carve(tdc_trm_gaze_t *st, const tdc_trm_gaze_config_t *cfg, tdc_arena_t *arena)
{
    st->tx = TDC_TRM_GAZE_TILES_X(cfg->width, cfg->tile);
    st->ty = TDC_TRM_GAZE_TILES_Y(cfg->height, cfg->tile);
    TDC_TRM_GAZE_ARENA(TDC_ARENA_CARVE, st->tx, st->ty)
}

size_t tdc_trm_gaze_get_size(const tdc_trm_gaze_config_t *cfg)
{
    if (!gaze_config_valid(cfg)) {
        return 0;
    }
    tdc_trm_gaze_t dry = {0};
    tdc_arena_t arena;
    tdc_arena_dry(&arena);
    gaze_carve(&dry, cfg, &arena);
    return tdc_arena_size(&arena);
}

tdc_status_t tdc_trm_gaze_init(tdc_trm_gaze_t *g, const tdc_trm_gaze_config_t *cfg, void *mem, size_t mem_bytes)
{
    if (!g || !mem || !gaze_config_valid(cfg)) {
        return TDC_ERR_ARG;
    }
    tdc_arena_t arena;
    if (!tdc_arena_over(&arena, mem, mem_bytes)) {
        return TDC_ERR_ARG;
    }
    if (mem_bytes < tdc_trm_gaze_get_size(cfg)) {
        return TDC_ERR_SIZE;
    }
    *g = (tdc_trm_gaze_t){0};
    g->cfg = *cfg;
    gaze_carve(g, cfg, &arena);
    for (uint32_t i = 0; i < g->tx * g->ty; i++) {
        g->k_q15[i] = 32768u;
    }
    for (uint32_t i = 0; i < g->ty; i++) {
        g->row_active[i] = 0;
    }
    return TDC_OK;
}

uint16_t tdc_trm_gaze_strength_q15(const tdc_trm_gaze_config_t *cfg, int32_t udx_q4, int32_t udy_q4)
{
    /* |u|^2 in Q8: each |component| <= 65535 (difference of two int16), so
     * the sum < 2^33: 64 bits */
    const uint64_t s2 = (uint64_t)((int64_t)udx_q4 * udx_q4) + (uint64_t)((int64_t)udy_q4 * udy_q4);
    const uint32_t a = (uint32_t)cfg->u0_q4 * cfg->u0_q4, b = (uint32_t)cfg->u1_q4 * cfg->u1_q4; /* < 2^32 */
    if (s2 <= a) {
        return 32768u;
    }
    if (s2 >= b) {
        return cfg->kmin_q15;
    }
    /* fraction (s2 - a) / (b - a) in Q30, num < den < 2^32 */
    const uint32_t f_q30 = (uint32_t)tdc_div_q30((uint32_t)(s2 - a), b - a);
    const uint32_t drop = 32768u - cfg->kmin_q15; /* <= 2^15 */
    /* k = 1 - drop f: Q15 * Q30 -> Q45 in 64 bits, rounded to Q15 */
    const uint32_t dk = (uint32_t)(((uint64_t)drop * f_q30 + (1ull << 29)) >> 30);
    return (uint16_t)(32768u - (dk > drop ? drop : dk));
}

tdc_status_t tdc_trm_gaze_update(tdc_trm_gaze_t *g, const int16_t *mv, uint32_t n_pairs, int16_t gdx_q4,
                                 int16_t gdy_q4)
{
    if (!g || !g->k_q15) {
        return TDC_ERR_ARG;
    }
    if (!mv || n_pairs != g->tx * g->ty || gdx_q4 == INT16_MIN || gdy_q4 == INT16_MIN) {
        g->rejected++;
        return TDC_ERR_ARG;
    }
    for (uint32_t i = 0; i < 2u * n_pairs; i++) {
        if (mv[i] == INT16_MIN) { /* the link's "no vector" sentinel is not a motion */
            g->rejected++;
            return TDC_ERR_ARG;
        }
    }
    for (uint32_t ty = 0; ty < g->ty; ty++) {
        uint8_t active = 0;
        for (uint32_t tx = 0; tx < g->tx; tx++) {
            const uint32_t i = ty * g->tx + tx;
            const uint16_t k = tdc_trm_gaze_strength_q15(&g->cfg, (int32_t)mv[2u * i] - gdx_q4,
                                                         (int32_t)mv[2u * i + 1u] - gdy_q4);
            g->k_q15[i] = k;
            active |= (uint8_t)(k < 32768u);
        }
        g->row_active[ty] = active;
    }
    g->updates++;
    return TDC_OK;
}

tdc_status_t tdc_trm_set_gaze(tdc_trm_t *st, const tdc_trm_gaze_t *g)
{
    if (!st) {
        return TDC_ERR_ARG;
    }
    if (g && (g->cfg.width != st->cfg.width || g->cfg.height != st->cfg.height || !g->k_q15)) {
        return TDC_ERR_SIZE;
    }
    st->gaze = g;
    return TDC_OK;
}

int tdc_trm_gaze_row_active(const tdc_trm_gaze_t *g, uint32_t y)
{
    return g->row_active[y / g->cfg.tile];
}

/* TRM's full row (tdc_trm_full_row_c) with beta = I + k (I - U D I): the
 * same decode, clamp, residual and encode, k per tile. */
void tdc_trm_gaze_full_row(const tdc_trm_rowctx_t *k, const tdc_trm_gaze_t *g, uint32_t y, const uint32_t *urow,
                           const uint8_t *src, uint8_t *dst, tdc_res_t *res, tdc_trm_full_counts_t *n)
{
    tdc_trm_gamma_t gm[3];
    tdc_trm_gamma_locals(k, gm);
    const uint16_t *krow = &g->k_q15[(y / g->cfg.tile) * g->tx];
    const uint32_t tile = g->cfg.tile;
    uint32_t nhi = 0, nlo = 0;
    for (uint32_t x = 0; x < k->width; x++) {
        const uint32_t i0 = 3u * k->ux[2u * x], f = k->ux[2u * x + 1u];
        const int64_t kq = krow[x / tile];
        for (uint32_t c = 0; c < 3u; c++) {
            const tdc_lin_t lu = tdc_trm_dec_q16(&gm[c], tdc_trm_hlerp(urow, i0 + c, f));
            const tdc_lin_t li = (tdc_lin_t)gm[c].dec[src[3u * x + c]];
            /* k = 32768: li + (li - lu) = 2 li - lu exactly, TRM's beta */
            const int32_t beta = li + (int32_t)tdc_rshr_round64(kq * (int64_t)(li - lu), 15);
            tdc_trm_put_beta(&gm[c], beta, &res[3u * x + c], &dst[3u * x + c], &nhi, &nlo);
        }
    }
    n->hi += nhi;
    n->lo += nlo;
}
