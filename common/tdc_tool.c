/*
 * tdc_tool.c - exit-code names, the one-line message, overflow-checked
 * number parsing, bounded line reading and rename-on-success output files
 * shared by every tdc host program (tdc_tool.h, docs/tools.md).
 */
#include "tdc_tool.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <getopt.h>
#include <sys/stat.h>
#include <unistd.h>

#define TDC_EXIT_NAME(code, name, meaning, programs) [code] = #name,
static const char *const k_exit_names[TDC_EXIT_COUNT] = {TDC_EXIT_TABLE(TDC_EXIT_NAME)};
#undef TDC_EXIT_NAME

const char *tdc_exit_name(int code)
{
    return code >= 0 && code < TDC_EXIT_COUNT ? k_exit_names[code] : "?";
}

static const char *g_name = "tdc";

void tdc_tool_set_name(const char *name)
{
    g_name = name;
}

const char *tdc_tool_name(void)
{
    return g_name;
}

int tdc_fail(int code, const char *cmd, const char *what, const char *why_fmt, ...)
{
    /* One fprintf of the whole line, so lines of parallel writers do not interleave. */
    char why[1024];
    va_list ap;
    va_start(ap, why_fmt);
    vsnprintf(why, sizeof why, why_fmt, ap);
    va_end(ap);
    fprintf(stderr, "%s: %s%s%s%s%s\n", g_name, cmd ? cmd : "", cmd ? ": " : "", what ? what : "", what ? ": " : "",
            why);
    return code;
}

int tdc_fail_option(const char *cmd, const char *opt, const char *val, const char *want)
{
    char what[256];
    snprintf(what, sizeof what, "bad value for %s '%s'", opt, val ? val : "");
    return tdc_fail(TDC_EXIT_ARGS, cmd, what, "%s", want);
}

int tdc_fail_usage(const char *cmd, const char *why_fmt, ...)
{
    char why[1024];
    va_list ap;
    va_start(ap, why_fmt);
    vsnprintf(why, sizeof why, why_fmt, ap);
    va_end(ap);
    return tdc_fail(TDC_EXIT_ARGS, cmd, NULL, "%s: try '%s --help'", why, g_name);
}

int tdc_errf(char *err, size_t errlen, const char *fmt, ...)
{
    if (err && errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return -1;
}

int tdc_fail_getopt(int c, char *const *argv)
{
    /* glibc: optind is past the offending element; optopt is the short
     * option's letter (0 for an unknown long option) */
    char opt[3] = {'-', (char)optopt, 0};
    const char *name = c == '?' && optopt > 0 && optopt < 128 ? opt : argv[optind - 1];
    return tdc_fail_usage(NULL, c == ':' ? "option '%s' needs a value" : "unknown option '%s'", name);
}

int tdc_in_check(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    struct stat st;
    const int dir = fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode);
    fclose(f);
    if (dir) {
        errno = EISDIR;
        return -1;
    }
    return 0;
}

/* Digits of base 10 (or 16 after 0x), each step checked against the limit
 * before the multiply: a value that does not fit is refused, never wrapped. */
static int parse_digits(const char *s, const char **end, int allow_hex, uint64_t hi, uint64_t *out)
{
    unsigned base = 10;
    if (allow_hex && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
        base = 16;
        s += 2;
    }
    uint64_t v = 0;
    const char *p = s;
    for (;; p++) {
        unsigned d;
        if (*p >= '0' && *p <= '9')
            d = (unsigned)(*p - '0');
        else if (base == 16 && *p >= 'a' && *p <= 'f')
            d = (unsigned)(*p - 'a' + 10);
        else if (base == 16 && *p >= 'A' && *p <= 'F')
            d = (unsigned)(*p - 'A' + 10);
        else
            break;
        if (d > hi || v > (hi - d) / base) return -1;
        v = v * base + d;
    }
    if (p == s) return -1;
    *end = p;
    *out = v;
    return 0;
}

int tdc_parse_u64(const char *s, uint64_t lo, uint64_t hi, uint64_t *out)
{
    const char *end;
    uint64_t v;
    if (s == NULL || parse_digits(s, &end, 1, hi, &v) != 0 || *end != '\0' || v < lo) return -1;
    *out = v;
    return 0;
}

int tdc_parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *out)
{
    uint64_t v;
    if (tdc_parse_u64(s, lo, hi, &v) != 0) return -1;
    *out = (uint32_t)v;
    return 0;
}

int tdc_parse_int(const char *s, int lo, int hi, int *out)
{
    if (s == NULL) return -1;
    int neg = s[0] == '-';
    const char *end;
    uint64_t mag;
    uint64_t lim = neg ? (uint64_t) - (int64_t)lo : (uint64_t)(hi < 0 ? 0 : hi);
    if ((neg && lo >= 0) || parse_digits(s + neg, &end, 0, lim, &mag) != 0 || *end != '\0') return -1;
    int64_t v = neg ? -(int64_t)mag : (int64_t)mag;
    if (v < lo || v > hi) return -1;
    *out = (int)v;
    return 0;
}

int tdc_parse_double_field(const char *s, const char **end, double *out)
{
    char *e;
    if (s == NULL) return -1;
    errno = 0;
    double v = strtod(s, &e);
    if (e == s || errno == ERANGE || !isfinite(v)) return -1;
    *end = e;
    *out = v;
    return 0;
}

int tdc_parse_double(const char *s, double lo, double hi, double *out)
{
    const char *end;
    double v;
    /* strtod skips leading white space; the convention does not. */
    if (s == NULL || s[0] == ' ' || s[0] == '\t' || tdc_parse_double_field(s, &end, &v) != 0 || *end != '\0' ||
        !(v >= lo && v <= hi))
        return -1;
    *out = v;
    return 0;
}

int tdc_parse_size(const char *s, unsigned max, unsigned *w, unsigned *h)
{
    const char *end;
    uint64_t a, b;
    if (s == NULL || parse_digits(s, &end, 0, max, &a) != 0 || *end != 'x' ||
        parse_digits(end + 1, &end, 0, max, &b) != 0 || *end != '\0' || a < 1 || b < 1)
        return -1;
    *w = (unsigned)a;
    *h = (unsigned)b;
    return 0;
}

int tdc_parse_u64_field(const char *s, const char **end, uint64_t hi, uint64_t *out)
{
    return s == NULL ? -1 : parse_digits(s, end, 0, hi, out);
}

int tdc_read_line(FILE *f, char *buf, size_t cap, unsigned *lineno)
{
    size_t n = 0;
    int c, too_long = 0, nul = 0;
    while ((c = getc(f)) != EOF && c != '\n') {
        if (c == 0) nul = 1;
        if (n + 1 < cap)
            buf[n++] = (char)c;
        else
            too_long = 1;
    }
    if (cap > 0) buf[n] = '\0';
    if (c == EOF && ferror(f)) return -2;
    if (c == EOF && n == 0 && !too_long) return 0;
    (*lineno)++;
    if (n > 0 && buf[n - 1] == '\r') buf[n - 1] = '\0';
    return too_long || nul ? -1 : 1;
}

int tdc_out_open(tdc_out_t *o, const char *path, const char *mode)
{
    o->f = NULL;
    if (snprintf(o->path, sizeof o->path, "%s", path) >= (int)sizeof o->path ||
        snprintf(o->tmp, sizeof o->tmp, "%s.tmp.%ld", path, (long)getpid()) >= (int)sizeof o->tmp) {
        errno = ENAMETOOLONG;
        return -1;
    }
    o->f = fopen(o->tmp, mode);
    return o->f ? 0 : -1;
}

int tdc_out_commit(tdc_out_t *o)
{
    if (o->f == NULL) {
        errno = EBADF;
        return -1;
    }
    errno = 0;
    int bad = ferror(o->f) != 0;
    bad |= fflush(o->f) != 0;
    bad |= fclose(o->f) != 0;
    o->f = NULL;
    if (!bad && rename(o->tmp, o->path) == 0) return 0;
    int e = errno ? errno : EIO;
    remove(o->tmp);
    errno = e;
    return -1;
}

void tdc_out_abort(tdc_out_t *o)
{
    if (o->f != NULL) {
        fclose(o->f);
        o->f = NULL;
        remove(o->tmp);
    }
}

int tdc_safe_name(const char *name)
{
    size_t n = strlen(name);
    if (n == 0 || n > 128 || strcmp(name, ".") == 0 || strcmp(name, "..") == 0) return 0;
    return strspn(name, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") == n;
}
