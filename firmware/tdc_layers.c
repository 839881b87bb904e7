/*
 * tdc_layers.c - layered tile assembly (tdc_layers.h): per-layer
 * reprojection with the layer's own vectors, shadow-vector splatting,
 * 1-sigma / 3-sigma clamps, the eq. 4 falloff on the shadow layer's history
 * weight, the §5 clean-up filter, recombination in linear light.
 * Integer only, caller-owned arena, no recursion.
 */
#include "tdc_layers.h"

#include <string.h>

#include "tdc_gamma.h"
#include "tdc_math.h"

#define VIS (TDC_LAYER_VISIBILITY - 1)
#define SIGMA_CAP_Q8 (5u * 256u) /* clean-up sigma limit, 5 px */
#define EPS_Q8 65u               /* eq. 8 epsilon 0.001 of full scale (255 x 256) */

static const uint8_t k_ch[TDC_LAYER_MAX] = {3u, 1u, 3u, 3u};

static int cfg_ok(const tdc_lasm_config_t *c)
{
    return c && c->width >= 1 && c->height >= 1 && c->width <= TDC_LASM_MAX_DIM && c->height <= TDC_LASM_MAX_DIM &&
           (c->layers & ~TDC_LAYER_PKT_TYPES) == 0 && (c->layers & TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING)) &&
           (c->clamp_k == TDC_LASM_CLAMP_TDRT || c->clamp_k == TDC_LASM_CLAMP_ZENG) && c->cleanup <= 1u &&
           c->splat_radius <= TDC_LASM_SPLAT_MAX && c->alpha_q15 <= 32768u && c->panel != NULL &&
           c->history <= 1u && (!c->history || c->alpha_q15 >= 1u);
}

static uint32_t chan(const tdc_lasm_config_t *c, unsigned i)
{
    return (c->layers & TDC_LAYER_PKT_TYPE(i + 1u)) ? k_ch[i] : 0u;
}

/* The one layout (TDC_LASM_ARENA); NULL views in a dry run. */
static void carve(tdc_lasm_t *st, const tdc_lasm_config_t *cfg, tdc_arena_t *arena)
{
    TDC_LASM_ARENA(TDC_ARENA_CARVE, cfg->width, cfg->height, TDC_PATTERN_BYTES(cfg->width, cfg->height),
                   chan(cfg, 0), chan(cfg, 1), chan(cfg, 2), chan(cfg, 3), cfg->history)
}

size_t tdc_lasm_get_size(const tdc_lasm_config_t *cfg)
{
    if (!cfg_ok(cfg)) {
        return 0;
    }
    tdc_lasm_t dry;
    tdc_arena_t arena;
    tdc_arena_dry(&arena);
    carve(&dry, cfg, &arena);
    return tdc_arena_size(&arena);
}

tdc_status_t tdc_lasm_init(tdc_lasm_t *st, const tdc_lasm_config_t *cfg, void *arena, size_t n)
{
    tdc_arena_t a;
    if (!st || !cfg_ok(cfg) || !tdc_arena_over(&a, arena, n)) {
        return TDC_ERR_ARG;
    }
    if (cfg->panel->bits != 8u) {
        return TDC_ERR_PANEL;
    }
    if (n < tdc_lasm_get_size(cfg)) {
        return TDC_ERR_SIZE;
    }
    memset(st, 0, sizeof *st);
    st->cfg = *cfg;
    carve(st, cfg, &a);
    const size_t wh = (size_t)cfg->width * cfg->height;
    st->tiles_x = TDC_TILES((uint32_t)cfg->width);
    st->tiles_y = TDC_TILES((uint32_t)cfg->height);
    for (unsigned i = 0; i < TDC_LAYER_MAX; i++) {
        st->ch[i] = (uint8_t)chan(cfg, i);
        st->kind[i] = TDC_LAYER_MV_SURFACE;
        if (st->ch[i]) {
            tdc_lasm_layer_t *l = &st->l[i];
            const int lit = i == VIS; /* visibility starts lit, colours black */
            memset(l->hist[0], lit ? 255 : 0, wh * st->ch[i]);
            memset(l->hist[1], lit ? 255 : 0, wh * st->ch[i]);
            memset(l->slots, 0, wh * st->ch[i] * 4u);
            memset(l->window, 0, wh);
            memset(l->mv, 0, wh * 4u);
            if (cfg->history) {
                const tdc_lhist_config_t hc = {cfg->width, cfg->height, st->ch[i], cfg->clamp_k, cfg->alpha_q15};
                const size_t hb = TDC_LASM_LHIST_WORDS(wh, (size_t)st->ch[i]) * 8u;
                if (tdc_lhist_init(&l->lh, &hc, l->lh_mem, hb) != TDC_OK) {
                    return TDC_ERR_SIZE; /* (the layout above is the one tdc_lhist carves) */
                }
            }
        }
    }
    if (st->hmv) {
        memset(st->hmv, 0, wh * 4u);
    }
    if (st->splat) {
        memset(st->splat, 0, wh * 4u);
    }
    memset(st->newmask, 0, wh);
    memset(st->sigma, 0, wh);
    memset(st->out, 0, wh * 3u);
    for (size_t p = 0; p < wh; p++) {
        st->weight[p] = (uint16_t)TDC_LAYER_W_ONE;
    }
    memset(st->pattern, 0, TDC_PATTERN_BYTES(cfg->width, cfg->height));
    /* Clean-up weights, Q12: round(4096 exp(-d^2 / (2 sigma^2))), sigma =
     * s / 16 px: x = 128 d^2 / s^2, in Q16 (d^2 << 23) / s^2 < 2^27. */
    for (uint32_t s = 0; s <= TDC_LASM_SIGMA_STEPS; s++) {
        for (uint32_t d = 0; d < 5u; d++) {
            uint32_t g = 0;
            if (d == 0) {
                g = 4096u;
            } else if (s > 0) {
                g = ((uint32_t)tdc_exp_neg_q16((d * d << 23) / (s * s)) + 4u) >> 3;
            }
            st->gauss[s * 5u + d] = (uint16_t)g;
        }
    }
    return TDC_OK;
}

tdc_status_t tdc_lasm_ingest(tdc_lasm_t *st, uint32_t frame, const tdc_layer_frame_t *lf, const uint8_t *pattern_bits)
{
    if (!st || !lf) {
        return TDC_ERR_ARG;
    }
    if (frame != st->next_frame || st->have_subframe) {
        return TDC_ERR_FRAME;
    }
    const uint32_t types = lf->present & TDC_LAYER_PKT_TYPES;
    if ((types & ~(uint32_t)st->cfg.layers) || types == 0 || lf->hdr.tiles_x != st->tiles_x ||
        lf->hdr.tiles_y != st->tiles_y || ((lf->present & TDC_LAYER_PKT_FALLOFF) && !lf->falloff)) {
        return TDC_ERR_LAYER;
    }
    for (unsigned i = 0; i < lf->hdr.count && i < TDC_LAYER_MAX; i++) {
        const unsigned t = lf->hdr.type[i];
        if (t < 1u || t > TDC_LAYER_MAX || !(types & TDC_LAYER_PKT_TYPE(t)) || !lf->value[t - 1u] || !lf->mv[t - 1u]) {
            return TDC_ERR_LAYER;
        }
        st->kind[t - 1u] = lf->hdr.mv_kind[i];
    }
    const uint32_t W = st->cfg.width, H = st->cfg.height;
    if ((frame & 3u) == 0u && pattern_bits) {
        memcpy(st->pattern, pattern_bits, TDC_PATTERN_BYTES(W, H));
    }
    const size_t wh = (size_t)W * H;
    const uint32_t slot = (frame >> 2) & 3u, k = frame & 3u;
    const int falloff = (lf->present & TDC_LAYER_PKT_FALLOFF) != 0;
    uint32_t n = 0;
    for (uint32_t ty = 0; ty < st->tiles_y; ty++) {
        for (uint32_t tx = 0; tx < st->tiles_x; tx++, n++) {
            const unsigned pos = tdc_ordering_pixel(tdc_ordering_get(st->pattern, n), k);
            const uint32_t x = 2u * tx + (pos & 1u), y = 2u * ty + (pos >> 1);
            if (x >= W || y >= H) {
                continue; /* partial tile */
            }
            const size_t p = (size_t)y * W + x;
            st->newmask[p] = 1;
            for (unsigned i = 0; i < TDC_LAYER_MAX; i++) {
                if (!(types & TDC_LAYER_PKT_TYPE(i + 1u))) {
                    continue;
                }
                const uint32_t ch = st->ch[i];
                uint8_t *dst = st->l[i].slots + (slot * wh + p) * ch;
                for (uint32_t c = 0; c < ch; c++) {
                    dst[c] = lf->value[i][n * ch + c];
                }
                st->l[i].mv[2u * p] = lf->mv[i][2u * n];
                st->l[i].mv[2u * p + 1u] = lf->mv[i][2u * n + 1u];
            }
            st->weight[p] = falloff ? lf->falloff[n] : (uint16_t)TDC_LAYER_W_ONE;
        }
    }
    st->present = (uint16_t)lf->present;
    st->have_subframe = 1;
    return TDC_OK;
}

/* §4.1 splatting: pixels without a shadow vector take the mean vector of the
 * in-shadow pixels (non-zero vectors) within the radius; rounded half away
 * from zero (C11 division truncates toward zero, the same on every CPU). */
static void splat(tdc_lasm_t *st)
{
    const int32_t W = st->cfg.width, H = st->cfg.height, R = st->cfg.splat_radius;
    const int16_t *mv = st->l[VIS].mv;
    for (int32_t y = 0; y < H; y++) {
        for (int32_t x = 0; x < W; x++) {
            const size_t p = (size_t)y * (size_t)W + (size_t)x;
            int32_t sx = mv[2u * p], sy = mv[2u * p + 1u], cnt = 0;
            if (sx == 0 && sy == 0) {
                sx = 0;
                for (int32_t yy = y - R; yy <= y + R; yy++) {
                    for (int32_t xx = x - R; xx <= x + R; xx++) {
                        if (yy < 0 || xx < 0 || yy >= H || xx >= W) {
                            continue;
                        }
                        const size_t q = (size_t)yy * (size_t)W + (size_t)xx;
                        if (mv[2u * q] || mv[2u * q + 1u]) {
                            sx += mv[2u * q];
                            sy += mv[2u * q + 1u];
                            cnt++;
                        }
                    }
                }
                if (cnt) {
                    /* |sum| <= 81 * 32767 < 2^22 */
                    sx = (2 * sx + (sx >= 0 ? cnt : -cnt)) / (2 * cnt);
                    sy = (2 * sy + (sy >= 0 ? cnt : -cnt)) / (2 * cnt);
                    st->stats.splatted++;
                }
            }
            st->splat[2u * p] = (int16_t)sx;
            st->splat[2u * p + 1u] = (int16_t)sy;
        }
    }
}

/* Bilinear sample (Q8 per channel) of img at (xq, yq) in Q4 pixel-index
 * coordinates, clamped to the frame. */
static void bilinear(const uint8_t *img, int32_t W, int32_t H, uint32_t ch, int32_t xq, int32_t yq, uint32_t out[3])
{
    xq = xq < 0 ? 0 : (xq > (W - 1) * 16 ? (W - 1) * 16 : xq);
    yq = yq < 0 ? 0 : (yq > (H - 1) * 16 ? (H - 1) * 16 : yq);
    const int32_t x0 = xq >> 4, y0 = yq >> 4, fx = xq & 15, fy = yq & 15;
    const int32_t x1 = fx ? x0 + 1 : x0, y1 = fy ? y0 + 1 : y0;
    const uint32_t w00 = (uint32_t)((16 - fx) * (16 - fy)), w10 = (uint32_t)(fx * (16 - fy));
    const uint32_t w01 = (uint32_t)((16 - fx) * fy), w11 = (uint32_t)(fx * fy);
    const uint8_t *a = img + ((size_t)y0 * (size_t)W + (size_t)x0) * ch, *b = img + ((size_t)y0 * (size_t)W + (size_t)x1) * ch;
    const uint8_t *c0 = img + ((size_t)y1 * (size_t)W + (size_t)x0) * ch, *d = img + ((size_t)y1 * (size_t)W + (size_t)x1) * ch;
    for (uint32_t c = 0; c < ch; c++) {
        out[c] = a[c] * w00 + b[c] * w10 + c0[c] * w01 + d[c] * w11;
    }
}

/* One layer into st->scratch (W x H x ch), with the clean-up sigma of each
 * pixel in st->sigma (1/16 px, 0 = none). */
static void assemble_layer(tdc_lasm_t *st, unsigned li, uint32_t frame)
{
    const int32_t W = st->cfg.width, H = st->cfg.height;
    const size_t wh = (size_t)W * (size_t)H;
    const uint32_t ch = st->ch[li], slot = (frame >> 2) & 3u, k = st->cfg.clamp_k;
    tdc_lasm_layer_t *L = &st->l[li];
    const uint8_t *prev = L->hist[st->cur];
    const uint8_t *cur_s = L->slots + slot * wh * ch; /* this frame's samples */
    uint8_t *dst = st->scratch;
    const int use_splat = li == VIS && st->splat && st->cfg.splat_radius && st->kind[li] == TDC_LAYER_MV_SHADOW;
    const int16_t *mvb = use_splat ? st->splat : L->mv;
    const int surface = st->kind[li] == TDC_LAYER_MV_SURFACE;
    const int have = st->have_subframe && (st->present & TDC_LAYER_PKT_TYPE(li + 1u));
    const int falloff = li == VIS;
    const uint32_t one_minus_alpha = 32768u - st->cfg.alpha_q15;
    int16_t *used = st->hmv; /* the vector of each pixel, for the history (NULL: none) */

    for (int32_t y = 0; y < H; y++) {
        for (int32_t x = 0; x < W; x++) {
            const size_t p = (size_t)y * (size_t)W + (size_t)x;
            int32_t mx = mvb[2u * p], my = mvb[2u * p + 1u];
            if (surface) {
                uint32_t best = (uint32_t)(mx * mx + my * my);
                for (int32_t yy = y - 1; yy <= y + 1; yy++) {
                    for (int32_t xx = x - 1; xx <= x + 1; xx++) {
                        if (yy < 0 || xx < 0 || yy >= H || xx >= W) {
                            continue;
                        }
                        const size_t q = (size_t)yy * (size_t)W + (size_t)xx;
                        const int32_t ax = mvb[2u * q], ay = mvb[2u * q + 1u];
                        const uint32_t l2 = (uint32_t)(ax * ax + ay * ay);
                        if (l2 > best) { /* first in raster order on ties: strict */
                            best = l2;
                            mx = ax;
                            my = ay;
                        }
                    }
                }
            }
            if (used) {
                used[2u * p] = (int16_t)mx;
                used[2u * p + 1u] = (int16_t)my;
            }
            const int isnew = have && st->newmask[p];
            uint8_t *o = dst + p * ch;
            st->sigma[p] = 0;
            if (mx == 0 && my == 0) {
                st->stats.static_px++;
                if (isnew) {
                    L->window[p] = (uint8_t)(L->window[p] | (1u << slot));
                    for (uint32_t c = 0; c < ch; c++) {
                        uint32_t sum = 0, n = 0;
                        for (uint32_t s = 0; s < 4u; s++) {
                            if (L->window[p] & (1u << s)) {
                                sum += L->slots[(s * wh + p) * ch + c];
                                n++;
                            }
                        }
                        o[c] = tdc_mean_u8(sum, n);
                    }
                } else {
                    for (uint32_t c = 0; c < ch; c++) {
                        o[c] = prev[p * ch + c];
                    }
                }
                continue;
            }
            if (isnew) {
                L->window[p] = (uint8_t)(1u << slot);
                for (uint32_t c = 0; c < ch; c++) {
                    o[c] = cur_s[p * ch + c];
                }
                continue;
            }
            L->window[p] = 0;
            st->stats.reprojected++;
            uint32_t h[3];
            bilinear(prev, W, H, ch, x * 16 + mx, y * 16 + my, h);
            /* the 8 neighbours traced this frame */
            uint32_t n = 0, s1[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
            if (have) {
                for (int32_t yy = y - 1; yy <= y + 1; yy++) {
                    for (int32_t xx = x - 1; xx <= x + 1; xx++) {
                        if (yy < 0 || xx < 0 || yy >= H || xx >= W || (yy == y && xx == x)) {
                            continue;
                        }
                        const size_t q = (size_t)yy * (size_t)W + (size_t)xx;
                        if (!st->newmask[q]) {
                            continue;
                        }
                        n++;
                        for (uint32_t c = 0; c < ch; c++) {
                            const uint32_t v = cur_s[q * ch + c];
                            s1[c] += v;
                            s2[c] += v * v;
                        }
                    }
                }
            }
            if (n == 0) {
                st->stats.no_neighbour++;
                for (uint32_t c = 0; c < ch; c++) {
                    o[c] = (uint8_t)((h[c] + 128u) >> 8);
                }
                continue;
            }
            const uint32_t g = falloff ? st->weight[p] : TDC_LAYER_W_ONE;
            uint32_t wc = 0;
            int clamped = 0;
            for (uint32_t c = 0; c < ch; c++) {
                const int32_t mu = (int32_t)tdc_div_small(s1[c] << 8, n); /* Q8, floor */
                const uint64_t var = (uint64_t)n * s2[c] - (uint64_t)s1[c] * s1[c];
                int32_t v = (int32_t)h[c];
                /* outside mean +- k sigma, exactly: (n h - 256 S1)^2 > 65536 k^2 var
                 * (|n h - 256 S1| < 2^19, var < 2^22: both sides < 2^42); only
                 * then the edge, with the floored Q8 mean and sigma */
                const int64_t dev = (int64_t)n * v - 256 * (int64_t)s1[c];
                if ((uint64_t)(dev * dev) > ((uint64_t)var << 16) * (k * k)) {
                    const int32_t sd = (int32_t)tdc_div_small(tdc_isqrt64(var << 16), n); /* Q8 sigma, floor */
                    v = dev > 0 ? mu + (int32_t)k * sd : mu - (int32_t)k * sd;
                }
                if (v != (int32_t)h[c]) {
                    clamped = 1;
                    const uint32_t d = (uint32_t)(v > (int32_t)h[c] ? v - (int32_t)h[c] : (int32_t)h[c] - v);
                    uint32_t r = (d << 8) / (h[c] + EPS_Q8);
                    r = r > SIGMA_CAP_Q8 ? SIGMA_CAP_Q8 : r;
                    wc = r > wc ? r : wc;
                }
                if (g < TDC_LAYER_W_ONE) {
                    /* history weight G, the rest spatial (the new neighbours' mean) */
                    v = (int32_t)(((uint32_t)v * g + (uint32_t)mu * (TDC_LAYER_W_ONE - g) + 16384u) >> 15);
                }
                v = (v + 128) >> 8;
                o[c] = (uint8_t)(v > 255 ? 255 : v);
            }
            uint32_t wa = 0;
            if (g < TDC_LAYER_W_ONE) {
                st->stats.weighted++;
                const uint32_t t = ((TDC_LAYER_W_ONE - g) * one_minus_alpha) >> 15; /* (1 - alpha)(1 - G), Q15 */
                wa = (t * t) >> 22;                                               /* squared, Q8 */
            }
            st->stats.clamped += (uint64_t)clamped;
            uint32_t sg = wa + wc;
            sg = sg > SIGMA_CAP_Q8 ? SIGMA_CAP_Q8 : sg;
            st->sigma[p] = (uint8_t)(sg >> 4);
        }
    }
}

/* Clean-up of layer li from st->scratch into its new frame. */
static void cleanup_layer(tdc_lasm_t *st, unsigned li)
{
    const int32_t W = st->cfg.width, H = st->cfg.height;
    const uint32_t ch = st->ch[li];
    const uint8_t *src = st->scratch;
    uint8_t *dst = st->l[li].hist[st->cur ^ 1];
    const size_t wh = (size_t)W * (size_t)H;
    if (!st->cfg.cleanup) {
        memcpy(dst, src, wh * ch);
        return;
    }
    for (int32_t y = 0; y < H; y++) {
        for (int32_t x = 0; x < W; x++) {
            const size_t p = (size_t)y * (size_t)W + (size_t)x;
            const uint32_t s = st->sigma[p];
            if (s == 0) {
                for (uint32_t c = 0; c < ch; c++) {
                    dst[p * ch + c] = src[p * ch + c];
                }
                continue;
            }
            st->stats.cleaned++;
            const uint16_t *g = st->gauss + s * 5u;
            const int32_t x0 = x < 4 ? 0 : x - 4, x1 = x + 4 >= W ? W - 1 : x + 4;
            const int32_t y0 = y < 4 ? 0 : y - 4, y1 = y + 4 >= H ? H - 1 : y + 4;
            uint32_t wx = 0, wy = 0;
            for (int32_t xx = x0; xx <= x1; xx++) {
                wx += g[xx > x ? xx - x : x - xx];
            }
            for (int32_t yy = y0; yy <= y1; yy++) {
                wy += g[yy > y ? yy - y : y - yy];
            }
            const uint32_t wsum = wx * wy; /* <= (9 * 4096)^2 < 2^31 */
            for (uint32_t c = 0; c < ch; c++) {
                uint64_t total = 0;
                for (int32_t yy = y0; yy <= y1; yy++) {
                    const uint8_t *row = src + (size_t)yy * (size_t)W * ch;
                    uint32_t r = 0;
                    for (int32_t xx = x0; xx <= x1; xx++) {
                        r += g[xx > x ? xx - x : x - xx] * (uint32_t)row[(size_t)xx * ch + c];
                    }
                    total += (uint64_t)g[yy > y ? yy - y : y - yy] * r;
                }
                /* round half up; the quotient is <= 255 */
                dst[p * ch + c] = (uint8_t)tdc_udiv64_32(2u * total + wsum, 2u * wsum);
            }
        }
    }
}

/* The frame of layer li that is recombined: the history's output, or the
 * assembled frame `b`. */
static const uint8_t *shown(const tdc_lasm_t *st, unsigned li, int b)
{
    return st->cfg.history ? tdc_lhist_output(&st->l[li].lh) : st->l[li].hist[b];
}

/* lin(S) V / 255 + lin(G) + lin(I), encoded (8-bit codes). */
static void recombine(tdc_lasm_t *st)
{
    const size_t wh = (size_t)st->cfg.width * st->cfg.height;
    const int nb = st->cur ^ 1;
    const uint8_t *S = shown(st, 0, nb);
    const uint8_t *V = st->ch[VIS] ? shown(st, VIS, nb) : NULL;
    const uint8_t *G = st->ch[2] ? shown(st, 2, nb) : NULL;
    const uint8_t *I = st->ch[3] ? shown(st, 3, nb) : NULL;
    if (!V && !G && !I) {
        memcpy(st->out, S, wh * 3u); /* one layer: nothing to combine */
        return;
    }
    const tdc_gamma_table_t *gt = st->cfg.panel->gamma;
    for (size_t p = 0; p < wh; p++) {
        for (uint32_t c = 0; c < 3u; c++) {
            uint32_t l = (uint32_t)tdc_gamma_decode(&gt[c], S[p * 3u + c]);
            if (V) {
                l = l * V[p] / 255u; /* <= 2^24 * 255 < 2^32 */
            }
            if (G) {
                l += (uint32_t)tdc_gamma_decode(&gt[c], G[p * 3u + c]);
            }
            if (I) {
                l += (uint32_t)tdc_gamma_decode(&gt[c], I[p * 3u + c]);
            }
            st->out[p * 3u + c] = (uint8_t)tdc_gamma_encode(&gt[c], (tdc_lin_t)l, 255u);
        }
    }
}

void tdc_lasm_start_at(tdc_lasm_t *st, uint32_t frame)
{
    st->next_frame = frame;
    st->have_subframe = 0;
}

tdc_status_t tdc_lasm_assemble(tdc_lasm_t *st, uint32_t frame)
{
    if (!st) {
        return TDC_ERR_ARG;
    }
    if (frame != st->next_frame) {
        return TDC_ERR_FRAME;
    }
    if (st->splat && st->cfg.splat_radius && st->kind[VIS] == TDC_LAYER_MV_SHADOW) {
        splat(st);
    }
    for (unsigned i = 0; i < TDC_LAYER_MAX; i++) {
        if (st->ch[i]) {
            assemble_layer(st, i, frame);
            cleanup_layer(st, i);
            if (st->cfg.history) {
                /* eq. 2 on the assembled frame, along the vectors it used;
                 * G of eq. 4 on the visibility layer */
                const tdc_status_t s = tdc_lhist_step(&st->l[i].lh, st->l[i].hist[st->cur ^ 1], st->hmv,
                                                      i == VIS ? st->weight : NULL);
                if (s != TDC_OK) {
                    return s;
                }
            }
        }
    }
    recombine(st);
    st->cur ^= 1;
    memset(st->newmask, 0, (size_t)st->cfg.width * st->cfg.height);
    st->have_subframe = 0;
    st->present = 0;
    st->next_frame = frame + 1u;
    st->stats.frames++;
    return TDC_OK;
}

const uint8_t *tdc_lasm_output(const tdc_lasm_t *st, int *stride_bytes)
{
    if (stride_bytes) {
        *stride_bytes = (int)st->cfg.width * 3;
    }
    return st->out;
}

const uint8_t *tdc_lasm_layer(const tdc_lasm_t *st, unsigned type, unsigned *ch)
{
    if (type < 1u || type > TDC_LAYER_MAX || !st->ch[type - 1u]) {
        return NULL;
    }
    if (ch) {
        *ch = st->ch[type - 1u];
    }
    return shown(st, type - 1u, st->cur);
}
