/*
 * ref_layer_hist.c - double reference of the per-layer history
 * (ref_layer_hist.h).  Straight from the equations.
 */
#include "ref_layer_hist.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int tdc_ref_lhist_init(tdc_ref_lhist_t *r, const tdc_lhist_config_t *cfg)
{
    const size_t n = (size_t)cfg->width * cfg->height * cfg->channels;
    memset(r, 0, sizeof *r);
    r->cfg = *cfg;
    r->hist = calloc(n, sizeof(double));
    r->next = calloc(n, sizeof(double));
    r->out = calloc(n, sizeof(double));
    if (!r->hist || !r->next || !r->out) {
        tdc_ref_lhist_free(r);
        return -1;
    }
    return 0;
}

void tdc_ref_lhist_free(tdc_ref_lhist_t *r)
{
    free(r->hist);
    free(r->next);
    free(r->out);
    memset(r, 0, sizeof *r);
}

void tdc_ref_lhist_step(tdc_ref_lhist_t *r, const uint8_t *x, const int16_t *mv, const uint16_t *falloff)
{
    const int W = r->cfg.width, H = r->cfg.height, ch = r->cfg.channels, k = r->cfg.clamp_k;
    const double alpha = r->cfg.alpha_q15 / 32768.0;
    for (int y = 0; y < H; y++) {
        for (int px = 0; px < W; px++) {
            const size_t p = (size_t)y * W + px;
            const double fx = px + (mv ? mv[2 * p] / 16.0 : 0.0), fy = y + (mv ? mv[2 * p + 1] / 16.0 : 0.0);
            const int ok = r->have && fx >= 0 && fy >= 0 && fx <= W - 1 && fy <= H - 1;
            for (int c = 0; c < ch; c++) {
                const double xv = x[p * ch + c];
                double v = xv;
                if (ok) {
                    const int x0 = (int)floor(fx), y0 = (int)floor(fy);
                    const int x1 = x0 + 1 < W ? x0 + 1 : x0, y1 = y0 + 1 < H ? y0 + 1 : y0;
                    const double ax = fx - x0, ay = fy - y0;
                    double h = (1 - ax) * (1 - ay) * r->hist[((size_t)y0 * W + x0) * ch + c] +
                               ax * (1 - ay) * r->hist[((size_t)y0 * W + x1) * ch + c] +
                               (1 - ax) * ay * r->hist[((size_t)y1 * W + x0) * ch + c] +
                               ax * ay * r->hist[((size_t)y1 * W + x1) * ch + c];
                    if (k) {
                        double s1 = 0, s2 = 0;
                        int n = 0;
                        for (int yy = y - 1; yy <= y + 1; yy++) {
                            for (int xx = px - 1; xx <= px + 1; xx++) {
                                if (xx < 0 || yy < 0 || xx >= W || yy >= H) {
                                    continue;
                                }
                                const double q = x[((size_t)yy * W + xx) * ch + c];
                                s1 += q;
                                s2 += q * q;
                                n++;
                            }
                        }
                        const double mu = s1 / n, sd = sqrt(fmax(0.0, s2 / n - mu * mu));
                        h = fmin(fmax(h, fmax(0.0, mu - k * sd)), fmin(255.0, mu + k * sd));
                    }
                    const double a = falloff ? 1.0 - falloff[p] / 32768.0 * (1.0 - alpha) : alpha;
                    v = a * xv + (1 - a) * h;
                }
                r->next[p * ch + c] = v;
                r->out[p * ch + c] = v;
            }
        }
    }
    double *t = r->hist;
    r->hist = r->next;
    r->next = t;
    r->have = 1;
}
