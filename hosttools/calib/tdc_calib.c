/*
 * tdc-calib - fits an LCD panel profile from alternating-pair luminance
 * measurements (TRM paper §4.4, Fig. 7-9; docs/design.md §6).
 *
 * Input: the measurement CSV of docs/lcd.md (rate_hz,channel,code_a,code_b,
 * luminance_cd_m2; '#' comments; header line).  For every (rate, channel)
 * the rows (0,0) and (max,max) are required: they give black and white, and
 * luminance is normalised Y = (L - black) / (white - black).
 *
 * Fit:
 *  1. gamma per channel from the static rows (a == b, every rate):
 *     least squares of Y - v^gamma over gamma in [1, 4] (golden section;
 *     the sum of squares is unimodal in gamma for Y in [0, 1]).
 *  2. per refresh rate, p1..p4 of M(a, b) (eq. 7) over every row of every
 *     channel (the liquid crystal is shared, the colour filters only change
 *     gamma): first linear least squares of M(a, b) = Y^(1/gamma_c) (normal
 *     equations of the features a^2 + b^2, a b, a + b, 1), then refined by
 *     Gauss-Newton least squares in luminance, sum (M^gamma_c - Y)^2, which
 *     is the quantity the eye integrates.
 *  3. RMSE of the fit, in luminance (% of white) and in M (codes), next to
 *     the RMSE of the plain gamma model that ignores the previous frame
 *     (predicted pair mean (a^g + b^g) / 2).
 * Output: a panel profile (boards/panels/NAME.panel format) with the fitted
 * gamma and coefficients; the firmware builds it through tdc-tablegen.
 *
 * With --transitions TRANS.csv (tdc-lcd-measure --transitions) it also fits
 * the stateful overdrive tables (tdc_calib_trans.h) and writes them into
 * the profile; the per-class fit errors are printed.
 *
 * The profile is written to OUT.panel.tmp.PID and renamed onto OUT.panel only
 * when everything succeeded: an error never truncates an existing profile.
 *
 * Exit codes (common/tdc_tool.h): 0 OK, ARGS (1) bad command line,
 * FILE (7) cannot read or write a file, INPUT (13) a measurement file is
 * malformed or cannot be fitted (the message says why).
 *
 * Usage: tdc-calib MEAS.csv -o OUT.panel --name NAME --width W --height H
 *                  [--eyes N] [--refresh HZ] [--table 0|17|33] [--note TEXT]
 *                  [--transitions TRANS.csv [--state-table 17|33|65] [--smooth]]
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_lcd_model.h"
#include "tdc_calib_trans.h"
#include "tdc_meas.h"
#include "tdc_panel.h"

/* rates_hz of a profile is 0-terminated in TDC_PANEL_MAX_RATES slots, so the
 * table generator takes at most TDC_PANEL_MAX_RATES - 1 rates. */
#define MAX_RATES (TDC_PANEL_MAX_RATES - 1)
_Static_assert(MAX_RATES == TDC_ST_MAX_RATES, "one rate limit for both fits");

typedef tdc_meas_row_t row_t;

static row_t *g_rows;
static int g_nrows;

/* Mean luminance of the rows (rate, ch, a, b); NAN if none. */
/* The first measured row at or after index i taken at rate (g_nrows: none):
 * the fits visit one rate's rows with
 *   for (int i = next_row(rate, 0); i < g_nrows; i = next_row(rate, i + 1)) */
static int next_row(int rate, int i)
{
    while (i < g_nrows && g_rows[i].rate != rate) {
        i++;
    }
    return i;
}

static double lookup(int rate, int ch, int a, int b)
{
    double s = 0.0;
    int n = 0;
    for (int i = 0; i < g_nrows; i++) {
        if (g_rows[i].rate == rate && g_rows[i].ch == ch && g_rows[i].a == a && g_rows[i].b == b) {
            s += g_rows[i].lum;
            n++;
        }
    }
    return n ? s / n : NAN;
}

static double g_black[MAX_RATES][3], g_white[MAX_RATES][3];
static int g_rates[MAX_RATES], g_nr;
static double g_max;

static int rate_index(int rate)
{
    for (int i = 0; i < g_nr; i++) {
        if (g_rates[i] == rate) {
            return i;
        }
    }
    return -1;
}

static double norm_lum(const row_t *r)
{
    int ri = rate_index(r->rate);
    return (r->lum - g_black[ri][r->ch]) / (g_white[ri][r->ch] - g_black[ri][r->ch]);
}

static double gamma_sse(int ch, double g)
{
    double s = 0.0;
    for (int i = 0; i < g_nrows; i++) {
        const row_t *r = &g_rows[i];
        if (r->ch == ch && r->a == r->b) {
            double e = norm_lum(r) - pow(r->a / g_max, g);
            s += e * e;
        }
    }
    return s;
}

static double fit_gamma(int ch)
{
    double lo = 1.0, hi = 4.0;
    const double k = 0.6180339887498949;
    double x1 = hi - k * (hi - lo), x2 = lo + k * (hi - lo);
    double f1 = gamma_sse(ch, x1), f2 = gamma_sse(ch, x2);
    for (int it = 0; it < 80; it++) {
        if (f1 < f2) {
            hi = x2, x2 = x1, f2 = f1;
            x1 = hi - k * (hi - lo);
            f1 = gamma_sse(ch, x1);
        } else {
            lo = x1, x1 = x2, f1 = f2;
            x2 = lo + k * (hi - lo);
            f2 = gamma_sse(ch, x2);
        }
    }
    return 0.5 * (lo + hi);
}

static void swap_d(double *a, double *b)
{
    const double t = *a;
    *a = *b;
    *b = t;
}

/* Swaps the n doubles at a and b (rows of a matrix, entries of vectors). */
static void swap_n(double *a, double *b, int n)
{
    for (int k = 0; k < n; k++) {
        swap_d(&a[k], &b[k]);
    }
}

/* Solves the 4x4 system A x = y by Gaussian elimination with partial pivoting. */
static int solve4(double A[4][4], double y[4], double x[4])
{
    for (int c = 0; c < 4; c++) {
        int piv = c;
        for (int r = c + 1; r < 4; r++) {
            if (fabs(A[r][c]) > fabs(A[piv][c])) {
                piv = r;
            }
        }
        if (fabs(A[piv][c]) < 1e-12) {
            return -1;
        }
        swap_n(A[c], A[piv], 4);
        swap_d(&y[c], &y[piv]);
        for (int r = c + 1; r < 4; r++) {
            double f = A[r][c] / A[c][c];
            for (int k = c; k < 4; k++) {
                A[r][k] -= f * A[c][k];
            }
            y[r] -= f * y[c];
        }
    }
    for (int c = 3; c >= 0; c--) {
        double s = y[c];
        for (int k = c + 1; k < 4; k++) {
            s -= A[c][k] * x[k];
        }
        x[c] = s / A[c][c];
    }
    return 0;
}

/* Sum of squared luminance errors of the model at one rate. */
static double lum_sse(int rate, const double p[4], const double gamma[3])
{
    double s = 0.0;
    for (int i = next_row(rate, 0); i < g_nrows; i = next_row(rate, i + 1)) {
        const row_t *w = &g_rows[i];
        double mm = tdc_lcdm_M(p, w->a / g_max, w->b / g_max);
        double e = pow(mm < 0.0 ? 0.0 : (mm > 1.0 ? 1.0 : mm), gamma[w->ch]) - norm_lum(w);
        s += e * e;
    }
    return s;
}

static const char usage[] = "usage: tdc-calib MEAS.csv -o OUT.panel --name NAME --width W --height H [--eyes N]\n"
                            "                 [--refresh HZ] [--table 0|17|33] [--note TEXT]\n"
                            "                 [--transitions TRANS.csv [--state-table 17|33|65] [--smooth]]\n"
                            "                 [--peak-cdm2 L --black-cdm2 L --distance-m D [--photometry-note TEXT]]\n";

/* Numeric option: the whole argument, in range, no wrap-around. */
static int opt_num(const char *opt, const char *v, int lo, int hi, int *out)
{
    if (tdc_parse_int(v, lo, hi, out) != 0) {
        fprintf(stderr, "tdc-calib: %s '%s': need an integer in %d..%d\n", opt, v, lo, hi);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    const char *in = NULL, *out = NULL, *name = NULL, *note = NULL, *trans = NULL;
    /* photometry is not fitted from the measurements (they are relative to
     * white): the caller states it, with its source, and it is copied */
    const char *peak = NULL, *black = NULL, *dist = NULL, *pnote = NULL;
    int width = 0, height = 0, eyes = 1, refresh = 0, table = 33, state_n = 33, smooth = 0;
    tdc_tool_set_name("tdc-calib");
    if (argc == 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        printf("%sFits an LCD panel profile (gamma, TRM eq. 7 p1..p4 per rate, optional state tables)\n"
               "to a measurement file of tdc-lcd-measure or a real colorimeter (docs/lcd.md).\n"
               "exit codes (docs/tools.md): 0 OK, 1 ARGS, 7 FILE, 13 INPUT (malformed or unfittable data)\n",
               usage);
        return TDC_EXIT_OK;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int bad = 0;
        if (!strcmp(a, "-o") && v) {
            out = argv[++i];
        } else if (!strcmp(a, "--name") && v) {
            name = argv[++i];
        } else if (!strcmp(a, "--width") && v) {
            bad = opt_num(a, argv[++i], 1, 16384, &width);
        } else if (!strcmp(a, "--height") && v) {
            bad = opt_num(a, argv[++i], 1, 16384, &height);
        } else if (!strcmp(a, "--eyes") && v) {
            bad = opt_num(a, argv[++i], 1, 2, &eyes);
        } else if (!strcmp(a, "--refresh") && v) {
            bad = opt_num(a, argv[++i], 1, 1000, &refresh);
        } else if (!strcmp(a, "--table") && v) {
            bad = opt_num(a, argv[++i], 0, 33, &table);
        } else if (!strcmp(a, "--state-table") && v) {
            bad = opt_num(a, argv[++i], 17, 65, &state_n);
        } else if (!strcmp(a, "--smooth")) {
            smooth = 1;
        } else if (!strcmp(a, "--transitions") && v) {
            trans = argv[++i];
        } else if (!strcmp(a, "--note") && v) {
            note = argv[++i];
        } else if (!strcmp(a, "--peak-cdm2") && v) {
            peak = argv[++i];
        } else if (!strcmp(a, "--black-cdm2") && v) {
            black = argv[++i];
        } else if (!strcmp(a, "--distance-m") && v) {
            dist = argv[++i];
        } else if (!strcmp(a, "--photometry-note") && v) {
            pnote = argv[++i];
        } else if (a[0] != '-' && !in) {
            in = a;
        } else {
            return tdc_fail_usage(NULL, a[0] != '-' ? "a second measurement file '%s'"
                                        : v         ? "unknown option '%s'"
                                                    : "unknown option '%s', or it needs a value",
                                  a);
        }
        if (bad) {
            return TDC_EXIT_ARGS;
        }
    }
    if (!in || !out || !name || width < 1 || height < 1) {
        return tdc_fail_usage(NULL, "needs MEAS.csv, -o OUT.panel, --name, --width and --height");
    }
    if ((peak || black || dist || pnote) && !(peak && black && dist)) {
        return tdc_fail_usage(NULL, "--peak-cdm2, --black-cdm2 and --distance-m go together");
    }
    if (peak) {
        char *e1, *e2, *e3;
        const double pk = strtod(peak, &e1), bl = strtod(black, &e2), dm = strtod(dist, &e3);
        if (*e1 || *e2 || *e3 || !(pk > 0 && pk <= 100000) || !(bl >= 0 && bl < pk) || !(dm > 0 && dm <= 100)) {
            return tdc_fail_usage(NULL, "photometry '%s %s %s': need 0 < peak <= 100000 cd/m^2, 0 <= black < peak, "
                                  "0 < distance <= 100 m", peak, black, dist);
        }
    }
    if ((table != 0 && table != 17 && table != 33) || (state_n != 17 && state_n != 33 && state_n != 65)) {
        return tdc_fail_usage(NULL, "--table is 0, 17 or 33; --state-table 17, 33 or 65");
    }
    if (!name[0] || strpbrk(name, " \t\r\n#")) {
        fprintf(stderr, "tdc-calib: --name '%s': need a non-empty name without blanks or '#'\n", name);
        return TDC_EXIT_ARGS;
    }
    char err[512];
    tdc_meas_t meas;
    const int lrc = tdc_meas_load(in, &meas, err, sizeof err);
    if (lrc != 0) {
        fprintf(stderr, "tdc-calib: %s\n", err);
        tdc_meas_free(&meas);
        return lrc == -2 ? TDC_EXIT_FILE : TDC_EXIT_INPUT;
    }
    if (meas.kind != TDC_MEAS_PAIRS) {
        fprintf(stderr,
                "tdc-calib: %s: a transition file; the first file is the pair measurement (Fig. 7), "
                "transitions go to --transitions\n",
                in);
        tdc_meas_free(&meas);
        return TDC_EXIT_INPUT;
    }
    g_rows = meas.rows;
    g_nrows = (int)meas.nrows;
    const int max_code = meas.max_code;
    if (max_code != 255 && max_code != 1023) {
        fprintf(stderr, "tdc-calib: %s: the largest code measured is %d; need the full-drive rows (255 or 1023)\n", in,
                max_code);
        return TDC_EXIT_INPUT;
    }
    g_max = max_code;
    const int bits = max_code == 255 ? 8 : 10;
    /* Rates, black and white per (rate, channel). */
    for (int i = 0; i < g_nrows; i++) {
        if (rate_index(g_rows[i].rate) < 0) {
            if (g_nr == MAX_RATES) {
                fprintf(stderr,
                        "tdc-calib: %s:%d: field rate_hz: a %dth refresh rate (%d Hz); a panel profile "
                        "holds at most %d\n",
                        in, g_rows[i].line, g_nr + 1, g_rows[i].rate, MAX_RATES);
                return TDC_EXIT_INPUT;
            }
            g_rates[g_nr++] = g_rows[i].rate;
        }
    }
    for (int r = 0; r < g_nr; r++) {
        for (int c = 0; c < 3; c++) {
            g_black[r][c] = lookup(g_rates[r], c, 0, 0);
            g_white[r][c] = lookup(g_rates[r], c, max_code, max_code);
            if (!isfinite(g_black[r][c]) || !isfinite(g_white[r][c]) || !(g_white[r][c] > g_black[r][c])) {
                fprintf(stderr, "tdc-calib: rate %d channel %c needs rows (0,0) and (%d,%d) with white > black\n",
                        g_rates[r], "RGB"[c], max_code, max_code);
                return TDC_EXIT_INPUT;
            }
        }
    }
    double gamma[3];
    for (int c = 0; c < 3; c++) {
        gamma[c] = fit_gamma(c);
    }
    double p[MAX_RATES][4];
    double rmse_lum[MAX_RATES], rmse_m[MAX_RATES], rmse_plain[MAX_RATES];
    int nfit[MAX_RATES];
    for (int r = 0; r < g_nr; r++) {
        double A[4][4] = {{0}}, y[4] = {0};
        int n = 0;
        for (int i = next_row(g_rates[r], 0); i < g_nrows; i = next_row(g_rates[r], i + 1)) {
            const row_t *w = &g_rows[i];
            double a = w->a / g_max, b = w->b / g_max;
            double yn = norm_lum(w);
            double m = pow(yn < 0.0 ? 0.0 : (yn > 1.0 ? 1.0 : yn), 1.0 / gamma[w->ch]);
            double f[4] = {a * a + b * b, a * b, a + b, 1.0};
            for (int k = 0; k < 4; k++) {
                for (int l = 0; l < 4; l++) {
                    A[k][l] += f[k] * f[l];
                }
                y[k] += f[k] * m;
            }
            n++;
        }
        if (n < 4 || solve4(A, y, p[r]) != 0) {
            fprintf(stderr, "tdc-calib: rate %d: too few or degenerate measurements for p1..p4\n", g_rates[r]);
            return TDC_EXIT_INPUT;
        }
        /* Refine in luminance space (what the eye integrates): Gauss-Newton on
         * sum (M^gamma - Y)^2 from the linear fit, with step halving. */
        double cur = lum_sse(g_rates[r], p[r], gamma);
        for (int it = 0; it < 50; it++) {
            double JA[4][4] = {{0}}, Jy[4] = {0}, step[4];
            for (int i = next_row(g_rates[r], 0); i < g_nrows; i = next_row(g_rates[r], i + 1)) {
                const row_t *w = &g_rows[i];
                double a = w->a / g_max, b = w->b / g_max, yn = norm_lum(w);
                double mm = tdc_lcdm_M(p[r], a, b);
                if (mm <= 1e-6) {
                    mm = 1e-6; /* derivative of M^g at M <= 0 (clamped): tiny slope */
                }
                double g = gamma[w->ch];
                double ym = pow(mm > 1.0 ? 1.0 : mm, g);
                double d = g * pow(mm > 1.0 ? 1.0 : mm, g - 1.0);
                double f[4] = {d * (a * a + b * b), d * a * b, d * (a + b), d};
                for (int k = 0; k < 4; k++) {
                    for (int l = 0; l < 4; l++) {
                        JA[k][l] += f[k] * f[l];
                    }
                    Jy[k] += f[k] * (yn - ym);
                }
            }
            if (solve4(JA, Jy, step) != 0) {
                break;
            }
            double lambda = 1.0, trial[4], sse = cur;
            for (int h = 0; h < 20; h++, lambda *= 0.5) {
                for (int k = 0; k < 4; k++) {
                    trial[k] = p[r][k] + lambda * step[k];
                }
                sse = lum_sse(g_rates[r], trial, gamma);
                if (sse < cur) {
                    break;
                }
            }
            if (!(sse < cur)) {
                break;
            }
            double gain = cur - sse;
            memcpy(p[r], trial, sizeof trial);
            cur = sse;
            if (gain < 1e-14 * (1.0 + cur)) {
                break;
            }
        }
        for (int k = 0; k < 4; k++) {
            if (!(fabs(p[r][k]) < 4.0)) {
                fprintf(stderr, "tdc-calib: rate %d: fitted p%d = %g outside the profile range [-4, 4]\n", g_rates[r],
                        k + 1, p[r][k]);
                return TDC_EXIT_INPUT;
            }
        }
        double sl = 0.0, sm = 0.0, sp = 0.0;
        for (int i = next_row(g_rates[r], 0); i < g_nrows; i = next_row(g_rates[r], i + 1)) {
            const row_t *w = &g_rows[i];
            double a = w->a / g_max, b = w->b / g_max, yn = norm_lum(w);
            double mm = tdc_lcdm_M(p[r], a, b);
            double ym = pow(mm < 0.0 ? 0.0 : (mm > 1.0 ? 1.0 : mm), gamma[w->ch]);
            double mt = pow(yn < 0.0 ? 0.0 : (yn > 1.0 ? 1.0 : yn), 1.0 / gamma[w->ch]);
            double yp = 0.5 * (pow(a, gamma[w->ch]) + pow(b, gamma[w->ch]));
            sl += (ym - yn) * (ym - yn);
            sm += (mm - mt) * (mm - mt) * g_max * g_max;
            sp += (yp - yn) * (yp - yn);
        }
        nfit[r] = n;
        rmse_lum[r] = sqrt(sl / n);
        rmse_m[r] = sqrt(sm / n);
        rmse_plain[r] = sqrt(sp / n);
    }
    /* Report. */
    printf("tdc-calib: %d measurements, %d-bit, %d rate(s)\n", g_nrows, bits, g_nr);
    printf("gamma R G B: %.4f %.4f %.4f (static rows; RMSE %.3e %.3e %.3e of white)\n", gamma[0], gamma[1], gamma[2],
           sqrt(gamma_sse(0, gamma[0]) / (g_nrows / 3.0 / g_nr)), sqrt(gamma_sse(1, gamma[1]) / (g_nrows / 3.0 / g_nr)),
           sqrt(gamma_sse(2, gamma[2]) / (g_nrows / 3.0 / g_nr)));
    for (int r = 0; r < g_nr; r++) {
        printf("rate %d Hz: p = %.6f %.6f %.6f %.6f  fit RMSE %.3f %% of white (%.3f codes in M); "
               "plain gamma model %.3f %% (%d rows)\n",
               g_rates[r], p[r][0], p[r][1], p[r][2], p[r][3], 100.0 * rmse_lum[r], rmse_m[r], 100.0 * rmse_plain[r],
               nfit[r]);
        if (!(rmse_lum[r] < rmse_plain[r])) {
            printf("rate %d Hz: the temporal model does not fit better than the plain gamma model: "
                   "drive this rate with the plain gamma inverse (tdc_lcd mode GAMMA)\n",
                   g_rates[r]);
        }
    }
    /* Rates in ascending order, nominal = --refresh or the lowest. */
    for (int i = 0; i < g_nr; i++) {
        for (int j = i + 1; j < g_nr; j++) {
            if (g_rates[j] < g_rates[i]) {
                int t = g_rates[i];
                g_rates[i] = g_rates[j];
                g_rates[j] = t;
                swap_n(p[i], p[j], 4);
                swap_d(&rmse_lum[i], &rmse_lum[j]);
                swap_d(&rmse_plain[i], &rmse_plain[j]);
            }
        }
    }
    int nominal = refresh ? rate_index(refresh) : 0;
    if (nominal < 0) {
        fprintf(stderr, "tdc-calib: --refresh %d was not measured in %s\n", refresh, in);
        return TDC_EXIT_INPUT;
    }
    /* Stateful tables from the transition measurement (every check before
     * anything is written). */
    static tdc_st_fits_t st;
    if (trans) {
        tdc_meas_t tm;
        int rc = tdc_meas_load(trans, &tm, err, sizeof err);
        const int code = rc == -2 ? TDC_EXIT_FILE : TDC_EXIT_INPUT;
        if (rc == 0) {
            rc = tdc_st_fit(&tm, trans, state_n, smooth, gamma, &st, err, sizeof err);
        }
        tdc_meas_free(&tm);
        if (rc != 0) {
            fprintf(stderr, "tdc-calib: %s\n", err);
            return code;
        }
        for (int r = 0; r < st.nrates; r++) {
            if (rate_index(st.rate[r].rate) < 0) {
                fprintf(stderr, "tdc-calib: %s: transitions at %d Hz, a rate %s does not measure\n", trans,
                        st.rate[r].rate, in);
                return TDC_EXIT_INPUT;
            }
        }
        tdc_st_print(&st, stdout);
    }
    /* Profile: written to OUT.tmp.PID (tdc_out_open), renamed onto OUT when complete. */
    tdc_out_t o;
    if (tdc_out_open(&o, out, "w") != 0) {
        return tdc_fail(TDC_EXIT_FILE, NULL, out, "cannot write: %s", strerror(errno));
    }
    FILE *f = o.f;
    fprintf(f, "# %s: LCD profile written by tdc-calib from %s.\n", name, in);
    if (note) {
        fprintf(f, "# %s\n", note);
    }
    fprintf(f, "# Fit: gamma per channel from static patches; p1..p4 of M (TRM eq. 7) per refresh\n");
    fprintf(f, "# rate by least squares over alternating pairs (Fig. 7).  Fit RMSE, %% of white:\n");
    for (int r = 0; r < g_nr; r++) {
        fprintf(f, "#   %d Hz: temporal model %.3f %%, plain gamma %.3f %%%s\n", g_rates[r], 100.0 * rmse_lum[r],
                100.0 * rmse_plain[r],
                rmse_lum[r] < rmse_plain[r] ? "" : "  -> model no better: use the plain gamma inverse at this rate");
    }
    fprintf(f, "name        %s\ntype        lcd\nwidth       %d\nheight      %d\neyes        %d\nbits        %d\n",
            name, width, height, eyes, bits);
    fprintf(f, "refresh_hz  %d\nrates_hz   ", g_rates[nominal]);
    for (int r = 0; r < g_nr; r++) {
        fprintf(f, " %d", g_rates[r]);
    }
    fprintf(f, "\ngamma       %.6f %.6f %.6f\n", gamma[0], gamma[1], gamma[2]);
    if (peak) {
        fprintf(f, "# photometry (given to tdc-calib, not fitted)%s%s\npeak_cdm2   %s\nblack_cdm2  %s\ndistance_m  %s\n",
                pnote ? ": " : "", pnote ? pnote : "", peak, black, dist);
    }
    /* Coefficients as the firmware holds them: Q24 integers (TDC_LCD_COEF_FRAC),
     * written as their exact decimal value q / 2^24 so that tdc-tablegen's
     * rounding gives back exactly q; the integers themselves in a comment. */
    long q[MAX_RATES][4];
    for (int r = 0; r < g_nr; r++) {
        for (int k = 0; k < 4; k++) {
            q[r][k] = lround(p[r][k] * 16777216.0);
        }
    }
    fprintf(f, "# coefficients in Q24 (firmware integers), per rate:");
    for (int r = 0; r < g_nr; r++) {
        fprintf(f, "%s %d Hz: %ld %ld %ld %ld", r ? ";" : "", g_rates[r], q[r][0], q[r][1], q[r][2], q[r][3]);
    }
    fprintf(f, "\nlcd_p       %.10f %.10f %.10f %.10f\n", q[nominal][0] / 16777216.0, q[nominal][1] / 16777216.0,
            q[nominal][2] / 16777216.0, q[nominal][3] / 16777216.0);
    for (int r = 0; r < g_nr; r++) {
        fprintf(f, "lcd_p_hz    %d %.10f %.10f %.10f %.10f\n", g_rates[r], q[r][0] / 16777216.0, q[r][1] / 16777216.0,
                q[r][2] / 16777216.0, q[r][3] / 16777216.0);
    }
    fprintf(f, "lcd_table   %d\n", table);
    if (trans) {
        tdc_st_write_profile(&st, f);
    }
    if (tdc_out_commit(&o) != 0) {
        return tdc_fail(TDC_EXIT_FILE, NULL, out, "cannot write: %s", strerror(errno));
    }
    printf("wrote %s\n", out);
    tdc_meas_free(&meas);
    return 0;
}
