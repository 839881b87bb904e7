/* tdc_sim_blockmatch.c - hierarchical block matching on decoded frames (tdc_sim_blockmatch.h). */
#include "simulator/tdc_sim_blockmatch.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_par.h"

int tdc_bm_init(tdc_bm_t *bm, int w, int h)
{
    memset(bm, 0, sizeof(*bm));
    for (int l = 0; l < TDC_BM_LEVELS; l++) {
        bm->w[l] = l ? (bm->w[l - 1] + 1) / 2 : w;
        bm->h[l] = l ? (bm->h[l - 1] + 1) / 2 : h;
        bm->bw[l] = (bm->w[l] + TDC_BM_BLOCK - 1) / TDC_BM_BLOCK;
        bm->bh[l] = (bm->h[l] + TDC_BM_BLOCK - 1) / TDC_BM_BLOCK;
        size_t n = (size_t)bm->w[l] * bm->h[l];
        bm->lum[0][l] = malloc(n * sizeof(float));
        bm->lum[1][l] = malloc(n * sizeof(float));
        bm->vec[l] = calloc((size_t)bm->bw[l] * bm->bh[l] * 2, sizeof(float));
        if (!bm->lum[0][l] || !bm->lum[1][l] || !bm->vec[l]) {
            return -1;
        }
    }
    bm->med = calloc((size_t)bm->bw[0] * bm->bh[0] * 2, sizeof(float));
    return bm->med ? 0 : -1;
}

void tdc_bm_free(tdc_bm_t *bm)
{
    for (int l = 0; l < TDC_BM_LEVELS; l++) {
        free(bm->lum[0][l]);
        free(bm->lum[1][l]);
        free(bm->vec[l]);
    }
    free(bm->med);
    memset(bm, 0, sizeof(*bm));
}

/* Rec. 601 luma of the codes (0..1) and the 2x2 box pyramid above it. */
static void pyramid(tdc_bm_t *bm, int k, const uint8_t *rgb)
{
    size_t n = (size_t)bm->w[0] * bm->h[0];
    float *l0 = bm->lum[k][0];
    for (size_t i = 0; i < n; i++) {
        l0[i] = (0.299f * rgb[3 * i] + 0.587f * rgb[3 * i + 1] + 0.114f * rgb[3 * i + 2]) * (1.0f / 255.0f);
    }
    for (int l = 1; l < TDC_BM_LEVELS; l++) {
        const float *s = bm->lum[k][l - 1];
        float *d = bm->lum[k][l];
        int sw = bm->w[l - 1], sh = bm->h[l - 1];
        for (int y = 0; y < bm->h[l]; y++) {
            int y0 = 2 * y, y1 = 2 * y + 1 < sh ? 2 * y + 1 : 2 * y;
            for (int x = 0; x < bm->w[l]; x++) {
                int x0 = 2 * x, x1 = 2 * x + 1 < sw ? 2 * x + 1 : 2 * x;
                d[(size_t)y * bm->w[l] + x] = 0.25f * (s[(size_t)y0 * sw + x0] + s[(size_t)y0 * sw + x1] +
                                                       s[(size_t)y1 * sw + x0] + s[(size_t)y1 * sw + x1]);
            }
        }
    }
}

/* Mean absolute luma difference of block (bx, by) of level l displaced by
 * the integer vector (dx, dy) (prev sampled with clamped coordinates), plus
 * the length penalty. */
static double sad(const tdc_bm_t *bm, int l, int bx, int by, int dx, int dy)
{
    int w = bm->w[l], h = bm->h[l];
    const float *p = bm->lum[0][l], *c = bm->lum[1][l];
    int x0 = bx * TDC_BM_BLOCK, y0 = by * TDC_BM_BLOCK;
    int x1 = x0 + TDC_BM_BLOCK < w ? x0 + TDC_BM_BLOCK : w, y1 = y0 + TDC_BM_BLOCK < h ? y0 + TDC_BM_BLOCK : h;
    double s = 0;
    for (int y = y0; y < y1; y++) {
        int yy = y + dy < 0 ? 0 : (y + dy >= h ? h - 1 : y + dy);
        const float *cr = c + (size_t)y * w, *pr = p + (size_t)yy * w;
        for (int x = x0; x < x1; x++) {
            int xx = x + dx < 0 ? 0 : (x + dx >= w ? w - 1 : x + dx);
            s += fabsf(cr[x] - pr[xx]);
        }
    }
    return s / ((double)(x1 - x0) * (y1 - y0)) + TDC_BM_LAMBDA * (abs(dx) + abs(dy)) * (1 << l);
}

/* Vertex offset of the parabola through (-1, a), (0, b), (1, c), in [-0.5, 0.5]. */
static double parabola(double a, double b, double c)
{
    double den = a - 2 * b + c;
    if (den <= 1e-12) {
        return 0.0;
    }
    double o = 0.5 * (a - c) / den;
    return o < -0.5 ? -0.5 : (o > 0.5 ? 0.5 : o);
}

static void search_level(tdc_bm_t *bm, int l)
{
    int top = l == TDC_BM_LEVELS - 1;
    int r = top ? (TDC_BM_RANGE + (1 << l) - 1) >> l : 1;
    int bw = bm->bw[l], bh = bm->bh[l];
    TDC_PAR_FOR((long)bw * bh * TDC_BM_BLOCK * TDC_BM_BLOCK * (top ? (2 * r + 1) * (2 * r + 1) : 45))
    for (int by = 0; by < bh; by++) {
        for (int bx = 0; bx < bw; bx++) {
            /* candidates: 0 at the top, else twice the parent's vector and its 4 neighbours' */
            int cand[6][2], nc = 0;
            if (top) {
                cand[nc][0] = cand[nc][1] = 0;
                nc++;
            } else {
                int pbw = bm->bw[l + 1], pbh = bm->bh[l + 1];
                static const int nb[5][2] = {{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}};
                for (int k = 0; k < 5; k++) {
                    int px = bx / 2 + nb[k][0], py = by / 2 + nb[k][1];
                    if (px < 0 || py < 0 || px >= pbw || py >= pbh) {
                        continue;
                    }
                    const float *v = bm->vec[l + 1] + 2 * ((size_t)py * pbw + px);
                    cand[nc][0] = 2 * (int)lrintf(v[0]);
                    cand[nc][1] = 2 * (int)lrintf(v[1]);
                    nc++;
                }
                if (l == 0) {
                    cand[nc][0] = cand[nc][1] = 0;
                    nc++;
                }
            }
            double best = DBL_MAX;
            int bx0 = 0, by0 = 0;
            for (int k = 0; k < nc; k++) {
                for (int dy = -r; dy <= r; dy++) {
                    for (int dx = -r; dx <= r; dx++) {
                        double s = sad(bm, l, bx, by, cand[k][0] + dx, cand[k][1] + dy);
                        if (s < best) {
                            best = s;
                            bx0 = cand[k][0] + dx;
                            by0 = cand[k][1] + dy;
                        }
                    }
                }
            }
            float *v = bm->vec[l] + 2 * ((size_t)by * bw + bx);
            v[0] = (float)bx0;
            v[1] = (float)by0;
            if (l == 0) { /* sub-pixel part from the SAD parabola (without the length penalty) */
                double lam = TDC_BM_LAMBDA * (abs(bx0) + abs(by0));
                double sb = best - lam;
                double sxm = sad(bm, 0, bx, by, bx0 - 1, by0) - TDC_BM_LAMBDA * (abs(bx0 - 1) + abs(by0));
                double sxp = sad(bm, 0, bx, by, bx0 + 1, by0) - TDC_BM_LAMBDA * (abs(bx0 + 1) + abs(by0));
                double sym = sad(bm, 0, bx, by, bx0, by0 - 1) - TDC_BM_LAMBDA * (abs(bx0) + abs(by0 - 1));
                double syp = sad(bm, 0, bx, by, bx0, by0 + 1) - TDC_BM_LAMBDA * (abs(bx0) + abs(by0 + 1));
                v[0] += (float)parabola(sxm, sb, sxp);
                v[1] += (float)parabola(sym, sb, syp);
            }
        }
    }
}

static float median9(float *a)
{
    for (int i = 1; i < 9; i++) { /* insertion sort of 9 */
        float x = a[i];
        int j = i - 1;
        while (j >= 0 && a[j] > x) {
            a[j + 1] = a[j];
            j--;
        }
        a[j + 1] = x;
    }
    return a[4];
}

void tdc_bm_estimate(tdc_bm_t *bm, const uint8_t *prev, const uint8_t *cur, double scale, int16_t *mv)
{
    pyramid(bm, 0, prev);
    pyramid(bm, 1, cur);
    for (int l = TDC_BM_LEVELS - 1; l >= 0; l--) {
        search_level(bm, l);
    }
    int bw = bm->bw[0], bh = bm->bh[0];
    for (int by = 0; by < bh; by++) {
        for (int bx = 0; bx < bw; bx++) {
            for (int c = 0; c < 2; c++) {
                float a[9];
                int k = 0;
                for (int j = -1; j <= 1; j++) {
                    for (int i = -1; i <= 1; i++) {
                        int xx = bx + i < 0 ? 0 : (bx + i >= bw ? bw - 1 : bx + i);
                        int yy = by + j < 0 ? 0 : (by + j >= bh ? bh - 1 : by + j);
                        a[k++] = bm->vec[0][2 * ((size_t)yy * bw + xx) + c];
                    }
                }
                bm->med[2 * ((size_t)by * bw + bx) + c] = median9(a);
            }
        }
    }
    int w = bm->w[0], h = bm->h[0];
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const float *v = bm->med + 2 * ((size_t)(y / TDC_BM_BLOCK) * bw + x / TDC_BM_BLOCK);
            int16_t *o = mv + 2 * ((size_t)y * w + x);
            o[0] = (int16_t)lrint(v[0] * scale * 16.0);
            o[1] = (int16_t)lrint(v[1] * scale * 16.0);
        }
    }
}
