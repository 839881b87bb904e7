/*
 * tdc_lcdsim.c - physical LCD pixel response, integrated exactly
 * (see tdc_lcdsim.h for the model and the closed forms).
 */
#include "lcd/tdc_lcdsim.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_tool.h"


int tdc_lcdsim_load(const char *path, tdc_lcdsim_panel_t *p, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        return tdc_errf(err, errlen, "%s: cannot open", path);
    }
    memset(p, 0, sizeof *p);
    p->strobe_duty = 1.0;
    char buf[512];
    int line = 0, tau_rows = 0, have_gamma = 0;
    while (fgets(buf, sizeof buf, f)) {
        line++;
        char *hash = strchr(buf, '#');
        if (hash) {
            *hash = 0;
        }
        char *tok[16];
        int n = 0;
        for (char *t = strtok(buf, " \t\r\n"); t && n < 16; t = strtok(NULL, " \t\r\n")) {
            tok[n++] = t;
        }
        if (n == 0) {
            continue;
        }
        double v[15];
        for (int i = 1; i < n; i++) {
            char *end;
            v[i - 1] = strtod(tok[i], &end);
            if (strcmp(tok[0], "name") && strcmp(tok[0], "backlight") && *end) {
                fclose(f);
                return tdc_errf(err, errlen, "%s:%d: not a number: '%s'", path, line, tok[i]);
            }
        }
        if (!strcmp(tok[0], "name") && n == 2) {
            snprintf(p->name, sizeof p->name, "%s", tok[1]);
        } else if (!strcmp(tok[0], "gamma") && n == 4) {
            for (int c = 0; c < 3; c++) {
                p->gamma[c] = v[c];
            }
            have_gamma = 1;
        } else if (!strcmp(tok[0], "black") && n == 2) {
            p->black = v[0];
        } else if (!strcmp(tok[0], "peak_cd") && n == 4) {
            for (int c = 0; c < 3; c++) {
                p->peak_cd[c] = v[c];
            }
        } else if (!strcmp(tok[0], "tau_levels") && n >= 3 && n - 1 <= TDC_LCDSIM_MAX_LEV) {
            p->nlev = n - 1;
            for (int i = 0; i < p->nlev; i++) {
                p->lev[i] = v[i] / 255.0;
            }
        } else if (!strcmp(tok[0], "tau_ms") && p->nlev && n == p->nlev + 1 && tau_rows < p->nlev) {
            for (int i = 0; i < p->nlev; i++) {
                if (!(v[i] > 0.0)) {
                    fclose(f);
                    return tdc_errf(err, errlen, "%s:%d: time constants must be > 0", path, line);
                }
                p->tau_ms[tau_rows][i] = v[i];
            }
            tau_rows++;
        } else if (!strcmp(tok[0], "backlight") && (n == 2 || n == 4)) {
            if (!strcmp(tok[1], "constant") && n == 2) {
                p->strobe = 0;
            } else if (!strcmp(tok[1], "strobe") && n == 4) {
                p->strobe = 1;
                p->strobe_duty = strtod(tok[2], NULL);
                p->strobe_phase = strtod(tok[3], NULL);
                if (!(p->strobe_duty > 0.0 && p->strobe_duty <= 1.0 && p->strobe_phase >= 0.0 &&
                      p->strobe_phase + p->strobe_duty <= 1.0 + 1e-12)) {
                    fclose(f);
                    return tdc_errf(err, errlen, "%s:%d: strobe needs 0 < duty <= 1, phase + duty <= 1", path, line);
                }
            } else {
                fclose(f);
                return tdc_errf(err, errlen, "%s:%d: backlight constant | strobe DUTY PHASE", path, line);
            }
        } else {
            fclose(f);
            return tdc_errf(err, errlen, "%s:%d: unknown key or wrong number of values: '%s'", path, line, tok[0]);
        }
    }
    fclose(f);
    if (!have_gamma || p->nlev < 2 || tau_rows != p->nlev) {
        return tdc_errf(err, errlen, "%s: needs gamma, tau_levels and one tau_ms row per level", path);
    }
    return 0;
}

/* Position of x in the level grid: index i and fraction t in [0, 1]. */
static void grid_pos(const tdc_lcdsim_panel_t *p, double x, int *i, double *t)
{
    int k = 0;
    while (k < p->nlev - 2 && x > p->lev[k + 1]) {
        k++;
    }
    double f = (x - p->lev[k]) / (p->lev[k + 1] - p->lev[k]);
    *i = k;
    *t = f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
}

double tdc_lcdsim_tau_ms(const tdc_lcdsim_panel_t *p, double from, double to)
{
    int i, j;
    double fi, fj;
    grid_pos(p, from, &i, &fi);
    grid_pos(p, to, &j, &fj);
    double a = p->tau_ms[i][j] + (p->tau_ms[i][j + 1] - p->tau_ms[i][j]) * fj;
    double b = p->tau_ms[i + 1][j] + (p->tau_ms[i + 1][j + 1] - p->tau_ms[i + 1][j]) * fj;
    return a + (b - a) * fi;
}

double tdc_lcdsim_step_exact(double x0, double target, double tau, double h, double *integral)
{
    /* decay = 1 - e^{-h/tau} without cancellation; for h/tau > ~745 the
     * exponential underflows to 0 and the step lands on the target. */
    const double decay = -expm1(-h / tau);
    if (integral) {
        *integral += target * h + (x0 - target) * tau * decay;
    }
    return target + (x0 - target) * (1.0 - decay);
}

int tdc_lcdsim_init(tdc_lcdsim_t *s, const tdc_lcdsim_panel_t *p, size_t n)
{
    memset(s, 0, sizeof *s);
    s->panel = p;
    s->n = n;
    s->substeps = 1;
    s->x = calloc(n ? n : 1, sizeof *s->x);
    s->prev = calloc(n ? n : 1, 1);
    return s->x && s->prev ? 0 : -1;
}

void tdc_lcdsim_free(tdc_lcdsim_t *s)
{
    free(s->x);
    free(s->prev);
    memset(s, 0, sizeof *s);
}

void tdc_lcdsim_settle(tdc_lcdsim_t *s, const uint8_t *drive)
{
    for (size_t i = 0; i < s->n; i++) {
        s->x[i] = pow(drive[i] / 255.0, s->panel->gamma[i % 3]);
        s->prev[i] = drive[i];
    }
    s->have_prev = 1;
}

void tdc_lcdsim_frame(tdc_lcdsim_t *s, const uint8_t *drive, double refresh_hz, double *lum)
{
    const tdc_lcdsim_panel_t *p = s->panel;
    const double T = 1.0 / refresh_hz;
    /* Integration windows of the refresh: backlight on in [t0, t1]. */
    const double t0 = p->strobe ? p->strobe_phase * T : 0.0;
    const double t1 = p->strobe ? (p->strobe_phase + p->strobe_duty) * T : T;
    const int ns = s->substeps < 1 ? 1 : s->substeps;
    for (size_t i = 0; i < s->n; i++) {
        const double v = drive[i] / 255.0;
        const double from = (s->have_prev ? s->prev[i] : drive[i]) / 255.0;
        const double target = pow(v, p->gamma[i % 3]);
        const double tau = tdc_lcdsim_tau_ms(p, from, v) * 1e-3;
        double x = s->x[i];
        double lit = 0.0;
        /* Exact pieces: [0, t0) dark, [t0, t1) lit (split into substeps), [t1, T) dark. */
        if (t0 > 0.0) {
            x = tdc_lcdsim_step_exact(x, target, tau, t0, NULL);
        }
        const double h = (t1 - t0) / ns;
        for (int k = 0; k < ns; k++) {
            x = tdc_lcdsim_step_exact(x, target, tau, h, &lit);
        }
        if (t1 < T) {
            x = tdc_lcdsim_step_exact(x, target, tau, T - t1, NULL);
        }
        s->x[i] = x;
        s->prev[i] = drive[i];
        if (lum) {
            lum[i] = p->black + (1.0 - p->black) * lit / (t1 - t0);
        }
    }
    s->have_prev = 1;
}

double tdc_lcdsim_measure_pair(const tdc_lcdsim_panel_t *p, int ch, int a, int b, double refresh_hz,
                               double integration_s)
{
    tdc_lcdsim_t s;
    if (tdc_lcdsim_init(&s, p, 3) != 0) {
        return NAN;
    }
    uint8_t da[3] = {0, 0, 0}, db[3] = {0, 0, 0};
    da[ch] = (uint8_t)a;
    db[ch] = (uint8_t)b;
    /* Settle: 20 of the slowest time constants, in whole pairs. */
    double slow = 0.0;
    for (int i = 0; i < p->nlev; i++) {
        for (int j = 0; j < p->nlev; j++) {
            slow = fmax(slow, p->tau_ms[i][j] * 1e-3);
        }
    }
    long settle = 2 * (long)ceil(20.0 * slow * refresh_hz / 2.0) + 2;
    long frames = 2 * (long)ceil(integration_s * refresh_hz / 2.0);
    double l[3];
    tdc_lcdsim_settle(&s, db);
    for (long k = 0; k < settle; k++) {
        tdc_lcdsim_frame(&s, (k & 1) ? db : da, refresh_hz, NULL);
    }
    double sum = 0.0;
    for (long k = 0; k < frames; k++) {
        tdc_lcdsim_frame(&s, (k & 1) ? db : da, refresh_hz, l);
        sum += l[ch];
    }
    tdc_lcdsim_free(&s);
    return sum / (double)frames;
}

void tdc_lcdsim_measure_transition(const tdc_lcdsim_panel_t *p, int ch, int prev, int code, double refresh_hz,
                                   double *light, double *end)
{
    /* The state of a settled drive and one exact refresh: no allocation, the
     * same closed forms as tdc_lcdsim_frame (one sub-pixel of it). */
    uint8_t d0[3] = {0, 0, 0}, d1[3] = {0, 0, 0};
    double x[3], l[3];
    uint8_t pr[3];
    d0[ch] = (uint8_t)prev;
    d1[ch] = (uint8_t)code;
    tdc_lcdsim_t s = {p, 3, x, pr, 0, 1};
    tdc_lcdsim_settle(&s, d0);
    tdc_lcdsim_frame(&s, d1, refresh_hz, l);
    *light = l[ch];
    *end = p->black + (1.0 - p->black) * x[ch];
}
