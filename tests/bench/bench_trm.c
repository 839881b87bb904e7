/*
 * bench_trm.c - TRM throughput on one core at 1440x1600 RGB (one eye of a
 * current headset), next to memcpy bandwidth measured in the same run.
 * Reports Mpixel/s of the full-res and reduced paths and the fraction of
 * the memory-bandwidth bound reached: (bytes touched per pixel x pixel
 * rate) / memcpy bandwidth.  Also prints the per-stage counters that show
 * elision (pass-through at r = 1, weights skipped on a static pair).
 * Usage: bench_trm [repeats]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "golden/tdc_content.h"
#include "bench/tdc_must.h"
#include "tdc_panels.h"
#include "tdc_trm.h"
#include "tdc_trm_kernels.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* memcpy bandwidth in bytes/s (read + write counted: 2 x size per copy). */
static double memcpy_bandwidth(void)
{
    const size_t n = (size_t)64 << 20;
    uint8_t *a = malloc(n), *b = malloc(n);
    memset(a, 1, n);
    memset(b, 2, n);
    double best = 0;
    for (int r = 0; r < 5; r++) {
        double t0 = now_s();
        memcpy(b, a, n);
        double dt = now_s() - t0;
        double bw = 2.0 * (double)n / dt;
        best = bw > best ? bw : best;
        a[r] = b[n - 1 - (size_t)r]; /* keep the copy observable */
    }
    free(a);
    free(b);
    return best;
}

int main(int argc, char **argv)
{
    const int W = 1440, H = 1600, reps = argc > 1 ? atoi(argv[1]) : 5;
    tdc_trm_config_t cfg;
    tdc_trm_default_config(&cfg, W, H, 90);
    size_t n = tdc_trm_get_size(&cfg);
    void *mem = malloc(n);
    tdc_trm_t trm;
    if (tdc_trm_init(&trm, &cfg, &tdc_panel_htc_vive, mem, n) != TDC_OK) {
        fprintf(stderr, "bench_trm: init failed\n");
        return 1;
    }
    uint8_t *in = malloc((size_t)W * H * 3), *out = malloc((size_t)W * H * 3);
    uint8_t *red = malloc((size_t)trm.rw * trm.rh * 3);
    tdc_content_frame(TDC_CONTENT_TEXT, 0, 3, in, W, H, W * 3);
    TDC_MUST(tdc_trm_downsample(&trm, in, W * 3u, red, trm.rw * 3u));
    /* a moving reduced frame so the weight path runs: content of frame 1 */
    uint8_t *in1 = malloc((size_t)W * H * 3);
    tdc_content_frame(TDC_CONTENT_TEXT, 1, 3, in1, W, H, W * 3);
    uint8_t *red_moving = malloc((size_t)trm.rw * trm.rh * 3);
    TDC_MUST(tdc_trm_downsample(&trm, in1, W * 3u, red_moving, trm.rw * 3u));

    double bw = memcpy_bandwidth();
    const double px = (double)W * H;
    /* Bytes touched per output pixel.  Full: read I (3) twice (D pass and
     * beta), write out (3), write rho (3 x 4), D(I) (3 x 2 x r^2).
     * Reduced: read i (3 r^2), D(I) (3 x 2 x r^2), read rho (12), write out (3). */
    const double r2 = (double)trm.rw * trm.rh / px;
    const double bytes_full = 3 + 3 + 3 + 12 + 6 * r2;
    const double bytes_red = 3 * r2 + 6 * r2 + 12 + 3;
    printf("TRM benchmark, %dx%d RGB, one core, r = 1/2, best of %d\n", W, H, reps);
    printf("  memcpy bandwidth            %8.2f GB/s (read + write)\n", bw / 1e9);
    /* the portable C kernels (what boards run), then the AVX2 kernels
     * (tdc_trm_avx2.c, same bytes) when this CPU has AVX2 */
    const int nsets = tdc_trm_avx2_available() ? 2 : 1;
    double mpx_set[2][3] = {{0}};
    for (int set = 0; set < nsets; set++) {
        tdc_trm_set_simd(&trm, set);
        double best_full = 1e9, best_red = 1e9, best_red_static = 1e9;
        for (int r = 0; r < reps; r++) {
            double t0 = now_s();
            TDC_MUST(tdc_trm_full(&trm, in, W * 3u, out, W * 3u));
            double t1 = now_s();
            TDC_MUST(tdc_trm_reduced(&trm, red_moving, trm.rw * 3u, out, W * 3u));
            double t2 = now_s();
            TDC_MUST(tdc_trm_full(&trm, in, W * 3u, out, W * 3u));
            double t3 = now_s();
            TDC_MUST(tdc_trm_reduced(&trm, red, trm.rw * 3u, out, W * 3u));
            double t4 = now_s();
            best_full = (t1 - t0) < best_full ? (t1 - t0) : best_full;
            best_full = (t3 - t2) < best_full ? (t3 - t2) : best_full;
            best_red = (t2 - t1) < best_red ? (t2 - t1) : best_red;
            best_red_static = (t4 - t3) < best_red_static ? (t4 - t3) : best_red_static;
        }
        printf("  %s kernels:\n", set ? "AVX2" : "portable C");
        const struct {
            const char *name;
            double t, bytes;
        } rows[] = {{"full-res path (beta, rho, D)", best_full, bytes_full},
                    {"reduced path, moving", best_red, bytes_red},
                    {"reduced path, static pair", best_red_static, bytes_red}};
        for (int i = 0; i < 3; i++) {
            double mpx = px / rows[i].t / 1e6;
            double bound = bw / rows[i].bytes / 1e6; /* Mpixel/s if memory-bound */
            mpx_set[set][i] = mpx;
            printf("  %-28s %8.2f Mpixel/s  %6.2f ms/frame  %5.1f B/px  bound %8.2f Mpixel/s  -> %5.1f %% of bound\n",
                   rows[i].name, mpx, rows[i].t * 1e3, rows[i].bytes, bound, 100.0 * mpx / bound);
        }
    }
    if (nsets == 2) {
        printf("  AVX2 / C: full %.2fx, reduced moving %.2fx, reduced static %.2fx\n", mpx_set[1][0] / mpx_set[0][0],
               mpx_set[1][1] / mpx_set[0][1], mpx_set[1][2] / mpx_set[0][2]);
    } else {
        printf("  (no AVX2 on this CPU: C kernels only)\n");
    }
    const tdc_trm_stats_t *s = &trm.stats;
    printf("  counters: full %u reduced %u pass-through %u; weights computed %llu, skipped (c = 0) %llu, "
           "no residual %llu\n",
           s->full_frames, s->reduced_frames, s->passthrough_frames, (unsigned long long)s->weight_computed,
           (unsigned long long)s->weight_skipped, (unsigned long long)s->residual_skipped);
    /* elision: r = 1 does no TRM work at all */
    cfg.r_num = cfg.r_den = 1;
    free(mem);
    n = tdc_trm_get_size(&cfg);
    mem = malloc(n);
    if (tdc_trm_init(&trm, &cfg, &tdc_panel_htc_vive, mem, n) != TDC_OK) {
        fprintf(stderr, "bench_trm: pass-through init failed\n");
        return 1;
    }
    double t0 = now_s();
    TDC_MUST(tdc_trm_full(&trm, in, W * 3u, out, W * 3u));
    double tp = now_s() - t0;
    printf("  r = 1 pass-through         %8.2f Mpixel/s (a frame copy; counters: pass-through %u, full %u)\n",
           px / tp / 1e6, trm.stats.passthrough_frames, trm.stats.full_frames);
    free(mem);
    free(in);
    free(in1);
    free(out);
    free(red);
    free(red_moving);
    return 0;
}
