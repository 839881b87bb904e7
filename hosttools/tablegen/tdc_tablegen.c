/*
 * tdc-tablegen - turns a panel profile (boards/panels/<name>.panel) into
 * firmware tables: <outdir>/tdc_panel_<name>.c (const tdc_panel_t with its
 * integer gamma tables) and <outdir>/tdc_panel_<name>_config.h (compile-time
 * sizes for board builds).  Host tool: uses double precision; the firmware
 * only ever sees the integers written here.
 *
 * Profile format: one "key value..." per line, '#' starts a comment.
 * Usage: tdc-tablegen PROFILE.panel OUTDIR
 *        tdc-tablegen --fov OUT.h   (the foveation stage's log/power tables)
 *        tdc-tablegen --trm OUT.h   (TRM's exp(-x) weight table)
 */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_math.h"
#include "tdc_panel.h"
#include "tdc_trm.h"
#include "tdc_tool.h"
#include "tdc_lcd.h"
#include "tdc_lcd_model.h"

#define MAX_CODES 1024

#define ST_MAXN 65 /* stateful tables: 17, 33 or 65 nodes per axis */

typedef struct {
    char name[64];
    char type[16];
    int width, height, eyes, bits, refresh_hz;
    double ppd; /* pixels per degree at the view centre (0: not given) */
    double peak_cdm2, black_cdm2, distance_m; /* photometry and viewing distance (0: not given) */
    int rates[TDC_PANEL_MAX_RATES];
    int nrates;
    double gamma[3];
    int have_gamma;
    /* LCD temporal model M(v_t, v_{t-1}) coefficients (normalised drive values). */
    double lcd_p[4];
    int have_lcd;
    /* Per-rate coefficient sets ("lcd_p_hz RATE p1 p2 p3 p4"); rates without
     * one use lcd_p.  lcd_table: the panel's default inverse (0 = exact). */
    double lcd_rate_p[TDC_PANEL_MAX_RATES][4];
    int lcd_rate_hz[TDC_PANEL_MAX_RATES];
    int n_lcd_rate_p;
    int lcd_table;
    /* Stateful overdrive tables (lcd_state_n, lcd_od, lcd_st, lcd_reach_lo/hi,
     * written by tdc-calib --transitions; firmware/tdc_lcd.h), per rate. */
    int st_n;
    int st_nr;
    int st_rate_hz[TDC_PANEL_MAX_RATES];
    uint16_t st_od[TDC_PANEL_MAX_RATES][3][ST_MAXN * ST_MAXN], st_next[TDC_PANEL_MAX_RATES][3][ST_MAXN * ST_MAXN];
    uint16_t st_reach[TDC_PANEL_MAX_RATES][3][2 * ST_MAXN];
    unsigned char st_seen[TDC_PANEL_MAX_RATES][3][2 * ST_MAXN + 2]; /* od rows, st rows, lo, hi */
} profile_t;

#define TOK_MAX (ST_MAXN + 8) /* lcd_od RATE CH ROW and 65 values */

static const char *g_path;
static FILE *g_in; /* the profile being read (closed by whoever catches a failure) */

/* Every failure ends here: "tdc-tablegen: PROFILE:LINE: why", then the named
 * exit code (docs/tools.md: INPUT for the profile's contents, FILE for files).
 * The fuzz harness (tests/fuzz/fuzz_panel.c) defines TDC_TABLEGEN_FAIL_HOOK to
 * return to itself instead of exiting. */
#ifdef TDC_TABLEGEN_FAIL_HOOK
void TDC_TABLEGEN_FAIL_HOOK(int code);
#endif
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void
die(int code, int line, const char *fmt, ...)
{
    char why[768], where[300];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    if (line > 0) {
        snprintf(where, sizeof where, "%s:%d", g_path, line);
    } else {
        snprintf(where, sizeof where, "%s", g_path);
    }
    tdc_fail(code, NULL, where, "%s", why);
#ifdef TDC_TABLEGEN_FAIL_HOOK
    TDC_TABLEGEN_FAIL_HOOK(code);
#endif
    exit(code);
}

static int parse_int(const char *s, int line, int lo, int hi, const char *key)
{
    int v = 0;
    if (tdc_parse_int(s, lo, hi, &v) != 0) {
        die(TDC_EXIT_INPUT, line, "%s: expected an integer in [%d, %d], got '%s'", key, lo, hi, s);
    }
    return v;
}

static double parse_double(const char *s, int line, double lo, double hi, const char *key)
{
    double v = 0;
    if (tdc_parse_double(s, lo, hi, &v) != 0) {
        die(TDC_EXIT_INPUT, line, "%s: expected a number in [%g, %g], got '%s'", key, lo, hi, s);
    }
    return v;
}

/* Index of a stateful-table rate (added on first use). */
static int st_rate(profile_t *p, int hz, int line)
{
    for (int i = 0; i < p->st_nr; i++) {
        if (p->st_rate_hz[i] == hz) {
            return i;
        }
    }
    if (p->st_nr == TDC_PANEL_MAX_RATES - 1) {
        die(TDC_EXIT_INPUT, line, "stateful tables for more than %d rates", TDC_PANEL_MAX_RATES - 1);
    }
    p->st_rate_hz[p->st_nr] = hz;
    return p->st_nr++;
}

/* Reads a profile from an open stream (g_in; g_path names it in messages). */
static void parse_profile_stream(FILE *f, profile_t *p)
{
    memset(p, 0, sizeof *p);
    char buf[512];
    unsigned line = 0;
    int r;
    while ((r = tdc_read_line(f, buf, sizeof buf, &line)) != 0) {
        if (r == -2) {
            die(TDC_EXIT_FILE, 0, "read error: %s", strerror(errno));
        }
        if (r < 0) {
            /* fgets would split it and parse the tail as a key (issue 19) */
            die(TDC_EXIT_INPUT, (int)line, "line longer than %zu bytes or with a NUL byte", sizeof buf - 1);
        }
        char *hash = strchr(buf, '#');
        if (hash) {
            *hash = 0;
        }
        char *tok[TOK_MAX];
        int n = 0;
        for (char *t = strtok(buf, " \t\r\n"); t; t = strtok(NULL, " \t\r\n")) {
            if (n == TOK_MAX) {
                die(TDC_EXIT_INPUT, (int)line, "more than %d values on one line", TOK_MAX);
            }
            tok[n++] = t;
        }
        if (n == 0) {
            continue;
        }
        const char *k = tok[0];
        if (!strcmp(k, "name") && n == 2) {
            if (strlen(tok[1]) >= sizeof p->name) {
                die(TDC_EXIT_INPUT, (int)line, "name too long");
            }
            for (const char *c = tok[1]; *c; c++) {
                if (!(isalnum((unsigned char)*c) || *c == '-')) {
                    die(TDC_EXIT_INPUT, (int)line, "name may only hold letters, digits and '-'");
                }
            }
            strcpy(p->name, tok[1]);
        } else if (!strcmp(k, "type") && n == 2) {
            if (strcmp(tok[1], "oled") && strcmp(tok[1], "lcd")) {
                die(TDC_EXIT_INPUT, (int)line, "type must be 'oled' or 'lcd'");
            }
            strcpy(p->type, tok[1]);
        } else if (!strcmp(k, "width") && n == 2) {
            p->width = parse_int(tok[1], (int)line, 1, 8192, k);
        } else if (!strcmp(k, "height") && n == 2) {
            p->height = parse_int(tok[1], (int)line, 1, 8192, k);
        } else if (!strcmp(k, "eyes") && n == 2) {
            p->eyes = parse_int(tok[1], (int)line, 1, 2, k);
        } else if (!strcmp(k, "bits") && n == 2) {
            p->bits = parse_int(tok[1], (int)line, 6, 10, k);
        } else if (!strcmp(k, "ppd") && n == 2) {
            p->ppd = parse_double(tok[1], (int)line, 1.0, 200.0, k);
        } else if (!strcmp(k, "peak_cdm2") && n == 2) {
            p->peak_cdm2 = parse_double(tok[1], (int)line, 1.0, 10000.0, k);
        } else if (!strcmp(k, "black_cdm2") && n == 2) {
            p->black_cdm2 = parse_double(tok[1], (int)line, 0.0, 100.0, k);
        } else if (!strcmp(k, "distance_m") && n == 2) {
            p->distance_m = parse_double(tok[1], (int)line, 0.01, 100.0, k);
        } else if (!strcmp(k, "refresh_hz") && n == 2) {
            p->refresh_hz = parse_int(tok[1], (int)line, 1, 1000, k);
        } else if (!strcmp(k, "rates_hz") && n >= 2 && n <= TDC_PANEL_MAX_RATES) {
            p->nrates = n - 1;
            for (int i = 1; i < n; i++) {
                p->rates[i - 1] = parse_int(tok[i], (int)line, 1, 1000, k);
            }
        } else if (!strcmp(k, "gamma") && n == 4) {
            for (int c = 0; c < 3; c++) {
                /* rounded to 1e-6: the integer stored in the profile is then
                 * exactly the gamma the tables were generated from */
                p->gamma[c] = llround(parse_double(tok[c + 1], (int)line, 1.0, 4.0, k) * 1e6) / 1e6;
            }
            p->have_gamma = 1;
        } else if (!strcmp(k, "lcd_p") && n == 5) {
            for (int c = 0; c < 4; c++) {
                p->lcd_p[c] = parse_double(tok[c + 1], (int)line, -4.0, 4.0, k);
            }
            p->have_lcd = 1;
        } else if (!strcmp(k, "lcd_p_hz") && n == 6) {
            if (p->n_lcd_rate_p >= TDC_PANEL_MAX_RATES) {
                die(TDC_EXIT_INPUT, (int)line, "at most %d lcd_p_hz lines", TDC_PANEL_MAX_RATES);
            }
            p->lcd_rate_hz[p->n_lcd_rate_p] = parse_int(tok[1], (int)line, 1, 1000, k);
            for (int c = 0; c < 4; c++) {
                p->lcd_rate_p[p->n_lcd_rate_p][c] = parse_double(tok[c + 2], (int)line, -4.0, 4.0, k);
            }
            p->n_lcd_rate_p++;
        } else if (!strcmp(k, "lcd_state_n") && n == 2) {
            p->st_n = parse_int(tok[1], (int)line, 17, ST_MAXN, k);
            if (p->st_n != 17 && p->st_n != 33 && p->st_n != 65) {
                die(TDC_EXIT_INPUT, (int)line, "lcd_state_n must be 17, 33 or 65");
            }
        } else if ((!strcmp(k, "lcd_od") || !strcmp(k, "lcd_st") || !strcmp(k, "lcd_reach_lo") ||
                    !strcmp(k, "lcd_reach_hi")) &&
                   n >= 3) {
            const int row_key = !strcmp(k, "lcd_od") || !strcmp(k, "lcd_st");
            if (!p->st_n) {
                die(TDC_EXIT_INPUT, (int)line, "%s before lcd_state_n", k);
            }
            if (n != 3 + row_key + p->st_n) {
                die(TDC_EXIT_INPUT, (int)line, "%s: expected RATE CH%s and %d values", k, row_key ? " ROW" : "",
                    p->st_n);
            }
            const int ri = st_rate(p, parse_int(tok[1], (int)line, 1, 1000, k), line);
            const int ch = !strcmp(tok[2], "R") ? 0 : !strcmp(tok[2], "G") ? 1 : !strcmp(tok[2], "B") ? 2 : -1;
            if (ch < 0) {
                die(TDC_EXIT_INPUT, (int)line, "%s: channel must be R, G or B", k);
            }
            const int row = row_key ? parse_int(tok[3], (int)line, 0, p->st_n - 1, k) : 0;
            const int slot = !strcmp(k, "lcd_od")         ? row
                             : !strcmp(k, "lcd_st")       ? ST_MAXN + row
                             : !strcmp(k, "lcd_reach_lo") ? 2 * ST_MAXN
                                                          : 2 * ST_MAXN + 1;
            if (p->st_seen[ri][ch][slot]) {
                die(TDC_EXIT_INPUT, (int)line, "%s: rate %s channel %s%s%s given twice", k, tok[1], tok[2],
                    row_key ? " row " : "", row_key ? tok[3] : "");
            }
            p->st_seen[ri][ch][slot] = 1;
            for (int c = 0; c < p->st_n; c++) {
                const uint16_t v = (uint16_t)parse_int(tok[3 + row_key + c], (int)line, 0, 255 * 16, k);
                if (!strcmp(k, "lcd_od")) {
                    p->st_od[ri][ch][row * p->st_n + c] = v;
                } else if (!strcmp(k, "lcd_st")) {
                    p->st_next[ri][ch][row * p->st_n + c] = v;
                } else {
                    p->st_reach[ri][ch][(slot - 2 * ST_MAXN) * p->st_n + c] = v;
                }
            }
        } else if (!strcmp(k, "lcd_table") && n == 2) {
            p->lcd_table = parse_int(tok[1], (int)line, 0, 33, k);
            if (p->lcd_table != 0 && p->lcd_table != 17 && p->lcd_table != 33) {
                die(TDC_EXIT_INPUT, (int)line, "lcd_table must be 0 (exact solve), 17 or 33");
            }
        } else {
            die(TDC_EXIT_INPUT, (int)line, "unknown key or wrong number of values: '%s'", k);
        }
    }
    if (!p->name[0] || !p->type[0] || !p->width || !p->height || !p->eyes || !p->bits || !p->refresh_hz ||
        !p->have_gamma) {
        die(TDC_EXIT_INPUT, 0, "profile needs name, type, width, height, eyes, bits, refresh_hz and gamma");
    }
    if (p->peak_cdm2 > 0.0 && p->black_cdm2 >= p->peak_cdm2) {
        die(TDC_EXIT_INPUT, 0, "black_cdm2 %g must be below peak_cdm2 %g", p->black_cdm2, p->peak_cdm2);
    }
    if (!strcmp(p->type, "lcd") && !p->have_lcd) {
        die(TDC_EXIT_INPUT, 0, "an lcd profile needs lcd_p p1 p2 p3 p4");
    }
    if (p->nrates == 0) {
        p->rates[0] = p->refresh_hz;
        p->nrates = 1;
    }
    for (int i = 0; i < p->n_lcd_rate_p; i++) {
        int found = 0;
        for (int r = 0; r < p->nrates; r++) {
            found |= p->rates[r] == p->lcd_rate_hz[i];
        }
        if (!found) {
            die(TDC_EXIT_INPUT, 0, "lcd_p_hz %d: not one of rates_hz", p->lcd_rate_hz[i]);
        }
    }
}

static void parse_profile(const char *path, profile_t *p)
{
    g_in = fopen(path, "r");
    if (!g_in) {
        die(TDC_EXIT_FILE, 0, "cannot open: %s", strerror(errno));
    }
    parse_profile_stream(g_in, p);
    fclose(g_in);
    g_in = NULL;
}

/* The stateful tables of a rate: complete, of a rate the profile has. */
static void check_state_tables(const profile_t *p)
{
    for (int i = 0; i < p->st_nr; i++) {
        int found = 0;
        for (int r = 0; r < p->nrates; r++) {
            found |= p->rates[r] == p->st_rate_hz[i];
        }
        if (!found) {
            die(TDC_EXIT_INPUT, 0, "stateful tables for %d Hz: not one of rates_hz", p->st_rate_hz[i]);
        }
        for (int ch = 0; ch < 3; ch++) {
            for (int row = 0; row < p->st_n; row++) {
                if (!p->st_seen[i][ch][row] || !p->st_seen[i][ch][ST_MAXN + row]) {
                    die(TDC_EXIT_INPUT, 0, "stateful tables for %d Hz channel %c: lcd_od/lcd_st row %d missing",
                        p->st_rate_hz[i], "RGB"[ch], row);
                }
            }
            if (!p->st_seen[i][ch][2 * ST_MAXN] || !p->st_seen[i][ch][2 * ST_MAXN + 1]) {
                die(TDC_EXIT_INPUT, 0, "stateful tables for %d Hz channel %c: lcd_reach_lo/hi missing",
                    p->st_rate_hz[i], "RGB"[ch]);
            }
        }
    }
}

/* Coefficients of one rate: its lcd_p_hz line, else lcd_p. */
static const double *lcd_coefs_for_rate(const profile_t *p, int rate)
{
    for (int i = 0; i < p->n_lcd_rate_p; i++) {
        if (p->lcd_rate_hz[i] == rate) {
            return p->lcd_rate_p[i];
        }
    }
    return p->lcd_p;
}

/*
 * Overdrive table of n x n deltas (convention in firmware/tdc_overdrive.h)
 * from the QUANTISED coefficients p_q24, through the double-precision
 * inverse of common/tdc_lcd_model.h: the table and the exact firmware solve
 * describe the same model.
 */
static void gen_od_table(FILE *f, const char *decl, const int32_t p_q24[4], int n, int bits)
{
    double dp[4];
    static short t[33 * 33];
    for (int c = 0; c < 4; c++) {
        dp[c] = p_q24[c] / (double)(1 << TDC_LCD_COEF_FRAC);
    }
    tdc_lcdm_make_od(dp, n, bits, t);
    fprintf(f, "%s[%d] = {", decl, n * n);
    for (int k = 0; k < n * n; k++) {
        fprintf(f, "%s%d,", (k % 12) ? " " : "\n    ", t[k]);
    }
    fprintf(f, "\n};\n");
}

static void gen_lcd(FILE *f, const profile_t *p, const char *id)
{
    for (int r = 0; r < p->nrates; r++) {
        const double *cp = lcd_coefs_for_rate(p, p->rates[r]);
        int32_t q[4];
        for (int c = 0; c < 4; c++) {
            q[c] = (int32_t)llround(cp[c] * (double)(1 << TDC_LCD_COEF_FRAC));
        }
        char decl[160];
        snprintf(decl, sizeof decl, "static const int16_t %s_od17_%dhz", id, p->rates[r]);
        gen_od_table(f, decl, q, 17, p->bits);
        snprintf(decl, sizeof decl, "static const int16_t %s_od33_%dhz", id, p->rates[r]);
        gen_od_table(f, decl, q, 33, p->bits);
    }
    for (int i = 0; i < p->st_nr; i++) {
        const int nn = p->st_n * p->st_n;
        for (int ch = 0; ch < 3; ch++) {
            const char cn = "rgb"[ch];
            const uint16_t *src[3] = {p->st_od[i][ch], p->st_next[i][ch], p->st_reach[i][ch]};
            const int len[3] = {nn, nn, 2 * p->st_n};
            static const char *const kind[3] = {"sod", "sst", "srch"};
            for (int k = 0; k < 3; k++) {
                fprintf(f, "static const uint16_t %s_%s_%dhz_%c[%d] = {", id, kind[k], p->st_rate_hz[i], cn, len[k]);
                for (int v = 0; v < len[k]; v++) {
                    fprintf(f, "%s%u,", (v % 16) ? " " : "\n    ", src[k][v]);
                }
                fprintf(f, "\n};\n");
            }
        }
    }
    fprintf(f, "\nstatic const struct tdc_lcd_profile %s_lcd = {\n", id);
    fprintf(f, "    .nrates = %d,\n    .default_table = %d,\n    .rate = {\n", p->nrates, p->lcd_table);
    for (int r = 0; r < p->nrates; r++) {
        const double *cp = lcd_coefs_for_rate(p, p->rates[r]);
        fprintf(f, "        {%d, {", p->rates[r]);
        for (int c = 0; c < 4; c++) {
            fprintf(f, "%ld%s", (long)llround(cp[c] * (double)(1 << TDC_LCD_COEF_FRAC)), c < 3 ? ", " : "");
        }
        fprintf(f, "}, %s_od17_%dhz, %s_od33_%dhz", id, p->rates[r], id, p->rates[r]);
        int si = -1;
        for (int i = 0; i < p->st_nr; i++) {
            si = p->st_rate_hz[i] == p->rates[r] ? i : si;
        }
        if (si >= 0) {
            fprintf(f, ", %d", p->st_n);
            static const char *const kind[3] = {"sod", "sst", "srch"};
            for (int k = 0; k < 3; k++) {
                fprintf(f, ", {%s_%s_%dhz_r, %s_%s_%dhz_g, %s_%s_%dhz_b}", id, kind[k], p->rates[r], id, kind[k],
                        p->rates[r], id, kind[k], p->rates[r]);
            }
        } else {
            fprintf(f, ", 0, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}");
        }
        fprintf(f, "},\n");
    }
    fprintf(f, "    },\n};\n");
}

static void c_ident(const char *name, char *out)
{
    for (; *name; name++) {
        *out++ = (*name == '-') ? '_' : *name;
    }
    *out = 0;
}

static void emit_u32(FILE *f, const char *decl, const uint32_t *v, int n)
{
    fprintf(f, "%s[%d] = {", decl, n);
    for (int i = 0; i < n; i++) {
        fprintf(f, "%s%uu,", (i % 8) ? " " : "\n    ", v[i]);
    }
    fprintf(f, "\n};\n");
}

static void emit_u16(FILE *f, const char *decl, const uint16_t *v, int n)
{
    fprintf(f, "%s[%d] = {", decl, n);
    for (int i = 0; i < n; i++) {
        fprintf(f, "%s%u,", (i % 12) ? " " : "\n    ", v[i]);
    }
    fprintf(f, "\n};\n");
}

static void gen_gamma(FILE *f, const char *id, int ch, double gamma, int bits)
{
    static uint32_t dec[MAX_CODES + 1], thr[MAX_CODES];
    static uint16_t idx[TDC_ENC_INDEX_SIZE];
    const int codes = 1 << bits;
    const double max = codes - 1;
    const double one = (double)(1 << 24);
    for (int k = 0; k < codes; k++) {
        dec[k] = (uint32_t)llround(one * pow(k / max, gamma));
        thr[k] = k == 0 ? 0u : (uint32_t)ceil(one * pow((k - 0.5) / max, gamma));
    }
    dec[codes] = dec[codes - 1];
    int k = 0;
    for (int b = 0; b < TDC_ENC_INDEX_SIZE; b++) {
        uint32_t start = (uint32_t)b << (24 - TDC_ENC_INDEX_BITS);
        while (k + 1 < codes && thr[k + 1] <= start) {
            k++;
        }
        idx[b] = (uint16_t)k;
    }
    char decl[128];
    snprintf(decl, sizeof decl, "static const uint32_t %s_decode_%d", id, ch);
    emit_u32(f, decl, dec, codes + 1);
    snprintf(decl, sizeof decl, "static const uint32_t %s_enc_thresh_%d", id, ch);
    emit_u32(f, decl, thr, codes);
    snprintf(decl, sizeof decl, "static const uint16_t %s_enc_index_%d", id, ch);
    emit_u16(f, decl, idx, TDC_ENC_INDEX_SIZE);
}

/* Every generated file is written to a temporary renamed over path only
 * when complete (tdc_out_t): a failed run never leaves a half-written table
 * that make would take for up to date.  A failure names the file. */
static FILE *gen_open(tdc_out_t *out, const char *path)
{
    if (tdc_out_open(out, path, "w") != 0) {
        g_path = path;
        die(TDC_EXIT_FILE, 0, "cannot write: %s", strerror(errno));
    }
    return out->f;
}

static void gen_commit(tdc_out_t *out, const char *path)
{
    if (tdc_out_commit(out) != 0) {
        g_path = path;
        die(TDC_EXIT_FILE, 0, "cannot write: %s", strerror(errno));
    }
}

/*
 * Tables of the foveated remap (firmware/tdc_fov.c), panel-independent:
 *   log2(1 + k/256)            k = 0..256, Q30        (eq. 2.2: log of the radius)
 *   2^(-k/256)                 k = 0..256, Q30        (eq. 2.2: K^-1(x) = x^(1/alpha) = 2^(log2 x / alpha))
 *   atan(k/256) / (2 pi)       k = 0..256, Q32 turns  (eq. 2.2: the angle, one octant)
 *   (e^(-t^2/2) - e^-2) / (1 - e^-2) at t^2 = k/64, k = 0..256, Q15
 *                                                     (eq. 4.4: the radial Gaussian, cut at t = 2)
 *   G(2f) / (G(2f) + G(2 - 2f)) at f = k/256, k = 0..256, Q15
 *                                                     (eq. 4.4 at sigma = 1/2: the normalised weight of
 *                                                      tap floor(u), f = frac(u); floor(u) + 1 gets the rest)
 * Each is interpolated linearly by the stage; the interpolation errors are
 * stated beside the functions that read them.
 */
static void gen_fov(const char *path)
{
    tdc_out_t out;
    FILE *f = gen_open(&out, path);
    static uint32_t t[257];
    fprintf(f, "/* generated by tdc-tablegen --fov: do not edit */\n");
    fprintf(f, "#ifndef TDC_FOV_TABLES_H\n#define TDC_FOV_TABLES_H\n#include <stdint.h>\n");
    for (int k = 0; k <= 256; k++) {
        t[k] = (uint32_t)llround(ldexp(log2(1.0 + k / 256.0), 30));
    }
    emit_u32(f, "static const uint32_t tdc_fov_log2_tab", t, 257);
    for (int k = 0; k <= 256; k++) {
        t[k] = (uint32_t)llround(ldexp(exp2(-k / 256.0), 30));
    }
    emit_u32(f, "static const uint32_t tdc_fov_exp2_tab", t, 257);
    for (int k = 0; k <= 256; k++) {
        t[k] = (uint32_t)llround(ldexp(atan(k / 256.0) / (2.0 * M_PI), 32));
    }
    emit_u32(f, "static const uint32_t tdc_fov_atan_tab", t, 257);
    for (int k = 0; k <= 256; k++) {
        const double g = (exp(-0.5 * (k / 64.0)) - exp(-2.0)) / (1.0 - exp(-2.0));
        t[k] = (uint32_t)llround(ldexp(g < 0 ? 0 : g, 15));
    }
    emit_u32(f, "static const uint32_t tdc_fov_gauss_tab", t, 257);
    for (int k = 0; k <= 256; k++) { /* sigma = 1/2: the taps at d = f and 1 - f, t = 2d */
        const double e2 = exp(-2.0), f0 = k / 256.0;
        const double g0 = (exp(-0.5 * 4 * f0 * f0) - e2) / (1 - e2), g1 = (exp(-0.5 * 4 * (1 - f0) * (1 - f0)) - e2) / (1 - e2);
        t[k] = (uint32_t)llround(ldexp(fmax(g0, 0) / (fmax(g0, 0) + fmax(g1, 0)), 15));
    }
    emit_u32(f, "static const uint32_t tdc_fov_tent_tab", t, 257);
    /* log2(ln 2) in Q24 (negative): d/dr of eq. 2.2 needs ln r = log2(r) ln 2 */
    fprintf(f, "#define TDC_FOV_LOG2_LN2_Q24 (%ld)\n", lround(ldexp(log2(log(2.0)), 24)));
    fprintf(f, "#endif\n");
    gen_commit(&out, path);
}

#ifndef TDC_TABLEGEN_NO_MAIN
/*
 * TRM's exp(-x) weight table (firmware/tdc_trm_kernels.h): exp(-k/256) in
 * Q30 for k < TDC_TRM_WEXP_ENTRIES, from the firmware's own integer
 * tdc_exp_neg_q16_q30 (linked in), so the table is bit-identical to what the
 * stage computed at init before it was generated.  Included by
 * firmware/tdc_trm_rows.c only (one definition, not static).
 */
/* (not in the fuzz_panel harness, which links no firmware) */
static void gen_trm(const char *path)
{
    tdc_out_t out;
    FILE *f = gen_open(&out, path);
    static uint32_t t[TDC_TRM_WEXP_ENTRIES];
    for (uint32_t k = 0; k < TDC_TRM_WEXP_ENTRIES; k++) {
        t[k] = tdc_exp_neg_q16_q30(k << 8);
    }
    fprintf(f, "/* generated by tdc-tablegen --trm: do not edit; included by tdc_trm_rows.c only */\n");
    fprintf(f, "#ifndef TDC_TRM_TABLES_H\n#define TDC_TRM_TABLES_H\n#include <stdint.h>\n");
    emit_u32(f, "const uint32_t tdc_trm_wexp_q30", t, (int)TDC_TRM_WEXP_ENTRIES);
    fprintf(f, "#endif\n");
    gen_commit(&out, path);
}

int main(int argc, char **argv)
{
    static const char usage[] = "usage: tdc-tablegen PROFILE.panel OUTDIR | tdc-tablegen --fov OUT.h | "
                                "tdc-tablegen --trm OUT.h";
    tdc_tool_set_name("tdc-tablegen");
    if (argc == 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        printf("%s\n"
               "Writes OUTDIR/tdc_panel_NAME.c and its config header from a panel profile, or the\n"
               "foveation (--fov) or TRM (--trm) constant tables, each only when complete.\n"
               "exit codes (docs/tools.md): 0 OK, 1 ARGS, 7 FILE, 13 INPUT (a malformed profile)\n",
               usage);
        return TDC_EXIT_OK;
    }
    if (argc == 3 && !strcmp(argv[1], "--fov")) {
        gen_fov(argv[2]);
        return TDC_EXIT_OK;
    }
    if (argc == 3 && !strcmp(argv[1], "--trm")) {
        gen_trm(argv[2]);
        return TDC_EXIT_OK;
    }
    if (argc > 1 && argv[1][0] == '-') {
        return tdc_fail_usage(NULL, "unknown option '%s'", argv[1]);
    }
    if (argc != 3) {
        return tdc_fail_usage(NULL, "%s", usage);
    }
    g_path = argv[1];
    profile_t p;
    parse_profile(argv[1], &p);
    check_state_tables(&p);
    char id[80], path[1024];
    c_ident(p.name, id);
    const int is_lcd = !strcmp(p.type, "lcd");

    snprintf(path, sizeof path, "%s/tdc_panel_%s.c", argv[2], p.name);
    tdc_out_t out;
    FILE *f = gen_open(&out, path);
    fprintf(f, "/* generated by tdc-tablegen from %s: do not edit */\n", argv[1]);
    fprintf(f, "#include \"tdc_panel.h\"\n\n");
    if (is_lcd) {
        /* only LCD panels reference the LCD stage's types */
        fprintf(f, "#include \"tdc_lcd.h\"\n\n");
    }
    for (int c = 0; c < 3; c++) {
        gen_gamma(f, id, c, p.gamma[c], p.bits);
    }
    if (is_lcd) {
        gen_lcd(f, &p, id);
    }
    fprintf(f, "\nconst tdc_panel_t tdc_panel_%s = {\n", id);
    fprintf(f, "    .name = \"%s\",\n    .type = %s,\n", p.name, is_lcd ? "TDC_PANEL_LCD" : "TDC_PANEL_OLED");
    fprintf(f, "    .width = %d, .height = %d, .eyes = %d, .bits = %d, .refresh_hz = %d,\n", p.width, p.height, p.eyes,
            p.bits, p.refresh_hz);
    fprintf(f, "    .ppd_x100 = %ldu,\n", lround(p.ppd * 100.0));
    fprintf(f, "    .peak_mcdm2 = %ldu, .black_ucdm2 = %ldu, .distance_mm = %ldu,\n", lround(p.peak_cdm2 * 1e3),
            lround(p.black_cdm2 * 1e6), lround(p.distance_m * 1e3));
    fprintf(f, "    .rates_hz = {");
    for (int i = 0; i < p.nrates; i++) {
        fprintf(f, "%d, ", p.rates[i]);
    }
    fprintf(f, "0},\n    .gamma_micro = {%ldu, %ldu, %ldu},\n", lround(p.gamma[0] * 1e6), lround(p.gamma[1] * 1e6),
            lround(p.gamma[2] * 1e6));
    fprintf(f, "    .gamma = {\n");
    for (int c = 0; c < 3; c++) {
        fprintf(f, "        {%s_decode_%d, %s_enc_thresh_%d, %s_enc_index_%d},\n", id, c, id, c, id, c);
    }
    if (is_lcd) {
        fprintf(f, "    },\n    .lcd = &%s_lcd,\n};\n", id);
    } else {
        fprintf(f, "    },\n    .lcd = 0,\n};\n");
    }
    gen_commit(&out, path);

    snprintf(path, sizeof path, "%s/tdc_panel_%s_config.h", argv[2], p.name);
    f = gen_open(&out, path);
    fprintf(f, "/* generated by tdc-tablegen from %s: do not edit */\n", argv[1]);
    fprintf(f, "#ifndef TDC_PANEL_CONFIG_H\n#define TDC_PANEL_CONFIG_H\n");
    fprintf(f, "#define TDC_PANEL_NAME \"%s\"\n#define TDC_PANEL_SYMBOL tdc_panel_%s\n", p.name, id);
    fprintf(f, "#define TDC_PANEL_WIDTH %d\n#define TDC_PANEL_HEIGHT %d\n#define TDC_PANEL_EYES %d\n", p.width,
            p.height, p.eyes);
    fprintf(f, "#define TDC_PANEL_BITS %d\n#define TDC_PANEL_REFRESH_HZ %d\n#define TDC_PANEL_IS_LCD %d\n", p.bits,
            p.refresh_hz, is_lcd);
    fprintf(f, "#endif\n");
    gen_commit(&out, path);
    return TDC_EXIT_OK;
}
#endif
