/*
 * ref_layers.c - double-precision reference of the layered tile assembly
 * (ref_layers.h).  Straight from the equations: no tables, no Q formats.
 */
#include "ref_layers.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ref_layer_hist.h"
#include "tdc_ordering.h"
#include "tdc_free.h"

#define NL TDC_LAYER_MAX
#define VIS (TDC_LAYER_VISIBILITY - 1)

static const int k_ch[NL] = {3, 1, 3, 3};

struct tdc_ref_lasm {
    tdc_ref_lasm_config_t cfg;
    int ch[NL], kind[NL];
    uint8_t *hist[NL][2], *slots[NL], *window[NL];
    int16_t *mv[NL], *splat;
    uint8_t *newmask, *pattern;
    uint16_t *weight;
    double *scratch, *sigma, *exact;
    uint8_t *out;
    /* history: per layer, the vectors used, the rounded outputs */
    tdc_ref_lhist_t lh[NL];
    int16_t *hmv;
    uint8_t *lh_out[NL];
    int cur, have;
    unsigned present;
    uint32_t next;
};

tdc_ref_lasm_t *tdc_ref_lasm_new(const tdc_ref_lasm_config_t *cfg)
{
    tdc_ref_lasm_t *r = calloc(1, sizeof *r);
    if (!r) {
        return NULL;
    }
    r->cfg = *cfg;
    const size_t wh = (size_t)cfg->width * cfg->height;
    int ok = 1;
    for (int i = 0; i < NL; i++) {
        r->ch[i] = (cfg->layers & TDC_LAYER_PKT_TYPE(i + 1)) ? k_ch[i] : 0;
        r->kind[i] = TDC_LAYER_MV_SURFACE;
        if (!r->ch[i]) {
            continue;
        }
        for (int b = 0; b < 2; b++) {
            r->hist[i][b] = malloc(wh * r->ch[i]);
            ok = ok && r->hist[i][b];
            if (r->hist[i][b]) {
                memset(r->hist[i][b], i == VIS ? 255 : 0, wh * r->ch[i]);
            }
        }
        r->slots[i] = calloc(wh * r->ch[i] * 4, 1);
        r->window[i] = calloc(wh, 1);
        r->mv[i] = calloc(wh * 2, sizeof(int16_t));
        ok = ok && r->slots[i] && r->window[i] && r->mv[i];
        if (cfg->history && ok) {
            const tdc_lhist_config_t hc = {(uint16_t)cfg->width, (uint16_t)cfg->height, (uint8_t)r->ch[i],
                                           (uint8_t)cfg->clamp_k, (uint16_t)floor(cfg->alpha * 32768.0 + 0.5)};
            r->lh_out[i] = calloc(wh * r->ch[i], 1);
            ok = r->lh_out[i] && tdc_ref_lhist_init(&r->lh[i], &hc) == 0;
        }
    }
    r->splat = calloc(wh * 2, sizeof(int16_t));
    r->hmv = calloc(wh * 2, sizeof(int16_t));
    r->newmask = calloc(wh, 1);
    r->pattern = calloc(TDC_PATTERN_BYTES(cfg->width, cfg->height) + 1, 1);
    r->weight = malloc(wh * sizeof(uint16_t));
    r->scratch = calloc(wh * 3, sizeof(double));
    r->sigma = calloc(wh, sizeof(double));
    r->exact = calloc(wh * 3, sizeof(double));
    r->out = calloc(wh * 3, 1);
    if (!ok || !r->splat || !r->hmv || !r->newmask || !r->pattern || !r->weight || !r->scratch || !r->sigma || !r->exact ||
        !r->out) {
        tdc_ref_lasm_free(r);
        return NULL;
    }
    for (size_t p = 0; p < wh; p++) {
        r->weight[p] = TDC_LAYER_W_ONE;
    }
    return r;
}

void tdc_ref_lasm_free(tdc_ref_lasm_t *r)
{
    if (!r) {
        return;
    }
    for (int i = 0; i < NL; i++) {
        TDC_FREE_ALL(r->hist[i][0], r->hist[i][1], r->slots[i], r->window[i], r->mv[i], r->lh_out[i]);
        if (r->lh[i].hist) {
            tdc_ref_lhist_free(&r->lh[i]);
        }
    }
    TDC_FREE_ALL(r->hmv, r->splat, r->newmask, r->pattern, r->weight, r->scratch, r->sigma, r->exact, r->out, r);
}

int tdc_ref_lasm_ingest(tdc_ref_lasm_t *r, uint32_t frame, const tdc_layer_frame_t *lf, const uint8_t *pattern_bits)
{
    if (frame != r->next || r->have) {
        return -1;
    }
    const int W = r->cfg.width, H = r->cfg.height, tx = (W + 1) / 2, ty = (H + 1) / 2;
    const size_t wh = (size_t)W * H;
    if ((frame & 3u) == 0 && pattern_bits) {
        memcpy(r->pattern, pattern_bits, TDC_PATTERN_BYTES(W, H));
    }
    for (unsigned i = 0; i < lf->hdr.count; i++) {
        r->kind[lf->hdr.type[i] - 1] = lf->hdr.mv_kind[i];
    }
    const unsigned slot = (frame >> 2) & 3u;
    int n = 0;
    for (int y = 0; y < ty; y++) {
        for (int x = 0; x < tx; x++, n++) {
            unsigned pos = tdc_ordering_pixel(tdc_ordering_get(r->pattern, (uint32_t)n), frame & 3u);
            int px = 2 * x + (int)(pos & 1u), py = 2 * y + (int)(pos >> 1);
            if (px >= W || py >= H) {
                continue;
            }
            size_t p = (size_t)py * W + px;
            r->newmask[p] = 1;
            for (int i = 0; i < NL; i++) {
                if (!(lf->present & TDC_LAYER_PKT_TYPE(i + 1)) || !r->ch[i]) {
                    continue;
                }
                for (int c = 0; c < r->ch[i]; c++) {
                    r->slots[i][(slot * wh + p) * r->ch[i] + c] = lf->value[i][n * r->ch[i] + c];
                }
                r->mv[i][2 * p] = lf->mv[i][2 * n];
                r->mv[i][2 * p + 1] = lf->mv[i][2 * n + 1];
            }
            r->weight[p] = (lf->present & TDC_LAYER_PKT_FALLOFF) ? lf->falloff[n] : TDC_LAYER_W_ONE;
        }
    }
    r->present = lf->present;
    r->have = 1;
    return 0;
}

static void ref_splat(tdc_ref_lasm_t *r)
{
    const int W = r->cfg.width, H = r->cfg.height, R = r->cfg.splat_radius;
    const int16_t *mv = r->mv[VIS];
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            size_t p = (size_t)y * W + x;
            double sx = mv[2 * p], sy = mv[2 * p + 1];
            if (sx == 0.0 && sy == 0.0) {
                int cnt = 0;
                for (int yy = y - R; yy <= y + R; yy++) {
                    for (int xx = x - R; xx <= x + R; xx++) {
                        if (yy < 0 || xx < 0 || yy >= H || xx >= W) {
                            continue;
                        }
                        size_t q = (size_t)yy * W + xx;
                        if (mv[2 * q] || mv[2 * q + 1]) {
                            sx += mv[2 * q];
                            sy += mv[2 * q + 1];
                            cnt++;
                        }
                    }
                }
                if (cnt) {
                    sx = round(sx / cnt); /* vectors are Q4 integers on the wire */
                    sy = round(sy / cnt);
                }
            }
            r->splat[2 * p] = (int16_t)sx;
            r->splat[2 * p + 1] = (int16_t)sy;
        }
    }
}

static void ref_layer(tdc_ref_lasm_t *r, int li, uint32_t frame)
{
    const int W = r->cfg.width, H = r->cfg.height, ch = r->ch[li];
    const size_t wh = (size_t)W * H;
    const unsigned slot = (frame >> 2) & 3u;
    const uint8_t *prev = r->hist[li][r->cur];
    const uint8_t *cs = r->slots[li] + slot * wh * ch;
    const int16_t *mvb =
        (li == VIS && r->cfg.splat_radius && r->kind[li] == TDC_LAYER_MV_SHADOW) ? r->splat : r->mv[li];
    const int surface = r->kind[li] == TDC_LAYER_MV_SURFACE;
    const int have = r->have && (r->present & TDC_LAYER_PKT_TYPE(li + 1));
    const double k = r->cfg.clamp_k, alpha = r->cfg.alpha;
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            size_t p = (size_t)y * W + x;
            int mx = mvb[2 * p], my = mvb[2 * p + 1];
            if (surface) {
                int best = mx * mx + my * my;
                for (int yy = y - 1; yy <= y + 1; yy++) {
                    for (int xx = x - 1; xx <= x + 1; xx++) {
                        if (yy < 0 || xx < 0 || yy >= H || xx >= W) {
                            continue;
                        }
                        size_t q = (size_t)yy * W + xx;
                        int l2 = mvb[2 * q] * mvb[2 * q] + mvb[2 * q + 1] * mvb[2 * q + 1];
                        if (l2 > best) {
                            best = l2;
                            mx = mvb[2 * q];
                            my = mvb[2 * q + 1];
                        }
                    }
                }
            }
            r->hmv[2 * p] = (int16_t)mx;
            r->hmv[2 * p + 1] = (int16_t)my;
            double *o = r->scratch + p * ch;
            int isnew = have && r->newmask[p];
            r->sigma[p] = 0.0;
            if (mx == 0 && my == 0) {
                if (isnew) {
                    r->window[li][p] |= (uint8_t)(1u << slot);
                    for (int c = 0; c < ch; c++) {
                        double s = 0;
                        int n = 0;
                        for (unsigned q = 0; q < 4; q++) {
                            if (r->window[li][p] & (1u << q)) {
                                s += r->slots[li][(q * wh + p) * ch + c];
                                n++;
                            }
                        }
                        o[c] = s / n;
                    }
                } else {
                    for (int c = 0; c < ch; c++) {
                        o[c] = prev[p * ch + c];
                    }
                }
                continue;
            }
            if (isnew) {
                r->window[li][p] = (uint8_t)(1u << slot);
                for (int c = 0; c < ch; c++) {
                    o[c] = cs[p * ch + c];
                }
                continue;
            }
            r->window[li][p] = 0;
            /* bilinear at p + m (pixel-index coordinates), clamped to the frame */
            double sxp = x + mx / 16.0, syp = y + my / 16.0;
            sxp = sxp < 0 ? 0 : (sxp > W - 1 ? W - 1 : sxp);
            syp = syp < 0 ? 0 : (syp > H - 1 ? H - 1 : syp);
            int x0 = (int)floor(sxp), y0 = (int)floor(syp);
            double fx = sxp - x0, fy = syp - y0;
            int x1 = x0 + 1 < W ? x0 + 1 : x0, y1 = y0 + 1 < H ? y0 + 1 : y0;
            double h[3];
            for (int c = 0; c < ch; c++) {
                h[c] = (1 - fx) * (1 - fy) * prev[((size_t)y0 * W + x0) * ch + c] +
                       fx * (1 - fy) * prev[((size_t)y0 * W + x1) * ch + c] +
                       (1 - fx) * fy * prev[((size_t)y1 * W + x0) * ch + c] + fx * fy * prev[((size_t)y1 * W + x1) * ch + c];
            }
            int n = 0;
            double s1[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
            if (have) {
                for (int yy = y - 1; yy <= y + 1; yy++) {
                    for (int xx = x - 1; xx <= x + 1; xx++) {
                        if (yy < 0 || xx < 0 || yy >= H || xx >= W || (yy == y && xx == x)) {
                            continue;
                        }
                        size_t q = (size_t)yy * W + xx;
                        if (!r->newmask[q]) {
                            continue;
                        }
                        n++;
                        for (int c = 0; c < ch; c++) {
                            double v = cs[q * ch + c];
                            s1[c] += v;
                            s2[c] += v * v;
                        }
                    }
                }
            }
            if (n == 0) {
                for (int c = 0; c < ch; c++) {
                    o[c] = h[c];
                }
                continue;
            }
            const double G = (li == VIS ? r->weight[p] : TDC_LAYER_W_ONE) / 32768.0;
            double wc = 0.0;
            for (int c = 0; c < ch; c++) {
                double mu = s1[c] / n, var = s2[c] / n - mu * mu;
                double sd = sqrt(var > 0 ? var : 0);
                double v = fabs(h[c] - mu) > k * sd ? (h[c] > mu ? mu + k * sd : mu - k * sd) : h[c];
                if (v != h[c]) {
                    /* eq. 8 on values in [0, 1] */
                    double w = fabs(v - h[c]) / 255.0 / (h[c] / 255.0 + 0.001);
                    wc = fmax(wc, w);
                }
                o[c] = G * v + (1.0 - G) * mu;
            }
            double wa = 0.0;
            if (G < 1.0) {
                double alpha_v = 1.0 - G * (1.0 - alpha); /* eq. 4 */
                wa = (alpha_v - alpha) * (alpha_v - alpha); /* eq. 7 */
            }
            r->sigma[p] = fmin(wa + wc, 5.0);
        }
    }
}

static void ref_cleanup(tdc_ref_lasm_t *r, int li)
{
    const int W = r->cfg.width, H = r->cfg.height, ch = r->ch[li];
    uint8_t *dst = r->hist[li][r->cur ^ 1];
    for (int y = 0; y < H; y++) {
        for (int x = 0; x < W; x++) {
            size_t p = (size_t)y * W + x;
            double s = floor(r->sigma[p] * 16.0) / 16.0; /* the defined 1/16 px step */
            for (int c = 0; c < ch; c++) {
                double v;
                if (!r->cfg.cleanup || s <= 0.0) {
                    v = r->scratch[p * ch + c];
                } else {
                    double sum = 0, wsum = 0;
                    for (int yy = y - 4; yy <= y + 4; yy++) {
                        for (int xx = x - 4; xx <= x + 4; xx++) {
                            if (yy < 0 || xx < 0 || yy >= H || xx >= W) {
                                continue;
                            }
                            double d2 = (double)(xx - x) * (xx - x), e2 = (double)(yy - y) * (yy - y);
                            double w = exp(-d2 / (2 * s * s)) * exp(-e2 / (2 * s * s));
                            /* the layer before clean-up, as the firmware holds it: 8-bit */
                            double u = floor(r->scratch[((size_t)yy * W + xx) * ch + c] + 0.5);
                            sum += w * u;
                            wsum += w;
                        }
                    }
                    v = sum / wsum;
                }
                v = floor(v + 0.5);
                dst[p * ch + c] = (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
            }
        }
    }
}

int tdc_ref_lasm_assemble(tdc_ref_lasm_t *r, uint32_t frame)
{
    if (frame != r->next) {
        return -1;
    }
    if (r->ch[VIS] && r->cfg.splat_radius && r->kind[VIS] == TDC_LAYER_MV_SHADOW) {
        ref_splat(r);
    }
    for (int i = 0; i < NL; i++) {
        if (r->ch[i]) {
            ref_layer(r, i, frame);
            ref_cleanup(r, i);
            if (r->cfg.history) {
                const size_t n = (size_t)r->cfg.width * r->cfg.height * r->ch[i];
                tdc_ref_lhist_step(&r->lh[i], r->hist[i][r->cur ^ 1], r->hmv, i == VIS ? r->weight : NULL);
                for (size_t j = 0; j < n; j++) {
                    const double v = floor(r->lh[i].out[j] + 0.5);
                    r->lh_out[i][j] = (uint8_t)(v < 0 ? 0 : (v > 255 ? 255 : v));
                }
            }
        }
    }
    const int nb = r->cur ^ 1;
    const size_t wh = (size_t)r->cfg.width * r->cfg.height;
    const uint8_t *L[NL];
    for (int i = 0; i < NL; i++) {
        L[i] = r->cfg.history ? r->lh_out[i] : r->hist[i][nb];
    }
    for (size_t p = 0; p < wh; p++) {
        for (int c = 0; c < 3; c++) {
            const double g = r->cfg.gamma[c];
            double l = pow(L[0][p * 3 + c] / 255.0, g);
            if (r->ch[VIS]) {
                l *= L[VIS][p] / 255.0;
            }
            for (int i = 2; i < NL; i++) {
                if (r->ch[i]) {
                    l += pow(L[i][p * 3 + c] / 255.0, g);
                }
            }
            double code = 255.0 * pow(fmin(l, 1.0), 1.0 / g);
            r->exact[p * 3 + c] = code;
            r->out[p * 3 + c] = (uint8_t)floor(code + 0.5);
        }
    }
    r->cur = nb;
    memset(r->newmask, 0, wh);
    r->have = 0;
    r->present = 0;
    r->next = frame + 1;
    return 0;
}

const uint8_t *tdc_ref_lasm_output(const tdc_ref_lasm_t *r)
{
    return r->out;
}

const double *tdc_ref_lasm_output_exact(const tdc_ref_lasm_t *r)
{
    return r->exact;
}

const uint8_t *tdc_ref_lasm_layer(const tdc_ref_lasm_t *r, unsigned type)
{
    if (type < 1 || type > NL || !r->ch[type - 1]) {
        return NULL;
    }
    return r->cfg.history ? r->lh_out[type - 1] : r->hist[type - 1][r->cur];
}
