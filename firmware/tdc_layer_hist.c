/*
 * tdc_layer_hist.c - exponential history per layer (tdc_layer_hist.h).
 */
#include "tdc_layer_hist.h"

#include "tdc_math.h"

static int cfg_ok(const tdc_lhist_config_t *c)
{
    return c && c->width >= 1u && c->height >= 1u && c->width <= TDC_LHIST_MAX_DIM &&
           c->height <= TDC_LHIST_MAX_DIM && (c->channels == 1u || c->channels == 3u) &&
           (c->clamp_k == 0u || c->clamp_k == 1u || c->clamp_k == 3u) && c->alpha_q15 >= 1u && c->alpha_q15 <= 32768u;
}

static void carve(tdc_lhist_t *st, tdc_arena_t *arena, const tdc_lhist_config_t *c)
{
    TDC_LHIST_ARENA(TDC_ARENA_CARVE, c->width, c->height, c->channels)
}

size_t tdc_lhist_get_size(const tdc_lhist_config_t *cfg)
{
    if (!cfg_ok(cfg)) {
        return 0;
    }
    tdc_lhist_t dry;
    tdc_arena_t a;
    tdc_arena_dry(&a);
    carve(&dry, &a, cfg);
    return tdc_arena_size(&a);
}

tdc_status_t tdc_lhist_init(tdc_lhist_t *st, const tdc_lhist_config_t *cfg, void *arena, size_t n)
{
    if (!st || !cfg_ok(cfg)) {
        return TDC_ERR_ARG;
    }
    const size_t need = tdc_lhist_get_size(cfg);
    tdc_arena_t a;
    if (!tdc_arena_over(&a, arena, n)) {
        return TDC_ERR_ARG;
    }
    if (n < need) {
        return TDC_ERR_SIZE;
    }
    st->cfg = *cfg;
    carve(st, &a, cfg);
    st->cur = 0;
    st->have = 0;
    st->stats.frames = st->stats.reset = st->stats.clamped = 0u;
    return TDC_OK;
}

/* floor(x / d) for the window sizes d = n in {1, 2, 3, 4, 6, 9} and d = n^2,
 * x < 2^26, by a multiply with ceil(2^40 / d): the error term x (d ceil(2^40
 * / d) - 2^40) / 2^40 < x d / 2^40 stays below 1/d for x < 2^40 / d^2
 * (2^40 / 81^2 > 2^27): exact, and no divide instruction in the pixel loop
 * (two divisions per channel cost 4x the rest of the step on x86). */
#define R40(d) [d] = (((uint64_t)1 << 40) + (d) - 1u) / (d)
static const uint64_t k_recip40[82] = {R40(1),  R40(2),  R40(3),  R40(4),  R40(6),  R40(9),
                                       R40(16), R40(36), R40(81)};
static inline uint32_t div_win(uint32_t x, uint32_t d) { return (uint32_t)(((uint64_t)x * k_recip40[d]) >> 40); }

/* Bilinear sample (Q8) of the Q8 history at (xq, yq), Q4 pixel-index
 * coordinates inside [0, (W-1) 16] x [0, (H-1) 16]. */
static void fetch(const uint16_t *h, uint32_t W, uint32_t ch, int32_t xq, int32_t yq, uint32_t out[3])
{
    const uint32_t x0 = (uint32_t)xq >> 4, y0 = (uint32_t)yq >> 4, fx = (uint32_t)xq & 15u, fy = (uint32_t)yq & 15u;
    const uint32_t x1 = fx ? x0 + 1u : x0, y1 = fy ? y0 + 1u : y0;
    const uint32_t w00 = (16u - fx) * (16u - fy), w10 = fx * (16u - fy), w01 = (16u - fx) * fy, w11 = fx * fy;
    const uint16_t *a = h + ((size_t)y0 * W + x0) * ch, *b = h + ((size_t)y0 * W + x1) * ch;
    const uint16_t *c = h + ((size_t)y1 * W + x0) * ch, *d = h + ((size_t)y1 * W + x1) * ch;
    for (uint32_t k = 0; k < ch; k++) {
        out[k] = (a[k] * w00 + b[k] * w10 + c[k] * w01 + d[k] * w11 + 128u) >> 8;
    }
}

tdc_status_t tdc_lhist_step(tdc_lhist_t *st, const uint8_t *x, const int16_t *mv, const uint16_t *falloff)
{
    if (!st || !x) {
        return TDC_ERR_ARG;
    }
    const uint32_t W = st->cfg.width, H = st->cfg.height, ch = st->cfg.channels, k = st->cfg.clamp_k;
    const uint32_t alpha = st->cfg.alpha_q15;
    const uint16_t *prev = st->hist[st->cur];
    uint16_t *next = st->hist[st->cur ^ 1];
    for (uint32_t y = 0; y < H; y++) {
        for (uint32_t px = 0; px < W; px++) {
            const size_t p = (size_t)y * W + px;
            const uint8_t *xv = x + p * ch;
            uint32_t h[3] = {0u, 0u, 0u};
            int ok = 0;
            if (st->have) {
                const int32_t xq = (int32_t)(px << 4) + (mv ? mv[2u * p] : 0);
                const int32_t yq = (int32_t)(y << 4) + (mv ? mv[2u * p + 1u] : 0);
                ok = xq >= 0 && yq >= 0 && xq <= (int32_t)((W - 1u) << 4) && yq <= (int32_t)((H - 1u) << 4);
                if (ok) {
                    fetch(prev, W, ch, xq, yq, h);
                }
            }
            if (!ok) {
                st->stats.reset++;
                for (uint32_t c = 0; c < ch; c++) {
                    next[p * ch + c] = (uint16_t)(xv[c] << 8);
                    st->out[p * ch + c] = xv[c];
                }
                continue;
            }
            if (k) {
                const uint32_t ya = y ? y - 1u : 0u, yb = y + 1u < H ? y + 1u : H - 1u;
                const uint32_t xa = px ? px - 1u : 0u, xb = px + 1u < W ? px + 1u : W - 1u;
                const uint32_t n = (yb - ya + 1u) * (xb - xa + 1u);
                for (uint32_t c = 0; c < ch; c++) {
                    uint32_t s1 = 0u, s2 = 0u;
                    for (uint32_t yy = ya; yy <= yb; yy++) {
                        for (uint32_t xx = xa; xx <= xb; xx++) {
                            const uint32_t v = x[((size_t)yy * W + xx) * ch + c];
                            s1 += v;
                            s2 += v * v;
                        }
                    }
                    /* mu in Q8 = 256 s1 / n; sigma in Q8 from the variance
                     * in Q4 (16 (n s2 - s1^2) / n^2 <= 16 * 255^2 / 4 < 2^20):
                     * tdc_sqrt_q8 / 4, within 12 / 4 Q8 (0.012 code) */
                    const uint32_t mu = div_win((s1 << 8) + n / 2u, n);
                    const uint32_t sd = tdc_sqrt_q8(div_win((n * s2 - s1 * s1) << 4, n * n)) >> 2;
                    const uint32_t ks = k * sd;
                    const uint32_t lo = mu > ks ? mu - ks : 0u, hi = mu + ks < 65280u ? mu + ks : 65280u;
                    const uint32_t hc = h[c] < lo ? lo : (h[c] > hi ? hi : h[c]);
                    st->stats.clamped += hc != h[c];
                    h[c] = hc;
                }
            }
            const uint32_t a = falloff ? 32768u - (((32768u - alpha) * falloff[p]) >> 15) : alpha;
            for (uint32_t c = 0; c < ch; c++) {
                const uint32_t v = (a * ((uint32_t)xv[c] << 8) + (32768u - a) * h[c] + 16384u) >> 15;
                next[p * ch + c] = (uint16_t)v;
                st->out[p * ch + c] = (uint8_t)((v + 128u) >> 8);
            }
        }
    }
    st->cur ^= 1;
    st->have = 1;
    st->stats.frames++;
    return TDC_OK;
}

const uint8_t *tdc_lhist_output(const tdc_lhist_t *st) { return st ? st->out : NULL; }

const uint16_t *tdc_lhist_history_q8(const tdc_lhist_t *st) { return st ? st->hist[st->cur] : NULL; }
