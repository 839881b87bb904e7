/*
 * tdc_calib_trans.c - stateful overdrive tables from transition
 * measurements (what and why: tdc_calib_trans.h).
 */
#include "tdc_calib_trans.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Refusal thresholds.  The run-to-run noise of a usable measurement is well
 * under 1 % of white (the simulated 0.2 % noise gives ~0.1 %); 2 % means the
 * instrument or the set-up is not measuring the panel.  A table whose light
 * error on the measured transitions exceeds 1.5 % RMS in a class would be no
 * better than the plain gamma inverse (~1-3 % on moving content). */
#define MAX_NOISE 0.02
#define MAX_CLASS_RMS 0.015
#define MIN_GRID 5

#define fail tdc_errf

typedef struct {
    int G;
    double max, gamma;
    double g[257];   /* grid codes */
    double *Lc, *Ll; /* light: gamma-encoded code, linear (normalised) [i * G + j] */
    double *Ec, *El; /* state at the end, likewise */
} chan_t;

static double T(const chan_t *c, double code)
{
    double x = code / c->max;
    return pow(x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x), c->gamma);
}

static double enc(const chan_t *c, double y)
{
    return c->max * pow(y < 0.0 ? 0.0 : (y > 1.0 ? 1.0 : y), 1.0 / c->gamma);
}

static void grid_pos(const chan_t *c, double x, int *i, double *f)
{
    int k = 0;
    while (k < c->G - 2 && x > c->g[k + 1]) {
        k++;
    }
    double t = (x - c->g[k]) / (c->g[k + 1] - c->g[k]);
    *i = k;
    *f = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
}

/* Light (linear) of a refresh at drive v from state s (codes); tab = Lc or Ec. */
static double eval(const chan_t *c, const double *tab, double s, double v)
{
    int i, j;
    double fs, fv;
    grid_pos(c, v, &j, &fv);
    grid_pos(c, s, &i, &fs);
    /* along the state in linear light: weight of the start transmittance */
    const double t0 = T(c, c->g[i]), t1 = T(c, c->g[i + 1]);
    const double ts = t1 > t0 ? (T(c, s) - t0) / (t1 - t0) : fs;
    const double w = ts < 0.0 ? 0.0 : (ts > 1.0 ? 1.0 : ts);
    double y[2];
    for (int r = 0; r < 2; r++) {
        const double *row = tab + (size_t)(i + r) * c->G;
        y[r] = T(c, row[j] + (row[j + 1] - row[j]) * fv);
    }
    return y[0] + (y[1] - y[0]) * w;
}

/* Drive with light(s, v) = want (linear), clamped to [0, max]: bisection on the
 * monotone (made non-decreasing) curve. */
static double invert(const chan_t *c, double s, double want)
{
    double lo = 0.0, hi = c->max;
    if (want <= eval(c, c->Lc, s, lo)) {
        return lo;
    }
    if (want >= eval(c, c->Lc, s, hi)) {
        return hi;
    }
    for (int it = 0; it < 50; it++) {
        double mid = 0.5 * (lo + hi);
        if (eval(c, c->Lc, s, mid) < want) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return 0.5 * (lo + hi);
}

/* Firmware-equivalent bilinear interpolation of an n x n Q4 table (codes). */
static double table_interp(const unsigned short *t, int n, double max, double a, double b)
{
    double x = a / max * (n - 1), y = b / max * (n - 1);
    int i = (int)x, j = (int)y;
    i = i > n - 2 ? n - 2 : i;
    j = j > n - 2 ? n - 2 : j;
    double fx = x - i, fy = y - j;
    const unsigned short *r0 = t + i * n + j, *r1 = r0 + n;
    double p = r0[0] + (r0[1] - r0[0]) * fy, q = r1[0] + (r1[1] - r1[0]) * fy;
    return (p + (q - p) * fx) / 16.0;
}

/* Measurement-noise smoothing of one G x G grid of cell means (tdc-calib
 * --smooth), along both axes: [1 2 1] / 4 inside, the 3-point least-squares
 * line at the ends (exact on locally linear data, so only curvature is
 * biased: light and end state vary smoothly with the drive and the start
 * state).  Noise variance x 0.375 per axis inside.  Why: on lcd-240 the
 * static perceived error of 65-node tables from an 8-run 33 x 33
 * measurement (0.2 % noise) was 0.108 / 0.145 / 0.116 % for three noise
 * seeds without it, 0.104 / 0.112 / 0.106 % with it (docs/lcd.md §5). */
static void smooth_grid(double *a, int G, double *tmp)
{
    for (int pass = 0; pass < 2; pass++) {
        const size_t si = pass ? 1u : (size_t)G, sj = pass ? (size_t)G : 1u; /* lines, then along each line */
        for (int i = 0; i < G; i++) {
            for (int j = 0; j < G; j++) {
                const double *y = a + (size_t)i * si;
                double v;
                if (j == 0) {
                    v = (5.0 * y[0] + 2.0 * y[sj] - y[2 * sj]) / 6.0;
                } else if (j == G - 1) {
                    v = (5.0 * y[(size_t)(G - 1) * sj] + 2.0 * y[(size_t)(G - 2) * sj] - y[(size_t)(G - 3) * sj]) / 6.0;
                } else {
                    v = 0.25 * (y[(size_t)(j - 1) * sj] + 2.0 * y[(size_t)j * sj] + y[(size_t)(j + 1) * sj]);
                }
                tmp[(size_t)i * si + (size_t)j * sj] = v;
            }
        }
        memcpy(a, tmp, (size_t)G * G * sizeof *a);
    }
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* The per-channel working arrays (freed between channels and at the end). */
static void chan_free(chan_t *c, int **cnt, double **acc)
{
    free(*cnt);
    free(*acc);
    free(c->Lc);
    free(c->Ll);
    free(c->Ec);
    free(c->El);
    *cnt = NULL;
    *acc = NULL;
    c->Lc = c->Ll = c->Ec = c->El = NULL;
}

static const char k_cls[5][12] = {"rise", "fall", "small step", "full swing", "all"};

int tdc_st_fit(const tdc_meas_t *m, const char *path, int n, int smooth, const double *gamma, tdc_st_fits_t *out,
               char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (m->kind != TDC_MEAS_TRANSITIONS) {
        return fail(err, errlen, "%s: not a transition measurement (header rate_hz,channel,prev_code,...)", path);
    }
    if (n != 17 && n != 33 && n != 65) {
        return fail(err, errlen, "state tables have 17, 33 or 65 nodes, not %d", n);
    }
    if (m->max_code != 255) {
        return fail(err, errlen,
                    "%s: the largest code measured is %d; the stateful tables need an 8-bit panel "
                    "measured up to 255",
                    path, m->max_code);
    }
    out->n = n;
    out->max_code = 255;
    /* Rates, ascending; at most what a profile holds. */
    int rates[TDC_ST_MAX_RATES];
    int nr = 0;
    for (size_t k = 0; k < m->nrows; k++) {
        int seen = 0;
        for (int r = 0; r < nr; r++) {
            seen |= rates[r] == m->rows[k].rate;
        }
        if (!seen) {
            if (nr == TDC_ST_MAX_RATES) {
                return fail(err, errlen,
                            "%s:%d: field rate_hz: a %dth refresh rate (%d Hz); a panel profile holds at "
                            "most %d",
                            path, m->rows[k].line, nr + 1, m->rows[k].rate, TDC_ST_MAX_RATES);
            }
            rates[nr++] = m->rows[k].rate;
        }
    }
    qsort(rates, (size_t)nr, sizeof rates[0], cmp_int);
    out->nrates = nr;
    chan_t c;
    memset(&c, 0, sizeof c);
    c.max = 255.0;
    int *cnt = NULL;
    double *acc = NULL;
    int rc = -1;
    for (int r = 0; r < nr; r++) {
        tdc_st_fit_t *fit = &out->rate[r];
        fit->rate = rates[r];
        double noise_ss = 0.0, noise_df = 0.0;
        for (int ch = 0; ch < 3; ch++) {
            const char chn = "RGB"[ch];
            /* The grid: distinct codes of this rate and channel. */
            int present[256] = {0};
            int first_line = 0;
            for (size_t k = 0; k < m->nrows; k++) {
                const tdc_meas_row_t *w = &m->rows[k];
                if (w->rate == rates[r] && w->ch == ch) {
                    present[w->a] = present[w->b] = 1;
                    first_line = first_line ? first_line : w->line;
                }
            }
            int G = 0;
            for (int k = 0; k < 256; k++) {
                G += present[k];
            }
            if (G < MIN_GRID) {
                fail(err, errlen,
                     "%s: rate %d channel %c: %d distinct codes; a transition grid needs at least %d "
                     "(17 x 17 or finer recommended)",
                     path, rates[r], chn, G, MIN_GRID);
                goto out;
            }
            for (int k = 0; k < G; k++) {
                const int want = (int)lround(k * 255.0 / (G - 1));
                if (!present[want]) {
                    fail(err, errlen,
                         "%s:%d: rate %d channel %c: codes are not the regular %d-code grid "
                         "(round(k * 255 / %d)); code %d is missing: wrong grid size?",
                         path, first_line, rates[r], chn, G, G - 1, want);
                    goto out;
                }
                c.g[k] = want;
            }
            c.G = G;
            chan_free(&c, &cnt, &acc);
            const size_t gg = (size_t)G * G;
            cnt = calloc(gg, sizeof *cnt);
            acc = calloc(gg * 4, sizeof *acc);
            c.Lc = calloc(gg, sizeof *c.Lc);
            c.Ll = calloc(gg, sizeof *c.Ll);
            c.Ec = calloc(gg, sizeof *c.Ec);
            c.El = calloc(gg, sizeof *c.El);
            if (!cnt || !acc || !c.Lc || !c.Ll || !c.Ec || !c.El) {
                fail(err, errlen, "out of memory");
                goto out;
            }
            int idx[256];
            for (int k = 0; k < G; k++) {
                idx[(int)c.g[k]] = k;
            }
            int *line_of = (int *)calloc(gg, sizeof(int));
            if (!line_of) {
                fail(err, errlen, "out of memory");
                goto out;
            }
            for (size_t k = 0; k < m->nrows; k++) {
                const tdc_meas_row_t *w = &m->rows[k];
                if (w->rate != rates[r] || w->ch != ch) {
                    continue;
                }
                size_t cell = (size_t)idx[w->a] * G + idx[w->b];
                cnt[cell]++;
                acc[4 * cell] += w->lum;
                acc[4 * cell + 1] += w->lum * w->lum;
                acc[4 * cell + 2] += w->end;
                acc[4 * cell + 3] += w->end * w->end;
                line_of[cell] = line_of[cell] ? line_of[cell] : w->line;
            }
            for (int i = 0; i < G; i++) {
                for (int j = 0; j < G; j++) {
                    if (!cnt[(size_t)i * G + j]) {
                        fail(err, errlen,
                             "%s: rate %d channel %c: transition prev_code %d -> code %d missing (the "
                             "%d x %d grid needs every pair)",
                             path, rates[r], chn, (int)c.g[i], (int)c.g[j], G, G);
                        free(line_of);
                        goto out;
                    }
                }
            }
            const size_t wc = gg - 1;
            const double black = acc[0] / cnt[0], white = acc[4 * wc] / cnt[wc];
            if (!(white > black) || !(black >= -1e-3 * fabs(white))) {
                fail(err, errlen,
                     "%s:%d: rate %d channel %c: field light_cd_m2: white (255 -> 255) %g must exceed "
                     "black (0 -> 0) %g >= 0",
                     path, line_of[wc], rates[r], chn, white, black);
                free(line_of);
                goto out;
            }
            const double span = white - black;
            for (size_t k = 0; k < gg; k++) {
                const double nn = cnt[k];
                c.Ll[k] = (acc[4 * k] / nn - black) / span;
                c.El[k] = (acc[4 * k + 2] / nn - black) / span;
                if (cnt[k] > 1) {
                    noise_ss += (acc[4 * k + 1] - acc[4 * k] * acc[4 * k] / nn) / (span * span);
                    noise_ss += (acc[4 * k + 3] - acc[4 * k + 2] * acc[4 * k + 2] / nn) / (span * span);
                    noise_df += 2.0 * (nn - 1.0);
                }
            }
            /* Gamma from the settled cells (prev == code), golden section. */
            double lo = 1.0, hi = 4.0;
            for (int it = 0; it < 80; it++) {
                double x1 = hi - 0.618034 * (hi - lo), x2 = lo + 0.618034 * (hi - lo), s1 = 0.0, s2 = 0.0;
                for (int i = 0; i < G; i++) {
                    double y = c.Ll[(size_t)i * G + i], v = c.g[i] / 255.0;
                    s1 += (y - pow(v, x1)) * (y - pow(v, x1));
                    s2 += (y - pow(v, x2)) * (y - pow(v, x2));
                }
                if (s1 < s2) {
                    hi = x2;
                } else {
                    lo = x1;
                }
            }
            c.gamma = fit->gamma[ch] = gamma ? gamma[ch] : 0.5 * (lo + hi);
            if (smooth) {
                smooth_grid(c.Ll, G, c.Lc); /* Lc, Ec: scratch until filled below */
                smooth_grid(c.El, G, c.Ec);
            }
            /* Monotonic in the drive beyond the noise (4 sigma of a cell mean,
             * at least 0.3 % of white): else the data are not a panel's. */
            const double sig = noise_df > 0.0 ? sqrt(noise_ss / noise_df) : 0.0;
            const double tol = fmax(0.003, 4.0 * sig);
            for (int i = 0; i < G; i++) {
                for (int j = 0; j + 1 < G; j++) {
                    const size_t a = (size_t)i * G + j;
                    const int bad_l = c.Ll[a + 1] < c.Ll[a] - tol, bad_e = c.El[a + 1] < c.El[a] - tol;
                    if (bad_l || bad_e) {
                        fail(err, errlen,
                             "%s:%d: rate %d channel %c: field %s: falls from %.4f (code %d) to %.4f "
                             "(code %d) of white from prev_code %d: not monotonic in the drive beyond "
                             "the noise (%.2f %%)",
                             path, line_of[a + 1], rates[r], chn, bad_l ? "light_cd_m2" : "end_cd_m2",
                             bad_l ? c.Ll[a] : c.El[a], (int)c.g[j], bad_l ? c.Ll[a + 1] : c.El[a + 1], (int)c.g[j + 1],
                             (int)c.g[i], 100.0 * tol);
                        free(line_of);
                        goto out;
                    }
                }
            }
            /* Encoded curves, made non-decreasing along the drive (within the
             * tolerance just checked) so the inverse is well defined. */
            for (int i = 0; i < G; i++) {
                double ml = -1.0, me = -1.0;
                for (int j = 0; j < G; j++) {
                    const size_t a = (size_t)i * G + j;
                    ml = fmax(ml, enc(&c, c.Ll[a]));
                    me = fmax(me, enc(&c, c.El[a]));
                    c.Lc[a] = ml;
                    c.Ec[a] = me;
                }
            }
            /* Tables at the n nodes. */
            for (int i = 0; i < n; i++) {
                const double s = i * 255.0 / (n - 1);
                for (int j = 0; j < n; j++) {
                    const double x = j * 255.0 / (n - 1);
                    const double v = invert(&c, s, T(&c, x));
                    fit->od[ch][i * n + j] = (unsigned short)lround(16.0 * v);
                    fit->st[ch][i * n + j] = (unsigned short)lround(16.0 * enc(&c, eval(&c, c.Ec, s, x)));
                }
                fit->lo[ch][i] = (unsigned short)lround(16.0 * enc(&c, eval(&c, c.Lc, s, 0.0)));
                fit->hi[ch][i] = (unsigned short)lround(16.0 * enc(&c, eval(&c, c.Lc, s, 255.0)));
                /* A settled state must reach its own static light (else no
                 * drive ever holds that level). */
                if (fit->lo[ch][i] > 16.0 * s + 8.0 || fit->hi[ch][i] + 8.0 < 16.0 * s) {
                    fail(err, errlen,
                         "%s: rate %d channel %c: from the settled state %.1f the reachable light is "
                         "%.1f..%.1f (codes): its own static light is out of reach; the measurement "
                         "is inconsistent",
                         path, rates[r], chn, s, fit->lo[ch][i] / 16.0, fit->hi[ch][i] / 16.0);
                    free(line_of);
                    goto out;
                }
                for (int j = 0; j < n; j++) {
                    const double x = j * 255.0 / (n - 1);
                    fit->unreachable_share += (16.0 * x > fit->hi[ch][i] + 8.0 || 16.0 * x + 8.0 < fit->lo[ch][i]);
                }
            }
            /* Fit errors on every measured transition, as the firmware's
             * bilinear lookup would do it. */
            for (int i = 0; i < G; i++) {
                for (int j = 0; j < G; j++) {
                    if (i == j) {
                        continue;
                    }
                    const size_t a = (size_t)i * G + j;
                    const double p = c.g[i], v = c.g[j];
                    const double want = c.Lc[a];
                    const double vh = table_interp(fit->od[ch], n, 255.0, p, want);
                    const double le = eval(&c, c.Lc, p, vh) - T(&c, want);
                    const double se = T(&c, table_interp(fit->st[ch], n, 255.0, p, v)) - c.El[a];
                    const int reach = want > 0.5 && want < 254.5 && fabs(vh - v) < 254.0;
                    int cls[4] = {v > p, v < p, fabs(v - p) <= 32.0, fabs(v - p) >= 192.0};
                    for (int k = 0; k < 5; k++) {
                        if (k == 4 || cls[k]) {
                            fit->count[k]++;
                            fit->light_rms[k] += le * le;
                            fit->state_rms[k] += se * se;
                            fit->drive_rms[k] += reach ? (vh - v) * (vh - v) : 0.0;
                        }
                    }
                }
            }
            fit->grid = G;
            free(line_of);
        }
        fit->noise_pct = noise_df > 0.0 ? 100.0 * sqrt(noise_ss / noise_df) : -1.0;
        fit->unreachable_share /= 3.0 * n * n;
        for (int k = 0; k < 5; k++) {
            const double cn = fit->count[k] ? (double)fit->count[k] : 1.0;
            fit->light_rms[k] = 100.0 * sqrt(fit->light_rms[k] / cn);
            fit->state_rms[k] = 100.0 * sqrt(fit->state_rms[k] / cn);
            fit->drive_rms[k] = sqrt(fit->drive_rms[k] / cn);
        }
        if (noise_df > 0.0 && sqrt(noise_ss / noise_df) > MAX_NOISE) {
            fail(err, errlen,
                 "%s: rate %d: run-to-run noise %.2f %% of white exceeds %.0f %%: the measurement is "
                 "too noisy to fit overdrive tables",
                 path, rates[r], fit->noise_pct, 100.0 * MAX_NOISE);
            goto out;
        }
        for (int k = 0; k < 5; k++) {
            if (fit->light_rms[k] > 100.0 * MAX_CLASS_RMS) {
                fail(err, errlen,
                     "%s: rate %d: the %d x %d tables miss the measured %s transitions by %.2f %% of "
                     "white RMS (limit %.1f %%): refusing a fit that is no better than plain gamma; "
                     "measure a finer grid or use 33 nodes",
                     path, rates[r], n, n, k_cls[k], fit->light_rms[k], 100.0 * MAX_CLASS_RMS);
                goto out;
            }
        }
    }
    rc = 0;
out:
    chan_free(&c, &cnt, &acc);
    return rc;
}

void tdc_st_print(const tdc_st_fits_t *fits, FILE *f)
{
    for (int r = 0; r < fits->nrates; r++) {
        const tdc_st_fit_t *t = &fits->rate[r];
        fprintf(f, "rate %d Hz: stateful %dx%d tables from a %dx%d transition grid; gamma %.4f %.4f %.4f; noise ",
                t->rate, fits->n, fits->n, t->grid, t->grid, t->gamma[0], t->gamma[1], t->gamma[2]);
        if (t->noise_pct >= 0.0) {
            fprintf(f, "%.3f %% of white (run to run)", t->noise_pct);
        } else {
            fprintf(f, "unknown (one run)");
        }
        fprintf(f, "; %.1f %% of (state, wanted) nodes out of reach in one refresh\n", 100.0 * t->unreachable_share);
        for (int k = 0; k < 5; k++) {
            fprintf(f,
                    "  %-10s %6ld transitions: light RMS %.3f %% of white, drive RMS %.2f codes, state RMS %.3f "
                    "%%\n",
                    k_cls[k], t->count[k], t->light_rms[k], t->drive_rms[k], t->state_rms[k]);
        }
    }
}

static void write_row(FILE *f, const char *key, int rate, int ch, int row, const unsigned short *v, int n)
{
    fprintf(f, "%-12s %d %c %d", key, rate, "RGB"[ch], row);
    for (int k = 0; k < n; k++) {
        fprintf(f, " %u", v[k]);
    }
    fputc('\n', f);
}

void tdc_st_write_profile(const tdc_st_fits_t *fits, FILE *f)
{
    const int n = fits->n;
    fprintf(f, "# stateful overdrive tables (docs/lcd.md §2): Q4 codes; lcd_od RATE CH STATE_ROW: drive per wanted\n"
               "# code column; lcd_st RATE CH STATE_ROW: state reached per drive column; lcd_reach_lo/hi RATE CH:\n"
               "# light (as a code) of drive 0 / 255 per state row\n");
    fprintf(f, "lcd_state_n %d\n", n);
    for (int r = 0; r < fits->nrates; r++) {
        const tdc_st_fit_t *t = &fits->rate[r];
        for (int ch = 0; ch < 3; ch++) {
            for (int i = 0; i < n; i++) {
                write_row(f, "lcd_od", t->rate, ch, i, t->od[ch] + i * n, n);
            }
            for (int i = 0; i < n; i++) {
                write_row(f, "lcd_st", t->rate, ch, i, t->st[ch] + i * n, n);
            }
            fprintf(f, "lcd_reach_lo %d %c", t->rate, "RGB"[ch]);
            for (int i = 0; i < n; i++) {
                fprintf(f, " %u", t->lo[ch][i]);
            }
            fprintf(f, "\nlcd_reach_hi %d %c", t->rate, "RGB"[ch]);
            for (int i = 0; i < n; i++) {
                fprintf(f, " %u", t->hi[ch][i]);
            }
            fputc('\n', f);
        }
    }
}
