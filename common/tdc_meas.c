/*
 * tdc_meas.c - LCD measurement file reader (formats and checks: tdc_meas.h).
 */
#include "tdc_meas.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_tool.h"

void tdc_meas_free(tdc_meas_t *m)
{
    if (m) {
        free(m->rows);
        memset(m, 0, sizeof *m);
    }
}

static const char k_hdr_pairs[] = "rate_hz,channel,code_a,code_b,luminance_cd_m2";
static const char k_hdr_trans[] = "rate_hz,channel,prev_code,code,run,light_cd_m2,end_cd_m2";

int tdc_meas_parse(const char *text, size_t len, const char *path, tdc_meas_t *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    static const char *const names[2][7] = {
        {"rate_hz", "channel", "code_a", "code_b", "luminance_cd_m2", "", ""},
        {"rate_hz", "channel", "prev_code", "code", "run", "light_cd_m2", "end_cd_m2"}};
    char buf[TDC_MEAS_MAX_LINE + 2];
    size_t pos = 0;
    int line = 0;
    while (pos < len) {
        size_t e = pos;
        while (e < len && text[e] != '\n') {
            e++;
        }
        line++;
        size_t n = e - pos;
        if (n > TDC_MEAS_MAX_LINE) {
            return tdc_errf(err, errlen, "%s:%d: line longer than %d characters", path, line, TDC_MEAS_MAX_LINE);
        }
        memcpy(buf, text + pos, n);
        buf[n] = 0;
        pos = e + 1;
        if (n && buf[n - 1] == '\r') {
            buf[--n] = 0;
        }
        if (memchr(buf, 0, n)) {
            return tdc_errf(err, errlen, "%s:%d: NUL byte in a text line", path, line);
        }
        char *s = buf;
        while (*s == ' ' || *s == '\t') {
            s++;
        }
        if (!*s || *s == '#') {
            continue;
        }
        if (!m->kind) {
            if (!strcmp(s, k_hdr_pairs)) {
                m->kind = TDC_MEAS_PAIRS;
            } else if (!strcmp(s, k_hdr_trans)) {
                m->kind = TDC_MEAS_TRANSITIONS;
            } else {
                return tdc_errf(err, errlen, "%s:%d: expected the header %s (pairs) or %s (transitions)", path,
                                     line, k_hdr_pairs, k_hdr_trans);
            }
            continue;
        }
        const int nf = m->kind == TDC_MEAS_PAIRS ? 5 : 7;
        const char *const *nm = names[m->kind - 1];
        char *fld[8];
        int k = 0;
        for (char *p = s;; p++) {
            if (k < 8) {
                fld[k] = p;
            }
            k++;
            p = strchr(p, ',');
            if (!p) {
                break;
            }
            *p = 0;
        }
        if (k != nf) {
            return tdc_errf(err, errlen, "%s:%d: %d fields, expected %d (%s)", path, line, k, nf,
                                 m->kind == TDC_MEAS_PAIRS ? k_hdr_pairs : k_hdr_trans);
        }
        tdc_meas_row_t r = {0};
        int v;
        r.line = line;
        if (tdc_parse_int(fld[0], 1, 1000, &v)) {
            return tdc_errf(err, errlen, "%s:%d: field %s: '%s' is not an integer in 1..1000", path, line, nm[0],
                                 fld[0]);
        }
        r.rate = v;
        if (strlen(fld[1]) != 1 || !strchr("RGB", fld[1][0])) {
            return tdc_errf(err, errlen, "%s:%d: field %s: '%s' is not R, G or B", path, line, nm[1], fld[1]);
        }
        r.ch = fld[1][0] == 'R' ? 0 : fld[1][0] == 'G' ? 1 : 2;
        if (tdc_parse_int(fld[2], 0, 1023, &v)) {
            return tdc_errf(err, errlen, "%s:%d: field %s: '%s' is not an integer in 0..1023", path, line, nm[2],
                                 fld[2]);
        }
        r.a = v;
        if (tdc_parse_int(fld[3], 0, 1023, &v)) {
            return tdc_errf(err, errlen, "%s:%d: field %s: '%s' is not an integer in 0..1023", path, line, nm[3],
                                 fld[3]);
        }
        r.b = v;
        int li = 4;
        if (m->kind == TDC_MEAS_TRANSITIONS) {
            if (tdc_parse_int(fld[4], 0, 999, &v)) {
                return tdc_errf(err, errlen, "%s:%d: field %s: '%s' is not an integer in 0..999", path, line,
                                     nm[4], fld[4]);
            }
            r.run = v;
            li = 5;
        }
        if (tdc_parse_double(fld[li], -1e6, 1e6, &r.lum)) {
            return tdc_errf(err, errlen, "%s:%d: field %s: '%s' is not a finite number (cd/m^2)", path, line,
                                 nm[li], fld[li]);
        }
        if (m->kind == TDC_MEAS_TRANSITIONS && tdc_parse_double(fld[6], -1e6, 1e6, &r.end)) {
            return tdc_errf(err, errlen, "%s:%d: field %s: '%s' is not a finite number (cd/m^2)", path, line,
                                 nm[6], fld[6]);
        }
        if (m->nrows == TDC_MEAS_MAX_ROWS) {
            return tdc_errf(err, errlen, "%s:%d: more than %d rows", path, line, TDC_MEAS_MAX_ROWS);
        }
        if (m->nrows == m->cap) {
            size_t nc = m->cap ? 2 * m->cap : 1024;
            tdc_meas_row_t *nr = realloc(m->rows, nc * sizeof *nr);
            if (!nr) {
                return tdc_errf(err, errlen, "%s:%d: out of memory", path, line);
            }
            m->rows = nr;
            m->cap = nc;
        }
        m->rows[m->nrows++] = r;
        m->max_code = r.a > m->max_code ? r.a : m->max_code;
        m->max_code = r.b > m->max_code ? r.b : m->max_code;
    }
    if (!m->kind) {
        return tdc_errf(err, errlen, "%s: no header line (empty file?)", path);
    }
    if (!m->nrows) {
        return tdc_errf(err, errlen, "%s: no measurements after the header", path);
    }
    return 0;
}

int tdc_meas_load(const char *path, tdc_meas_t *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    FILE *f = tdc_in_check(path) == 0 ? fopen(path, "rb") : NULL; /* a folder: EISDIR, FILE */
    if (!f) {
        tdc_errf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -2;
    }
    size_t cap = 1 << 16, n = 0;
    char *text = malloc(cap);
    const size_t limit = (size_t)256 << 20;
    while (text) {
        if (n == cap) {
            if (cap >= limit) {
                free(text);
                fclose(f);
                return tdc_errf(err, errlen, "%s: larger than 256 MiB", path);
            }
            char *t = realloc(text, cap * 2);
            if (!t) {
                free(text);
                text = NULL;
                break;
            }
            text = t;
            cap *= 2;
        }
        size_t got = fread(text + n, 1, cap - n, f);
        n += got;
        if (got == 0) {
            break;
        }
    }
    const int rd_err = ferror(f);
    fclose(f);
    if (!text || rd_err) {
        free(text);
        tdc_errf(err, errlen, "%s: read error", path);
        return -2;
    }
    int rc = tdc_meas_parse(text, n, path, m, err, errlen);
    free(text);
    return rc;
}
