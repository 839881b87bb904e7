/*
 * tdc_sim_heatmap.c - the judge's visible-difference map (tdc_sim_heatmap.h).
 *
 * Cost per frame: one expand per band level (4/3 of a frame of 5-tap
 * passes) and a pow per pixel, eye 0 only.  Measured: trm family, 128x96,
 * 48 refreshes, judged: 8.97 / 9.00 CPU s with the heat maps (-o) against
 * 9.10 / 8.85 without, i.e. within the noise of the shared machine.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/tdc_fvvdp.h"
#include "simulator/tdc_sim_heatmap.h"
#include "tdc_png.h"

/* Colour scale (tdc_sim_heatmap.h): red at 3 JOD, full tint from 0.5. */
#define HEAT_TOP 3.0
#define HEAT_FULL 0.5

struct tdc_sim_heatmap {
    int w, h, nb, frames;
    tdc_fvvdp_pyr_t pyr;
    double *band[TDC_FVVDP_MAX_LEVELS];
    double *a, *b, *tmp;  /* collapse: two levels and the expand's scratch */
    double *map, *ctx;    /* sums over frames: dmap and the reference's luminance */
    double *mean;         /* map / frames (tdc_sim_heatmap_map) */
};

tdc_sim_heatmap_t *tdc_sim_heatmap_new(int w, int h, double ppd)
{
    tdc_sim_heatmap_t *hm = calloc(1, sizeof *hm);
    if (!hm || tdc_fvvdp_pyr_layout(&hm->pyr, w, h, ppd) != 0 || hm->pyr.levels < 2) {
        free(hm);
        return NULL;
    }
    hm->w = w;
    hm->h = h;
    hm->nb = hm->pyr.levels - 1; /* the bands the metric judges (not the baseband) */
    size_t n = (size_t)w * h;
    int ok = 1;
    for (int l = 0; l < hm->nb; l++) {
        ok &= (hm->band[l] = calloc((size_t)hm->pyr.w[l] * hm->pyr.h[l], sizeof(double))) != NULL;
    }
    ok &= (hm->a = calloc(n, sizeof(double))) != NULL;
    ok &= (hm->b = calloc(n, sizeof(double))) != NULL;
    ok &= (hm->tmp = calloc(n, sizeof(double))) != NULL;
    ok &= (hm->map = calloc(n, sizeof(double))) != NULL;
    ok &= (hm->ctx = calloc(n, sizeof(double))) != NULL;
    ok &= (hm->mean = calloc(n, sizeof(double))) != NULL;
    if (!ok) {
        tdc_sim_heatmap_free(hm);
        return NULL;
    }
    return hm;
}

void tdc_sim_heatmap_free(tdc_sim_heatmap_t *hm)
{
    if (!hm) {
        return;
    }
    for (int l = 0; l < TDC_FVVDP_MAX_LEVELS; l++) {
        free(hm->band[l]);
    }
    free(hm->a);
    free(hm->b);
    free(hm->tmp);
    free(hm->map);
    free(hm->ctx);
    free(hm->mean);
    free(hm);
}

double *const *tdc_sim_heatmap_bands(tdc_sim_heatmap_t *hm)
{
    for (int l = 0; l < hm->nb; l++) {
        memset(hm->band[l], 0, (size_t)hm->pyr.w[l] * hm->pyr.h[l] * sizeof(double));
    }
    return hm->band;
}

void tdc_sim_heatmap_add(tdc_sim_heatmap_t *hm, const float *ref_y)
{
    /* collapse, coarsest band first: cur = expand(cur) + band[l] */
    int top = hm->nb - 1;
    double *cur = hm->a, *next = hm->b;
    memcpy(cur, hm->band[top], (size_t)hm->pyr.w[top] * hm->pyr.h[top] * sizeof(double));
    for (int l = top - 1; l >= 0; l--) {
        int bw = hm->pyr.w[l], bh = hm->pyr.h[l];
        tdc_fvvdp_expand(cur, bw, bh, next, hm->tmp);
        for (size_t i = 0; i < (size_t)bw * bh; i++) {
            next[i] += hm->band[l][i];
        }
        double *t = cur;
        cur = next;
        next = t;
    }
    size_t n = (size_t)hm->w * hm->h;
    for (size_t i = 0; i < n; i++) {
        /* the expand's kernel is non-negative, so is D: no clamp needed
         * beyond rounding */
        hm->map[i] += 10.0 - tdc_fvvdp_q2jod(cur[i] > 0.0 ? cur[i] : 0.0);
        hm->ctx[i] += ref_y[i];
    }
    hm->frames++;
}

int tdc_sim_heatmap_frames(const tdc_sim_heatmap_t *hm)
{
    return hm->frames;
}

const double *tdc_sim_heatmap_map(const tdc_sim_heatmap_t *hm)
{
    if (!hm->frames) {
        return NULL;
    }
    size_t n = (size_t)hm->w * hm->h;
    for (size_t i = 0; i < n; i++) {
        hm->mean[i] = hm->map[i] / hm->frames;
    }
    return hm->mean;
}

static uint8_t u8(double v)
{
    v = v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
    return (uint8_t)(255.0 * v + 0.5);
}

int tdc_sim_heatmap_write(const tdc_sim_heatmap_t *hm, const char *path, char *err, size_t errlen)
{
    const double *d = tdc_sim_heatmap_map(hm);
    size_t n = (size_t)hm->w * hm->h;
    uint8_t *img = d ? malloc(3 * n) : NULL;
    if (!img) {
        snprintf(err, errlen, "%s: %s", path, d ? "out of memory" : "no frame was judged (the run is within the warm-up)");
        return -1;
    }
    /* context: log luminance, min..max -> 0.15..0.65 grey */
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        double l = log10(fmax(hm->ctx[i] / hm->frames, 1e-3));
        lo = fmin(lo, l);
        hi = fmax(hi, l);
    }
    double span = hi - lo > 1e-6 ? hi - lo : 1.0;
    for (size_t i = 0; i < n; i++) {
        double g = 0.15 + 0.5 * (log10(fmax(hm->ctx[i] / hm->frames, 1e-3)) - lo) / span;
        double a = d[i] < 0.0 ? 0.0 : (d[i] > HEAT_TOP ? 1.0 : d[i] / HEAT_TOP);
        double c[3] = { fmin(1.0, 2.0 * a), fmin(1.0, 2.0 - 2.0 * a), 0.0 }; /* green, yellow, red */
        double wt = fmin(1.0, d[i] / HEAT_FULL);
        for (int k = 0; k < 3; k++) {
            img[3 * i + k] = u8((1.0 - wt) * g + wt * c[k]);
        }
    }
    int rc = tdc_png_write(path, img, hm->w, hm->h, 8, (size_t)hm->w * 3, err, errlen);
    free(img);
    return rc ? -1 : 0;
}
