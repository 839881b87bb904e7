/*
 * bench_layer_hist.c - speed of the per-layer history (firmware/
 * tdc_layer_hist.h, Zeng eq. 2/4) on one core at 960x540, beside the
 * memcpy cost of an RGB888 pixel measured in this run (the ratio is the figure to keep:
 * the host is shared).  CPU time of the benchmark thread, best of 3 runs of
 * FRAMES frames of the noisy panning layer of tests/golden/
 * tdc_lhist_content.h.  Usage: bench_layer_hist [frames]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench/bench_clock.h"
#include "golden/tdc_lhist_content.h"
#include "tdc_layer_hist.h"

#define BW 960
#define BH 540
#define NF 4

static uint8_t x[NF][BW * BH * 3];
static int16_t mv[NF][BW * BH * 2];
static uint16_t g[NF][BW * BH];

static double run(const char *label, uint8_t ch, uint8_t k, uint8_t falloff, int frames)
{
    const tdc_lhist_content_t c = {BW, BH, ch, 30, 20, -6, 0, falloff, 1u};
    for (int f = 0; f < NF; f++) {
        tdc_lhist_content(&c, (uint32_t)f, x[f], mv[f], g[f]);
    }
    const tdc_lhist_config_t cfg = {BW, BH, ch, k, 3277};
    const size_t n = tdc_lhist_get_size(&cfg);
    void *arena = aligned_alloc(8, n);
    tdc_lhist_t st;
    double best = 1e30;
    for (int r = 0; r < 3; r++) {
        if (!arena || tdc_lhist_init(&st, &cfg, arena, n) != TDC_OK) {
            printf("bench_layer_hist: init failed\n");
            exit(1);
        }
        double t0 = now_s();
        for (int f = 0; f < frames; f++) {
            if (tdc_lhist_step(&st, x[f % NF], mv[f % NF], falloff ? g[f % NF] : NULL) != TDC_OK) {
                printf("bench_layer_hist: step failed\n");
                exit(1);
            }
        }
        double t = (now_s() - t0) / frames;
        best = t < best ? t : best;
    }
    const double ns = 1e9 * best / ((double)BW * BH);
    printf("  %-52s %7.2f ms/frame %6.2f ns/px  arena %4.1f B/px\n", label, 1e3 * best, ns, (double)n / (BW * BH));
    free(arena);
    return ns;
}

int main(int argc, char **argv)
{
    const int frames = argc > 1 ? atoi(argv[1]) : 20;
    printf("bench_layer_hist: %dx%d, %d frames, best of 3 (thread CPU time; a shared host: read the ratios)\n", BW,
           BH, frames);
    /* bytes/s of a 64 MiB memcpy -> ns per RGB888 pixel copied */
    const double mc = 3e9 / memcpy_bandwidth();
    const double a = run("colour layer (eq. 2, 3 sigma)", 3, 3, 0, frames);
    const double b = run("visibility (eq. 2 + eq. 4 falloff, 3 sigma)", 1, 3, 1, frames);
    const double d = run("colour layer, no clamp", 3, 0, 0, frames);
    printf("  memcpy of an RGB888 pixel: %.3f ns; colour layer %.0fx memcpy, visibility %.0fx, no clamp %.0fx\n",
           mc, a / mc, b / mc, d / mc);
    return 0;
}
