/*
 * test_render_hash.c - a 64-bit FNV-1a hash of every output of every
 * built-in scene in every mode (full, reduced, subframe, ground truth; with
 * and without shadow and dual MVs; 480x270, 2 threads, frames 238..245), one
 * line per scene and option set: the hash of the outputs, then the hash of
 * the ray counts (work-saving changes move only the second).  A tool, not a registered test: run it
 * before and after a change that must not change pixels (the performance
 * work of issue 6) and compare the lines.  The hashes depend on the Embree,
 * libm and firmware ordering code of the build, so they are not a
 * portable golden.
 * Usage: test_render_hash [width height [threads]] (threads default 2: the
 * lines must not depend on it)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/tdc_render.h"

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++) {
        h ^= b[i];
        h *= 1099511628211ull;
    }
    return h;
}

int main(int argc, char **argv)
{
    int W = argc > 2 ? atoi(argv[1]) : 480, H = argc > 2 ? atoi(argv[2]) : 270, T = argc > 3 ? atoi(argv[3]) : 2;
    if (W < 2 || H < 2 || W > 4096 || H > 4096 || T < 1 || T > 64) {
        fprintf(stderr, "usage: %s [width height [threads]]\n", argv[0]);
        return 2;
    }
    static tdc_scene_t sc;
    char err[512];
    size_t n = (size_t)W * H;
    float *rgb = malloc(n * 12), *mvf = malloc(n * 8), *sw = malloc(n * 4), *dep = malloc(n * 4);
    int16_t *mv = malloc(n * 4), *mvs = malloc(n * 4), *mvd = malloc(n * 4);
    if (!rgb || !mvf || !sw || !dep || !mv || !mvs || !mvd) return 1;
    for (int si = 0; si < tdc_scene_builtin_count; si++) {
        const char *name = tdc_scene_builtin_names[si];
        if (tdc_scene_builtin(name, &sc, err, sizeof err) != TDC_SCENE_OK) {
            fprintf(stderr, "%s\n", err);
            return 1;
        }
        for (int opt = 0; opt < 2; opt++) {
            tdc_render_config_t cfg;
            tdc_render_default_config(&cfg);
            cfg.width = W;
            cfg.height = H;
            cfg.threads = T;
            cfg.shadow_mv = opt;
            cfg.dual_mv = opt;
            cfg.gt_samples = 4;
            tdc_render_t *r = tdc_render_open(&sc, &cfg, err, sizeof err);
            if (!r) {
                fprintf(stderr, "%s\n", err);
                return 1;
            }
            uint64_t h = 1469598103934665603ull, hr = h;
            for (int mode = 0; mode < 4; mode++) {
                uint32_t f1 = mode == TDC_RENDER_SUBFRAME ? 246u : mode == TDC_RENDER_GROUND_TRUTH ? 239u : 241u;
                for (uint32_t f = 238; f < f1; f++) {
                    memset(rgb, 0, n * 12);
                    memset(mvf, 0, n * 8);
                    memset(sw, 0, n * 4);
                    memset(dep, 0, n * 4);
                    memset(mv, 0, n * 4);
                    memset(mvs, 0, n * 4);
                    memset(mvd, 0, n * 4);
                    tdc_render_out_t o = {
                        .rgb = rgb, .mv = mv, .mv_f = mvf, .mv_shadow = mvs, .shadow_weight = sw, .mv_dual = mvd, .depth = dep};
                    tdc_render_stats_t st;
                    if (tdc_render_frame(r, f, (tdc_render_mode_t)mode, &o, &st) != 0) return 1;
                    h = fnv(h, rgb, n * 12);
                    h = fnv(h, mvf, n * 8);
                    h = fnv(h, sw, n * 4);
                    h = fnv(h, dep, n * 4);
                    h = fnv(h, mv, n * 4);
                    h = fnv(h, mvs, n * 4);
                    h = fnv(h, mvd, n * 4);
                    hr = fnv(hr, st.rays, sizeof st.rays);
                }
            }
            printf("%-9s %s %016llx rays %016llx\n", name, opt ? "shadow+dual" : "plain      ", (unsigned long long)h,
                   (unsigned long long)hr);
            tdc_render_close(r);
        }
    }
    free(rgb);
    free(mvf);
    free(sw);
    free(dep);
    free(mv);
    free(mvs);
    free(mvd);
    return 0;
}
