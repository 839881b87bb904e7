/*
 * bench_lcd_floor.c - what limits the stateful LCD tables on static content
 * (docs/lcd.md §8, "Which cause limited lcd-240 static content"): the
 * report's static contents (text, gradient, noise; TRM r = 1/2) through
 * plain gamma and the stateful stage, shown on the simulated panel, RMS of
 * the perceived pair error against the instant reference (as
 * bench_lcd_report).  The stage's dense lookup can be replaced after init by
 * tables computed from the simulated physics, and the panel's time constant
 * can be made to depend on the state instead of the previous drive, to
 * measure each cause on its own.
 *
 * Usage: bench_lcd_floor [--panel lcd-240|pg279q] [--width W]
 *                        [--tables shipped|dense|dense-reach|nodesN]
 *                        [--tau-by-state]
 *   shipped      the profile's tables through tdc_lcd_init (what the firmware does)
 *   dense        the drive and next state of every (state, wanted) from the
 *                physics (settled state q: a refresh from x = T(q) with the
 *                previous drive q, as a transition measurement sees it), the
 *                profile's reach limits
 *   dense-reach  the same and the reach limits from the physics
 *   nodesN       N x N nodes (N = 17..129) from the physics, interpolated
 *                bilinearly in double into the lookup (the firmware's
 *                interpolation without a measurement or a fit)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench/tdc_must.h"
#include "golden/tdc_content.h"
#include "lcd/tdc_lcdsim.h"
#include "tdc_lcd.h"
#include "tdc_panels.h"
#include "tdc_trm.h"

#define MAXN 129

static tdc_lcdsim_panel_t g_sp;
static double g_rate;
static int g_tau_by_state;

/* One refresh of one sub-pixel of channel c at (continuous) drive d after
 * previous drive prevd; x: transmittance, updated.  Returns the light seen
 * (normalised, black included), as tdc_lcdsim_frame. */
static double refresh(int c, double *x, double prevd, double d)
{
    const double T = 1.0 / g_rate;
    const double t0 = g_sp.strobe ? g_sp.strobe_phase * T : 0.0;
    const double t1 = g_sp.strobe ? (g_sp.strobe_phase + g_sp.strobe_duty) * T : T;
    const double from = g_tau_by_state ? pow(*x > 0.0 ? *x : 0.0, 1.0 / g_sp.gamma[c]) : prevd / 255.0;
    const double target = pow(d / 255.0, g_sp.gamma[c]);
    const double tau = tdc_lcdsim_tau_ms(&g_sp, from, d / 255.0) * 1e-3;
    double lit = 0.0, v = *x;
    if (t0 > 0.0) {
        v = tdc_lcdsim_step_exact(v, target, tau, t0, NULL);
    }
    v = tdc_lcdsim_step_exact(v, target, tau, t1 - t0, &lit);
    if (t1 < T) {
        v = tdc_lcdsim_step_exact(v, target, tau, T - t1, NULL);
    }
    *x = v;
    return g_sp.black + (1.0 - g_sp.black) * lit / (t1 - t0);
}

static double ref_light(int c, double code)
{
    return g_sp.black + (1.0 - g_sp.black) * pow(code / 255.0, g_sp.gamma[c]);
}

/* From the settled state q (a code), one refresh at drive d: light, and the end state as a code. */
static double from_state(int c, double q, double d, double *end_code)
{
    double x = pow(q / 255.0, g_sp.gamma[c]);
    const double l = refresh(c, &x, q, d);
    if (end_code) {
        *end_code = 255.0 * pow(x > 0.0 ? x : 0.0, 1.0 / g_sp.gamma[c]);
    }
    return l;
}

static uint32_t clamp_code(double v)
{
    return v < 0.0 ? 0u : (v > 255.0 ? 255u : (uint32_t)lround(v));
}

/* The continuous drive that delivers the light of wanted code w from state q (clamped to 0..255). */
static double drive_for(int c, double q, double w)
{
    const double want = ref_light(c, w);
    double lo = 0.0, hi = 255.0;
    if (from_state(c, q, lo, NULL) >= want) {
        return lo;
    }
    if (from_state(c, q, hi, NULL) <= want) {
        return hi;
    }
    for (int it = 0; it < 50; it++) {
        const double mid = 0.5 * (lo + hi);
        if (from_state(c, q, mid, NULL) < want) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

static double g_od[3][MAXN][MAXN], g_nx[3][MAXN][MAXN];

static double bilinear(const double t[MAXN][MAXN], int n, double a, double b)
{
    double fa = a / 255.0 * (n - 1), fb = b / 255.0 * (n - 1);
    int ia = (int)fa, ib = (int)fb;
    ia = ia > n - 2 ? n - 2 : ia;
    ib = ib > n - 2 ? n - 2 : ib;
    fa -= ia;
    fb -= ib;
    return (1.0 - fa) * ((1.0 - fb) * t[ia][ib] + fb * t[ia][ib + 1]) +
           fa * ((1.0 - fb) * t[ia + 1][ib] + fb * t[ia + 1][ib + 1]);
}

/* Replaces the stage's lookup (and with reach, its reach limits) by tables from the physics. */
static void physics_tables(tdc_lcd_t *st, int reach, int nodes)
{
    for (int c = 0; c < 3 && nodes; c++) {
        for (int i = 0; i < nodes; i++) {
            for (int j = 0; j < nodes; j++) {
                const double q = 255.0 * i / (nodes - 1), v = 255.0 * j / (nodes - 1);
                g_od[c][i][j] = drive_for(c, q, v);
                from_state(c, q, v, &g_nx[c][i][j]);
            }
        }
    }
    static double L[256], E[256];
    for (int c = 0; c < 3; c++) {
        for (int q = 0; q < 256; q++) {
            for (int d = 0; d < 256; d++) {
                L[d] = from_state(c, q, d, &E[d]);
            }
            const size_t k = (size_t)c * 256u + (size_t)q;
            if (reach) {
                int whi = 255, wlo = 0;
                while (whi > 0 && 0.5 * (ref_light(c, whi) + ref_light(c, whi - 1)) > L[255]) {
                    whi--;
                }
                while (wlo < 255 && 0.5 * (ref_light(c, wlo) + ref_light(c, wlo + 1)) < L[0]) {
                    wlo++;
                }
                st->st_whi[k] = (uint8_t)whi;
                st->st_wlo[k] = (uint8_t)wlo;
                st->st_lhi[k] = (int32_t)lround((L[255] - g_sp.black) / (1.0 - g_sp.black) * 16777216.0);
                st->st_llo[k] = (int32_t)lround((L[0] - g_sp.black) / (1.0 - g_sp.black) * 16777216.0);
            }
            for (int w = 0; w < 256; w++) {
                uint32_t d = 0, nx;
                if (nodes) {
                    d = clamp_code(bilinear(g_od[c], nodes, q, w));
                } else {
                    for (int e = 1; e < 256; e++) {
                        d = fabs(L[e] - ref_light(c, w)) < fabs(L[d] - ref_light(c, w)) ? (uint32_t)e : d;
                    }
                }
                d = w > st->st_whi[k] ? 255u : (w < st->st_wlo[k] ? 0u : d);
                if (nodes) {
                    nx = clamp_code(bilinear(g_nx[c], nodes, q, d));
                } else {
                    nx = clamp_code(E[d]); /* the end state, a code */
                }
                st->st_lut[k * 256u + (size_t)w] = (uint16_t)(d | nx << 8);
            }
        }
    }
}

int main(int argc, char **argv)
{
    const char *pname = "lcd-240", *tables = "shipped";
    int W = 240;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--panel") && i + 1 < argc) {
            pname = argv[++i];
        } else if (!strcmp(argv[i], "--width") && i + 1 < argc) {
            W = atoi(argv[++i]);
        } else if (!strcmp(argv[i], "--tables") && i + 1 < argc) {
            tables = argv[++i];
        } else if (!strcmp(argv[i], "--tau-by-state")) {
            g_tau_by_state = 1;
        } else {
            fprintf(stderr, "usage: bench_lcd_floor [--panel lcd-240|pg279q] [--width W] "
                            "[--tables shipped|dense|dense-reach|nodesN] [--tau-by-state]\n");
            return 2;
        }
    }
    const int nodes = !strncmp(tables, "nodes", 5) ? atoi(tables + 5) : 0;
    if (W < 16 || W > 1440 || (strncmp(tables, "nodes", 5) && strcmp(tables, "shipped") && strcmp(tables, "dense") &&
                               strcmp(tables, "dense-reach")) ||
        (!strncmp(tables, "nodes", 5) && (nodes < 17 || nodes > MAXN))) {
        fprintf(stderr, "bench_lcd_floor: --width 16..1440, --tables shipped|dense|dense-reach|nodes17..nodes129\n");
        return 2;
    }
    const tdc_panel_t *panel = NULL;
#define PICK(p)                     \
    if (!strcmp((p).name, pname)) { \
        panel = &(p);               \
    }
    TDC_PANEL_LIST(PICK)
#undef PICK
    char path[256], err[256];
    snprintf(path, sizeof path, "sim/lcd/panels/%s.lcdsim", pname);
    if (!panel || panel->type != TDC_PANEL_LCD || tdc_lcdsim_load(path, &g_sp, err, sizeof err) != 0) {
        fprintf(stderr, "bench_lcd_floor: no LCD panel '%s' with %s\n", pname, path);
        return 1;
    }
    g_rate = panel->refresh_hz;
    const int H = W * 10 / 9, frames = 12;
    const tdc_content_t contents[] = {TDC_CONTENT_TEXT, TDC_CONTENT_GRADIENT, TDC_CONTENT_NOISE};
    const size_t n = (size_t)W * H * 3;
    uint8_t *in = malloc(n), *red = malloc(n), *w = malloc(n), *wref = malloc(n), *drive = malloc(n), *pd = malloc(n);
    double *x = malloc(n * sizeof *x), *lp = malloc(n * sizeof *lp), *rp = malloc(n * sizeof *rp);
    tdc_trm_config_t tcfg;
    tdc_trm_default_config(&tcfg, (uint16_t)W, (uint16_t)H, (uint16_t)g_rate);
    tcfg.keep_residual = 1;
    const size_t tn = tdc_trm_get_size(&tcfg);
    void *tm = malloc(tn), *tm2 = malloc(tn);
    if (!in || !red || !w || !wref || !drive || !pd || !x || !lp || !rp || !tm || !tm2) {
        fprintf(stderr, "bench_lcd_floor: out of memory\n");
        return 1;
    }
    double rms[2];
    for (int mode = 0; mode < 2; mode++) {
        double s2 = 0.0;
        long cnt = 0;
        for (int ci = 0; ci < 3; ci++) {
            tdc_trm_t trm, trr;
            TDC_MUST(tdc_trm_init(&trm, &tcfg, panel, tm, tn));
            TDC_MUST(tdc_trm_init(&trr, &tcfg, panel, tm2, tn));
            tdc_lcd_config_t lc = {(uint16_t)W, (uint16_t)H, (uint16_t)g_rate,
                                   (uint8_t)(mode ? TDC_LCD_MODE_STATEFUL : TDC_LCD_MODE_GAMMA), 8};
            const size_t ln = tdc_lcd_get_size(&lc);
            void *lm = malloc(ln);
            tdc_lcd_t lcd;
            TDC_MUST(tdc_lcd_init(&lcd, &lc, panel, lm, ln));
            if (mode && strcmp(tables, "shipped")) {
                physics_tables(&lcd, strcmp(tables, "dense") != 0, nodes);
            }
            for (int t = 0; t < frames; t++) {
                /* TRM of the static content, for the stage and for the reference (no LCD stage) */
                for (int r = 0; r < 2; r++) {
                    tdc_trm_t *tt = r ? &trr : &trm;
                    uint8_t *o = r ? wref : w;
                    tdc_content_frame(contents[ci], 0, 7, in, W, H, W * 3);
                    if ((t & 1) == 0) {
                        TDC_MUST(tdc_trm_full(tt, in, W * 3u, o, W * 3u));
                    } else {
                        TDC_MUST(tdc_trm_downsample(tt, in, W * 3u, red, tt->rw * 3u));
                        TDC_MUST(tdc_trm_reduced(tt, red, tt->rw * 3u, o, W * 3u));
                    }
                }
                TDC_MUST(tdc_lcd_frame(&lcd, w, W * 3u, drive, W * 3u, tdc_trm_residual(&trm)));
                for (size_t i = 0; i < n; i++) {
                    const int c = (int)(i % 3u);
                    if (t == 0) {
                        x[i] = pow(drive[i] / 255.0, g_sp.gamma[c]); /* settled */
                        pd[i] = drive[i];
                    }
                    const double l = refresh(c, &x[i], pd[i], drive[i]), rf = ref_light(c, wref[i]);
                    pd[i] = drive[i];
                    if ((t & 1) && t >= 3) {
                        const double e = 0.5 * (l + lp[i]) - 0.5 * (rf + rp[i]);
                        s2 += e * e;
                        cnt++;
                    }
                    lp[i] = l;
                    rp[i] = rf;
                }
            }
            free(lm);
        }
        rms[mode] = 100.0 * sqrt(s2 / (double)cnt);
    }
    printf("%s %d Hz, static contents %dx%d, tables %s%s: RMS perceived error plain gamma %.4f %%, stateful %.4f %% "
           "(%.2fx)\n",
           pname, (int)g_rate, W, H, tables, g_tau_by_state ? ", tau by state" : "", rms[0], rms[1], rms[1] / rms[0]);
    return 0;
}
