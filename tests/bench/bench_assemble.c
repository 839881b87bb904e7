/*
 * bench_assemble.c - speed of tile-ordered frame assembly at 1920x1080 on
 * one core, against the memory-bandwidth bound measured in the same run.
 *
 * Times are CPU time of the benchmark thread (CLOCK_THREAD_CPUTIME_ID).
 *   Mpixel/s = output pixels / (ingest + assemble time), best of 3 runs of
 *              FRAMES frames each.
 *   memcpy bandwidth = bytes read + written per second by memcpy of a 64 MiB
 *              buffer (best of 5).
 *   bound    = bandwidth / bytes touched per output pixel (counted from the
 *              data layout below; cache-resident scratch rows not counted).
 *   fraction = Mpixel/s / bound.
 *
 * Streams: a pan (every pixel dynamic: the worst case: reprojection + clamp
 * of 3/4 of the pixels every frame), a static scene (the elided path) and
 * moving lines over a static background (sparse motion in every row: the
 * general per-pixel path).
 * Usage: bench_assemble [frames [pan|static|lines]]   (default 48, all)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ref_assemble.h"
#include "bench/tdc_must.h"
#include "tdc_assemble.h"
#include "bench_clock.h"

#define BW 1920
#define BH 1080

/*
 * Bytes touched per output pixel per frame (steady state), useful bytes read
 * + written, from the layout of tdc_assemble.c (samples in 16 dense planes:
 * slot x tile position):
 *   ingest, per tile (= 4 px): sample in 3 + MV in 4, sample write 3 (dense
 *     plane), MV buffer read 4 (the entry is written only when the vector
 *     changes, never in these constant-motion streams) -> 14 / 4 = 3.5 B/px;
 *   dynamic frame: MV buffer read 4 (row summaries / 3x3 search), previous
 *     frame read 3, new frame write 3, window byte read 1, the newest slot's
 *     4 planes read once (neighbour boxes and new pixels; 12 B per tile) 3
 *     -> 14 B/px; total 17.5 B/px;
 *   static frame (elided): ingest 3.5 + per new pixel (1/4 of them): window
 *     read + write 2, 4 window samples 12, output write 3 -> 17 / 4;
 *     total 7.75 B/px.
 * (Until 2026-11-22 the MV buffer write was counted too: 18.5 and 8.75.)
 * Cache-line granularity would count more (the MV, window and output rows
 * are touched at a stride of 2 pixels), so the fraction is conservative.
 */
#define BYTES_PX_DYNAMIC 17.5
#define BYTES_PX_STATIC 7.75

typedef struct {
    uint8_t *samples[8];
    int16_t *mvs[8];
    uint8_t *bits[8];
} stream_t;

static void make_stream(stream_t *s, tdc_scene_kind_t kind, int32_t vx, int32_t vy)
{
    tdc_scene_t sc;
    size_t tiles = (size_t)((BW + 1) / 2) * ((BH + 1) / 2);
    tdc_scene_init(&sc, kind, BW, BH, vx, vy, 1);
    for (uint32_t f = 0; f < 8; f++) {
        s->samples[f] = malloc(tiles * 3);
        s->mvs[f] = malloc(tiles * 4);
        s->bits[f] = malloc((size_t)TDC_PATTERN_BYTES(BW, BH));
        tdc_scene_subframe(&sc, f, s->samples[f], s->mvs[f], s->bits[f]);
    }
    tdc_scene_free(&sc);
}

static void free_stream(stream_t *s)
{
    for (int f = 0; f < 8; f++) free(s->samples[f]), free(s->mvs[f]), free(s->bits[f]);
}

/* Runs `frames` frames (subframes repeat with period 8) and returns the best
 * seconds per frame of 3 runs; fills *stats with the last run's counters. */
static double run(const stream_t *s, int frames, tdc_asm_stats_t *stats)
{
    tdc_asm_config_t cfg = {BW, BH};
    size_t n = tdc_asm_get_size(&cfg);
    void *arena = aligned_alloc(64, (n + 63) & ~(size_t)63);
    tdc_asm_t st;
    double best = 1e30;
    for (int rep = 0; rep < 3; rep++) {
        TDC_MUST(tdc_asm_init(&st, &cfg, arena, n));
        /* warm-up cycle: fills the buffers (not timed) */
        uint32_t f = 0;
        for (; f < 8; f++) {
            TDC_MUST(tdc_asm_ingest(&st, f, s->samples[f & 7], s->mvs[f & 7], (f & 3) == 0 ? s->bits[f & 7] : NULL));
            TDC_MUST(tdc_asm_assemble(&st, f));
        }
        double t0 = now_s();
        for (int i = 0; i < frames; i++, f++) {
            TDC_MUST(tdc_asm_ingest(&st, f, s->samples[f & 7], s->mvs[f & 7], NULL));
            TDC_MUST(tdc_asm_assemble(&st, f));
        }
        double t = (now_s() - t0) / frames;
        if (t < best) best = t;
    }
    *stats = st.stats;
    free(arena);
    return best;
}

int main(int argc, char **argv)
{
    int frames = argc > 1 ? atoi(argv[1]) : 48;
    if (frames < 4) frames = 4;
    double bw = memcpy_bandwidth();
    printf("bench_assemble: %dx%d, %d frames per run, best of 3; memcpy bandwidth %.2f GB/s (read+write)\n", BW, BH,
           frames, bw / 1e9);
    const struct {
        const char *name;
        tdc_scene_kind_t kind;
        int32_t vx, vy;
        double bytes;
    } cases[] = {
        {"pan (2.3,-1.3) px/frame, all dynamic", TDC_SCENE_PAN, 37, -21, BYTES_PX_DYNAMIC},
        {"static scene (elided path)", TDC_SCENE_STATIC, 0, 0, BYTES_PX_STATIC},
        /* Sparse motion: moving 1-px lines over a static background, so
         * every row mixes motion and none: the general per-pixel 3x3 path.
         * Bytes counted as a frame with motion (an upper estimate). */
        {"lines (1.5 px/frame, sparse motion)", TDC_SCENE_LINE, 24, 0, BYTES_PX_DYNAMIC},
    };
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        if (argc > 2 && strncmp(cases[i].name, argv[2], strlen(argv[2])) != 0) continue;
        stream_t s;
        tdc_asm_stats_t stats;
        make_stream(&s, cases[i].kind, cases[i].vx, cases[i].vy);
        double t = run(&s, frames, &stats);
        double mpx = (double)BW * BH / t / 1e6;
        double bound = bw / cases[i].bytes / 1e6;
        printf("  %-38s %7.2f ms/frame  %8.1f Mpixel/s  (%5.1f fps; 240 Hz needs %.0f Mpixel/s)  "
               "bound %.2f B/px -> %.0f Mpixel/s  fraction %.1f %%\n",
               cases[i].name, t * 1e3, mpx, 1.0 / t, 240.0 * BW * BH / 1e6, cases[i].bytes, bound, 100.0 * mpx / bound);
        printf("  %-38s counters (last run): reprojected %llu clamp boxes %llu clamp changed %llu static frames %u "
               "static rows %llu\n",
               "", (unsigned long long)stats.reprojected, (unsigned long long)stats.clamp_boxes,
               (unsigned long long)stats.clamp_changed, stats.static_frames, (unsigned long long)stats.static_rows);
        free_stream(&s);
    }
    return 0;
}
