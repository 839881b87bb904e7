/*
 * bench_lcd_report.c - the LCD report (issue 3, docs/lcd.md): perceived
 * luminance error of alternating TRM frames on the simulated LCD and the
 * firmware time per 1440x1600 frame, for
 *   (a) the plain gamma inverse (drive = TRM code),
 *   (b) the exact temporal inverse, (c) the 17x17 and (d) 33x33 overdrive
 *   tables, (e) reduced-precision (6-bit) previous-frame buffers.
 *
 * Error: TRM runs on moving content (full frame, then reduced frame, ...);
 * each mode's LCD stage turns TRM's codes into drives (adding unreached
 * light to TRM's residual), the physical LCD simulation (sim/lcd) shows
 * them, and the eye fuses each (full, reduced) pair (Talbot-Plateau: mean
 * luminance of the two refreshes).  The reference is an instant panel with
 * the same static response showing the codes of a TRM run without any LCD
 * stage.  Error = perceived - reference, normalised luminance (% of white),
 * over every sub-pixel of every pair after the first.
 * Time: tdc_lcd_frame on a 1440x1600 RGB frame, best of several runs, next
 * to memcpy of the same frame measured in the same run.
 *
 * Usage: bench_lcd_report [-o report.md] [--panel pg279q|lcd-240] [--quick]
 * Without -o (as `make bench` runs it) the quick sizes are used unless --full.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "golden/tdc_content.h"
#include "lcd/tdc_lcdsim.h"
#include "bench/bench_clock.h"
#include "bench/tdc_must.h"
#include "tdc_lcd.h"
#include "tdc_panels.h"
#include "tdc_trm.h"

typedef struct {
    const char *label;
    tdc_lcd_mode_t mode;
    unsigned prev_bits;
} mode_t_;

static const mode_t_ k_modes[] = {
    {"(a) plain gamma inverse", TDC_LCD_MODE_GAMMA, 8},
    {"(b) exact temporal inverse", TDC_LCD_MODE_EXACT, 8},
    {"(c) 17x17 overdrive table", TDC_LCD_MODE_TABLE17, 8},
    {"(d) 33x33 overdrive table", TDC_LCD_MODE_TABLE33, 8},
    {"(e) exact, 6-bit previous frame", TDC_LCD_MODE_EXACT, 6},
    {"(e') 33x33, 6-bit previous frame", TDC_LCD_MODE_TABLE33, 6},
    {"(f) stateful measured tables", TDC_LCD_MODE_STATEFUL, 8},
    {"(f') stateful, 6-bit state", TDC_LCD_MODE_STATEFUL, 6},
    {"(g) stateful, pair-fused", TDC_LCD_MODE_STATEFUL_PAIR, 8},
};
#define NMODES (sizeof k_modes / sizeof k_modes[0])

typedef struct {
    double sum2, sumabs, max;
    long n;
    long hist[10001]; /* |error| in 0.005 % steps up to 50 % */
} err_t;

static void err_add(err_t *e, double v)
{
    double a = fabs(v);
    e->sum2 += v * v;
    e->sumabs += a;
    e->max = a > e->max ? a : e->max;
    int k = (int)(a * 100.0 / 0.005);
    e->hist[k > 10000 ? 10000 : k]++;
    e->n++;
}

static double err_pct(const err_t *e, double q)
{
    long want = (long)ceil(q * e->n), acc = 0;
    for (int k = 0; k <= 10000; k++) {
        acc += e->hist[k];
        if (acc >= want) {
            return (k + 1) * 0.005;
        }
    }
    return 50.0;
}

/* TRM codes for frame t of the content (even: full, odd: reduced). */
static int trm_step(tdc_trm_t *trm, tdc_content_t c, int speed, int t, int W, int H, uint8_t *in, uint8_t *red,
                    uint8_t *out)
{
    tdc_content_frame(c, (uint32_t)(speed * t), 7, in, W, H, W * 3);
    if ((t & 1) == 0) {
        return tdc_trm_full(trm, in, (uint32_t)W * 3u, out, (uint32_t)W * 3u);
    }
    const tdc_status_t st = tdc_trm_downsample(trm, in, (uint32_t)W * 3u, red, trm->rw * 3u);
    if (st != TDC_OK) {
        return st;
    }
    return tdc_trm_reduced(trm, red, trm->rw * 3u, out, (uint32_t)W * 3u);
}

/* The stateful stage's streams without its lookups, 8 bytes at a time:
 * out = in ^ state, state = in (n a multiple of 8). */
static void traffic(const uint8_t *restrict in, uint8_t *restrict out, uint8_t *restrict state, size_t n)
{
    for (size_t i = 0; i + 8u <= n; i += 8u) {
        uint64_t a, q;
        memcpy(&a, in + i, 8);
        memcpy(&q, state + i, 8);
        q ^= a;
        memcpy(out + i, &q, 8);
        memcpy(state + i, &a, 8);
    }
}

/* Best-of-reps thread CPU time of one frame of mode k_modes[m] (simd 0: the
 * stateful inverse's portable C row), after a first frame for history;
 * in_place: the drive written over a copy of the wanted frame (in == out,
 * the copy not timed). */
static double time_mode(const tdc_panel_t *panel, int rate, size_t m, int simd, int in_place, const uint8_t *fa,
                        const uint8_t *fb, uint8_t *fo, int TW, int TH, int reps, size_t *hist_bytes)
{
    tdc_lcd_config_t lcfg = {(uint16_t)TW, (uint16_t)TH, (uint16_t)rate, (uint8_t)k_modes[m].mode,
                             (uint8_t)k_modes[m].prev_bits};
    size_t ln = tdc_lcd_get_size(&lcfg);
    void *lmem = malloc(ln);
    tdc_lcd_t lcd;
    TDC_MUST(tdc_lcd_init(&lcd, &lcfg, panel, lmem, ln));
    tdc_lcd_set_simd(&lcd, simd);
    *hist_bytes = tdc_lcd_cfg_history_bytes(&lcfg);
    TDC_MUST(tdc_lcd_frame(&lcd, fa, TW * 3u, fo, TW * 3u, NULL)); /* first frame: history */
    double best = 1e9;
    for (int r = 0; r < reps; r++) {
        const uint8_t *in = (r & 1) ? fa : fb;
        if (in_place) {
            memcpy(fo, in, (size_t)TW * TH * 3u);
            in = fo;
        }
        double t0 = now_s();
        TDC_MUST(tdc_lcd_frame(&lcd, in, TW * 3u, fo, TW * 3u, NULL));
        best = fmin(best, now_s() - t0);
    }
    free(lmem);
    return best;
}

int main(int argc, char **argv)
{
    const char *out_path = NULL, *panel_name = "pg279q";
    int quick = 0, time_only = 0; /* --time-only: only the firmware times (seconds, not the error runs) */
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-o") && i + 1 < argc) {
            out_path = argv[++i];
        } else if (!strcmp(argv[i], "--panel") && i + 1 < argc) {
            panel_name = argv[++i];
        } else if (!strcmp(argv[i], "--quick")) {
            quick = 1;
        } else if (!strcmp(argv[i], "--time-only")) {
            time_only = 1;
        } else if (!strcmp(argv[i], "--full")) {
            quick = -1;
        } else {
            fprintf(stderr,
                    "usage: bench_lcd_report [-o report.md] [--panel pg279q|lcd-240] [--quick] [--time-only]\n");
            return 2;
        }
    }
    quick = quick == 1 || (quick == 0 && !out_path);
    const tdc_panel_t *panel = NULL;
#define PICK(p)                          \
    if (!strcmp((p).name, panel_name)) { \
        panel = &(p);                    \
    }
    TDC_PANEL_LIST(PICK)
#undef PICK
    if (!panel || panel->type != TDC_PANEL_LCD) {
        fprintf(stderr, "bench_lcd_report: no LCD panel profile '%s'\n", panel_name);
        return 1;
    }
    char simpath[256], err[256];
    snprintf(simpath, sizeof simpath, "sim/lcd/panels/%s.lcdsim", panel_name);
    tdc_lcdsim_panel_t sp;
    if (tdc_lcdsim_load(simpath, &sp, err, sizeof err) != 0) {
        fprintf(stderr, "bench_lcd_report: %s\n", err);
        return 1;
    }
    const int rate = panel->refresh_hz;
    /* Error measurement: a 720 x 800 eye (a quarter of 1440 x 1600; the
     * double-precision LCD simulation costs ~1 s per full frame). */
    const int W = quick ? 240 : 720, H = quick ? 200 : 800;
    const int frames = quick ? 8 : 12;
    /* Static contents first (TRM's frame pairs repeat: the Fig. 7 condition the
     * model is fitted for), then moving ones (transitions every frame). */
    /* Moving contents at several speeds and step sizes: text (full-swing
     * strokes) at 2 and 6 px/frame, the edge (one full swing per row) at 3 and
     * 12 px/frame, the gradient (steps of ~1 code) at 1 and 8 px/frame
     * (~8-code steps).  speed = frame-index multiplier of the content. */
    const tdc_content_t contents[] = {TDC_CONTENT_TEXT, TDC_CONTENT_GRADIENT, TDC_CONTENT_NOISE,
                                      TDC_CONTENT_TEXT, TDC_CONTENT_TEXT,     TDC_CONTENT_EDGE,
                                      TDC_CONTENT_EDGE, TDC_CONTENT_GRADIENT, TDC_CONTENT_GRADIENT};
    const int speed[] = {0, 0, 0, 1, 3, 1, 4, 1, 8};
    const int ncontents = 9;
    const size_t n = (size_t)W * H * 3;
    uint8_t *in = malloc(n), *red = malloc(n), *wref = malloc(n), *w = malloc(n), *drive = malloc(n);
    double *lum = malloc(n * sizeof *lum), *lum_prev = malloc(n * sizeof *lum);
    double *ref = malloc(n * sizeof *ref), *ref_prev = malloc(n * sizeof *ref);
    double ref_lut[3][256];
    for (int c = 0; c < 3; c++) {
        for (int k = 0; k < 256; k++) {
            ref_lut[c][k] = sp.black + (1.0 - sp.black) * pow(k / 255.0, sp.gamma[c]);
        }
    }
    tdc_trm_config_t tcfg;
    tdc_trm_default_config(&tcfg, (uint16_t)W, (uint16_t)H, (uint16_t)rate);
    tcfg.keep_residual = 1; /* the LCD inverse adds its unreached light to rho */
    size_t tn = tdc_trm_get_size(&tcfg);
    void *tmem = malloc(tn), *tmem_ref = malloc(tn);
    static err_t errs_cls[2][NMODES]; /* [static, moving] */
    memset(errs_cls, 0, sizeof errs_cls);
    tdc_lcd_stats_t stats[NMODES];
    memset(stats, 0, sizeof stats);
    for (size_t m = 0; m < NMODES && !time_only; m++) {
        for (int ci = 0; ci < ncontents; ci++) {
            tdc_trm_t trm, trm_ref;
            if (tdc_trm_init(&trm, &tcfg, panel, tmem, tn) != TDC_OK ||
                tdc_trm_init(&trm_ref, &tcfg, panel, tmem_ref, tn) != TDC_OK) {
                fprintf(stderr, "bench_lcd_report: TRM init failed\n");
                return 1;
            }
            tdc_lcd_config_t lcfg = {(uint16_t)W, (uint16_t)H, (uint16_t)rate, (uint8_t)k_modes[m].mode,
                                     (uint8_t)k_modes[m].prev_bits};
            size_t ln = tdc_lcd_get_size(&lcfg);
            void *lmem = malloc(ln);
            tdc_lcd_t lcd;
            if (tdc_lcd_init(&lcd, &lcfg, panel, lmem, ln) != TDC_OK) {
                fprintf(stderr, "bench_lcd_report: LCD init failed (mode %s)\n", k_modes[m].label);
                return 1;
            }
            tdc_lcdsim_t sim;
            tdc_lcdsim_init(&sim, &sp, n);
            for (int t = 0; t < frames; t++) {
                trm_step(&trm_ref, contents[ci], speed[ci], t, W, H, in, red, wref);
                trm_step(&trm, contents[ci], speed[ci], t, W, H, in, red, w);
                TDC_MUST(tdc_lcd_frame(&lcd, w, (uint32_t)W * 3u, drive, (uint32_t)W * 3u, tdc_trm_residual(&trm)));
                if (t == 0) {
                    tdc_lcdsim_settle(&sim, drive);
                }
                tdc_lcdsim_frame(&sim, drive, rate, lum);
                for (size_t i = 0; i < n; i++) {
                    ref[i] = ref_lut[i % 3][wref[i]];
                }
                if ((t & 1) && t >= 3) {
                    for (size_t i = 0; i < n; i++) {
                        err_add(&errs_cls[speed[ci] != 0][m],
                                0.5 * (lum[i] + lum_prev[i]) - 0.5 * (ref[i] + ref_prev[i]));
                    }
                }
                double *sw = lum_prev;
                lum_prev = lum;
                lum = sw;
                sw = ref_prev;
                ref_prev = ref;
                ref = sw;
            }
            stats[m].roots += lcd.stats.roots;
            stats[m].clamped_low += lcd.stats.clamped_low;
            stats[m].clamped_high += lcd.stats.clamped_high;
            stats[m].residual_added += lcd.stats.residual_added;
            tdc_lcdsim_free(&sim);
            free(lmem);
        }
        fprintf(stderr, "%-36s RMS static %.4f %%, moving %.4f %%\n", k_modes[m].label,
                100.0 * sqrt(errs_cls[0][m].sum2 / errs_cls[0][m].n),
                100.0 * sqrt(errs_cls[1][m].sum2 / errs_cls[1][m].n));
    }

    /* Firmware time per 1440 x 1600 frame. */
    const int TW = 1440, TH = 1600, reps = quick ? 2 : 9;
    const size_t tnb = (size_t)TW * TH * 3;
    uint8_t *fa = malloc(tnb), *fb = malloc(tnb), *fo = malloc(tnb);
    tdc_content_frame(TDC_CONTENT_TEXT, 0, 7, fa, TW, TH, TW * 3);
    tdc_content_frame(TDC_CONTENT_TEXT, 1, 7, fb, TW, TH, TW * 3);
    double t_memcpy = 1e9;
    for (int r = 0; r < reps; r++) {
        double t0 = now_s();
        memcpy(fo, (r & 1) ? fa : fb, tnb);
        t_memcpy = fmin(t_memcpy, now_s() - t0);
    }
    /* The stateful stage's own memory traffic without its lookups (the
     * bytes-touched bound): read the wanted frame and the state, write the
     * drive frame and the state, 4 x 6.9 MB against memcpy's 2 x 6.9 MB. */
    uint8_t *tst = malloc(tnb);
    memcpy(tst, fa, tnb);
    double t_traffic = 1e9;
    for (int r = 0; r < reps; r++) {
        const uint8_t *src = (r & 1) ? fa : fb;
        double t0 = now_s();
        traffic(src, fo, tst, tnb);
        t_traffic = fmin(t_traffic, now_s() - t0);
    }
    free(tst);
    double t_mode[NMODES];
    size_t hist_bytes[NMODES];
    for (size_t m = 0; m < NMODES; m++) {
        t_mode[m] = time_mode(panel, rate, m, 1, 0, fa, fb, fo, TW, TH, reps, &hist_bytes[m]);
    }
    /* mode (f) again with the portable C run (tdc_lcd_set_simd 0), same inputs */
    size_t hist_c;
    const double t_stateful_c = time_mode(panel, rate, 6, 0, 0, fa, fb, fo, TW, TH, reps, &hist_c);
    /* and with the drive written over the wanted frame (the traffic question of docs/lcd.md §8) */
    const double t_stateful_ip = time_only ? time_mode(panel, rate, 6, 1, 1, fa, fb, fo, TW, TH, reps, &hist_c) : 0.0;

    if (time_only) {
        /* The firmware times alone, as a Markdown table on stdout (docs/lcd.md §8). */
        char la[128];
        bench_loadavg(la, sizeof la);
        printf("%s, %d x %d, thread CPU time, best of %d; memcpy %.3f ms; the stateful stage's traffic without its "
               "lookups (read frame + state, write drive + state) %.3f ms = %.1fx memcpy; loadavg %s\n\n| mode | ms / "
               "frame | x memcpy | x traffic bound | history bytes |\n|---|---|---|---|---|\n",
               panel_name, TW, TH, reps, 1e3 * t_memcpy, 1e3 * t_traffic, t_traffic / t_memcpy, la);
        for (size_t m = 0; m < NMODES; m++) {
            printf("| %s | %.2f | %.1f | %.1f | %zu |\n", k_modes[m].label, 1e3 * t_mode[m], t_mode[m] / t_memcpy,
                   t_mode[m] / t_traffic, hist_bytes[m]);
        }
        printf("| %s, portable C row | %.2f | %.1f | %.1f | %zu |\n", k_modes[6].label, 1e3 * t_stateful_c,
               t_stateful_c / t_memcpy, t_stateful_c / t_traffic, hist_bytes[6]);
        printf("| %s, drive over the wanted frame (in == out) | %.2f | %.1f | %.1f | %zu |\n", k_modes[6].label,
               1e3 * t_stateful_ip, t_stateful_ip / t_memcpy, t_stateful_ip / t_traffic, hist_bytes[6]);
        return 0;
    }
    FILE *f = out_path ? fopen(out_path, "w") : stdout;
    if (!f) {
        fprintf(stderr, "bench_lcd_report: cannot write %s\n", out_path);
        return 1;
    }
    fprintf(f, "# LCD report: perceived error of TRM on the simulated %s and firmware time\n\n", panel_name);
    fprintf(f, "Generated by `make report-lcd` (`%s%s%s`); every figure below comes from that run.\n\n", argv[0],
            out_path ? " -o " : "", out_path ? out_path : "");
    fprintf(f,
            "* Panel: firmware profile `boards/panels/%s.panel` (fitted by tdc-calib to the simulated panel), "
            "physical simulation `%s` at %d Hz.\n",
            panel_name, simpath, rate);
    fprintf(f,
            "* Error: TRM (r = 1/2, sigma 2.5 px), %d x %d, %d frames per content; perceived = mean luminance "
            "of each (full, reduced) pair on the simulated LCD; reference = an instant panel with the same static "
            "response showing the codes of TRM without an LCD stage; the first pair of each run is warm-up. "
            "Luminance normalised to white, errors in %% of white.\n",
            W, H, frames);
    char load[128];
    bench_loadavg(load, sizeof load);
    fprintf(f,
            "* Time: `tdc_lcd_frame` on a %d x %d RGB frame (alternating two text frames), best of %d, thread "
            "CPU time (CLOCK_THREAD_CPUTIME_ID), host build of this run (one core; /proc/loadavg at the end of the "
            "run: %s: the machine is shared, CPU time leaves out the time the thread waited, the ratios to memcpy "
            "come from the same run); memcpy of the same %zu bytes: %.3f ms.\n",
            TW, TH, reps, load, tnb, 1e3 * t_memcpy);
    static const char *cls_name[2] = {"Static contents (text, gradient, noise): TRM's full/reduced pairs repeat, the "
                                      "condition of paper Fig. 7 that M is fitted for",
                                      "Moving contents (text scrolling 2 and 6 px/frame, edge 3 and 12 px/frame, "
                                      "gradient 1 and 8 px/frame): a transition every frame"};
    for (int cls = 0; cls < 2; cls++) {
        const err_t *errs = errs_cls[cls];
        fprintf(f, "\n## %s\n\n%ld sub-pixel pairs per mode.\n\n", cls_name[cls], errs[0].n);
        fprintf(f, "| mode | RMS error %% | mean abs %% | 99th pct %% | max %% | RMS vs (a) | ms / 1440x1600 frame "
                   "| x memcpy | history bytes |\n|---|---|---|---|---|---|---|---|---|\n");
        const double rms_a = sqrt(errs[0].sum2 / errs[0].n);
        for (size_t m = 0; m < NMODES; m++) {
            const double rms = sqrt(errs[m].sum2 / errs[m].n);
            fprintf(f, "| %s | %.4f | %.4f | %.3f | %.3f | %.2f | %.2f | %.1f | %zu |\n", k_modes[m].label, 100.0 * rms,
                    100.0 * errs[m].sumabs / errs[m].n, err_pct(&errs[m], 0.99), 100.0 * errs[m].max, rms / rms_a,
                    1e3 * t_mode[m], t_mode[m] / t_memcpy, hist_bytes[m]);
        }
        size_t best = 1;
        for (size_t m = 1; m < NMODES; m++) {
            best = errs[m].sum2 / errs[m].n < errs[best].sum2 / errs[best].n ? m : best;
        }
        const double rb = sqrt(errs[best].sum2 / errs[best].n);
        fprintf(f,
                "\nGoal (issue 18): the best LCD mode at most 0.5x the RMS error of (a): %s (best %s, ratio %.2f).\n",
                rb <= 0.5 * rms_a ? "met" : "NOT met", k_modes[best].label, rb / rms_a);
    }
    fprintf(f, "\nLCD stage counters over the error runs (pixel-channels): ");
    for (size_t m = 1; m < NMODES; m++) {
        fprintf(f, "%s%s: %llu roots, %llu unreachable low, %llu unreachable high, %llu residual adds",
                m > 1 ? "; " : "", k_modes[m].label, (unsigned long long)stats[m].roots,
                (unsigned long long)stats[m].clamped_low, (unsigned long long)stats[m].clamped_high,
                (unsigned long long)stats[m].residual_added);
    }
    fprintf(f, ".\n\n");
    fprintf(f,
            "Reduced-precision previous frame (6 bits per channel, both history buffers): %zu bytes instead of %zu "
            "(saves %.1f %%).\n",
            hist_bytes[4], hist_bytes[1], 100.0 * (1.0 - (double)hist_bytes[4] / (double)hist_bytes[1]));
    const tdc_lcd_config_t scfg = {(uint16_t)TW, (uint16_t)TH, (uint16_t)rate, TDC_LCD_MODE_STATEFUL, 8u};
    const size_t st_get_size = tdc_lcd_get_size(&scfg);
    fprintf(f,
            "\nStateful table path (f), 8-bit state: %.2f ms per 1440x1600 frame = %.1fx memcpy of the frame (goal "
            "<= 2x: %s; the portable C row %.2f ms = %.1fx); the stage's traffic without its lookups (read frame and "
            "state, write drive and state) %.3f ms = %.1fx memcpy in the same run, the bound of this data layout; "
            "%zu state bytes (%.1f per pixel) + %u bytes of tables.\n",
            1e3 * t_mode[6], t_mode[6] / t_memcpy, t_mode[6] <= 2.0 * t_memcpy ? "met" : "NOT met", 1e3 * t_stateful_c,
            t_stateful_c / t_memcpy, 1e3 * t_traffic, t_traffic / t_memcpy, hist_bytes[6], (double)hist_bytes[6] / (TW * TH),
            (unsigned)(st_get_size - hist_bytes[6]));
    if (out_path) {
        fclose(f);
    }
    return 0;
}
