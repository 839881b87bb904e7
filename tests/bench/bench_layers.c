/*
 * bench_layers.c - speed of the layered tile assembly (firmware/tdc_layers.h)
 * on one core at 960x540, beside the single-layer assembly
 * (firmware/tdc_assemble.h, what a stream without layers runs: unchanged)
 * on the same shading samples and the memcpy bandwidth, all measured in
 * this run.  CPU time of the benchmark thread, best of 3 runs of FRAMES
 * frames (the layered stream of tests/golden/tdc_layer_content.h, fence at
 * 1.125 px/frame, glossy panning).  Usage: bench_layers [frames]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench/bench_clock.h"
#include "golden/tdc_layer_content.h"
#include "tdc_assemble.h"
#include "tdc_layers.h"
#include "tdc_panels.h"

#define BW 960
#define BH 540
#define NT (((BW + 1) / 2) * ((BH + 1) / 2))
#define NF 8 /* distinct subframes, repeated */

#define SH TDC_LAYER_PKT_TYPE(TDC_LAYER_SHADING)
#define VI TDC_LAYER_PKT_TYPE(TDC_LAYER_VISIBILITY)
#define GL TDC_LAYER_PKT_TYPE(TDC_LAYER_GLOSSY)
#define IN TDC_LAYER_PKT_TYPE(TDC_LAYER_INDIRECT)
#define FO TDC_LAYER_PKT_FALLOFF

static uint8_t *val[NF][TDC_LAYER_MAX];
static int16_t *mvs[NF][TDC_LAYER_MAX];
static uint16_t *wts[NF];
static tdc_layer_frame_t lfs[NF];
static uint8_t pattern[TDC_PATTERN_BYTES(BW, BH)];

static void make(const tdc_lcontent_t *c)
{
    for (int f = 0; f < NF; f++) {
        memset(&lfs[f], 0, sizeof lfs[f]);
        for (int t = 0; t < TDC_LAYER_MAX; t++) {
            if (!val[f][t]) {
                val[f][t] = malloc(NT * 3);
                mvs[f][t] = malloc(NT * 4);
            }
            lfs[f].value[t] = val[f][t];
            lfs[f].mv[t] = mvs[f][t];
        }
        if (!wts[f]) {
            wts[f] = malloc(NT * 2);
        }
        lfs[f].falloff = wts[f];
        tdc_layer_content_subframe(c, (uint32_t)f, pattern, &lfs[f]);
    }
}

static double run_layers_h(const char *label, const tdc_lcontent_t *c, uint8_t k, uint8_t cleanup, uint8_t splat,
                           uint8_t history, int frames)
{
    make(c);
    tdc_lasm_config_t cfg = {BW, BH, (uint16_t)(c->layers & 0xF), k, cleanup, splat, history, 3277,
                             &tdc_panel_htc_vive};
    size_t n = tdc_lasm_get_size(&cfg);
    void *arena = aligned_alloc(8, (n + 7) & ~(size_t)7);
    tdc_lasm_t *st = malloc(sizeof *st);
    double best = 1e30;
    for (int r = 0; r < 3; r++) {
        if (!arena || !st || tdc_lasm_init(st, &cfg, arena, n) != TDC_OK) {
            printf("bench_layers: init failed\n");
            exit(1);
        }
        double t0 = now_s();
        for (int f = 0; f < frames; f++) {
            if (tdc_lasm_ingest(st, (uint32_t)f, &lfs[f % NF], pattern) != TDC_OK ||
                tdc_lasm_assemble(st, (uint32_t)f) != TDC_OK) {
                printf("bench_layers: stage failed\n");
                exit(1);
            }
        }
        double t = (now_s() - t0) / frames;
        best = t < best ? t : best;
    }
    const double ns = 1e9 * best / ((double)BW * BH);
    printf("  %-44s %7.2f ms/frame %6.2f ns/px %7.1f Mpixel/s  arena %5.1f B/px  (reprojected %llu clamped %llu "
           "cleaned %llu splatted %llu)\n",
           label, 1e3 * best, ns, (double)BW * BH / best / 1e6, (double)n / ((double)BW * BH),
           (unsigned long long)st->stats.reprojected, (unsigned long long)st->stats.clamped,
           (unsigned long long)st->stats.cleaned, (unsigned long long)st->stats.splatted);
    free(st);
    free(arena);
    return ns;
}

static double run_layers(const char *label, const tdc_lcontent_t *c, uint8_t k, uint8_t cleanup, uint8_t splat,
                         int frames)
{
    return run_layers_h(label, c, k, cleanup, splat, 0, frames);
}

static double run_asm(const tdc_lcontent_t *c, int frames)
{
    make(c);
    tdc_asm_config_t cfg = {BW, BH};
    size_t n = tdc_asm_get_size(&cfg);
    void *arena = aligned_alloc(8, (n + 7) & ~(size_t)7);
    tdc_asm_t *st = malloc(sizeof *st);
    double best = 1e30;
    for (int r = 0; r < 3; r++) {
        if (!arena || !st || tdc_asm_init(st, &cfg, arena, n) != TDC_OK) {
            printf("bench_layers: asm init failed\n");
            exit(1);
        }
        double t0 = now_s();
        for (int f = 0; f < frames; f++) {
            const tdc_layer_frame_t *l = &lfs[f % NF];
            if (tdc_asm_ingest(st, (uint32_t)f, l->value[0], l->mv[0], (f & 3) == 0 ? pattern : NULL) != TDC_OK ||
                tdc_asm_assemble(st, (uint32_t)f) != TDC_OK) {
                printf("bench_layers: asm failed\n");
                exit(1);
            }
        }
        double t = (now_s() - t0) / frames;
        best = t < best ? t : best;
    }
    const double ns = 1e9 * best / ((double)BW * BH);
    printf("  %-44s %7.2f ms/frame %6.2f ns/px %7.1f Mpixel/s  arena %5.1f B/px\n",
           "single-layer tdc_asm (today's path)", 1e3 * best, ns, (double)BW * BH / best / 1e6,
           (double)n / ((double)BW * BH));
    free(st);
    free(arena);
    return ns;
}

int main(int argc, char **argv)
{
    const int frames = argc > 1 ? atoi(argv[1]) : 16;
    const double bw = memcpy_bandwidth();
    printf("bench_layers: %dx%d, %d frames per run, best of 3; memcpy bandwidth %.2f GB/s (read+write)\n", BW, BH,
           frames, bw / 1e9);
    const tdc_lcontent_t one = {BW, BH, SH, 24, 8, 0, 0, 0, 0, 0, 1u};
    const tdc_lcontent_t fence = {BW, BH, SH | VI | FO, 0, 0, 18, 0, 0, 1, 0, 1u};
    const tdc_lcontent_t all = {BW, BH, SH | VI | GL | IN | FO, 0, 0, 18, -30, 10, 1, 0, 1u};
    const double a = run_asm(&one, frames);
    const double l1 = run_layers("layered, one layer (pan 1.5 px)", &one, 1, 0, 0, frames);
    run_layers("layered, fence: shading + shadow, 3 sigma", &fence, 3, 0, 0, frames);
    run_layers("layered, fence + splat 2", &fence, 3, 0, 2, frames);
    const double z = run_layers("layered, fence + splat 2 + clean-up", &fence, 3, 1, 2, frames);
    const double l4 = run_layers("layered, all 4 layers + splat + clean-up", &all, 3, 1, 2, frames);
    const double l4h = run_layers_h("layered, all 4 layers + clean-up + history", &all, 3, 1, 2, 1, frames);
    printf("  ratios: layered one-layer / tdc_asm %.2f; fence Zeng + clean-up / tdc_asm %.2f; all 4 layers with "
           "history / without %.2f (history %.2f ns/px); memcpy of one RGB888 frame %.3f ns/px\n",
           l1 / a, z / a, l4h / l4, l4h - l4, 6.0 / bw * 1e9);
    return 0;
}
