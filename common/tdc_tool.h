/*
 * tdc_tool.h - the one convention of every tdc host program (tdc-run,
 * tdc-sim, tdc-render, tdc-linkdump, tdc-usb, tdc-gpio, tdc-calib,
 * tdc-lcd-measure, the table generator): one table of named exit codes,
 * one-line messages "tool: command: what failed: why", and number parsing
 * that refuses what does not fit instead of wrapping it.
 *
 * The table is tdc_exit.h; it and the message format are in docs/tools.md; a
 * program uses the codes that can happen in it and never gives a code
 * another meaning.  Host code only (libc, stdio).
 */
#ifndef TDC_TOOL_H
#define TDC_TOOL_H

#include <stdint.h>
#include <stdio.h>

#include "tdc_exit.h"

/* Named exit codes, positive so shells see them (picotool style): the one
 * table in tdc_exit.h, TDC_EXIT_OK = 0, TDC_EXIT_ARGS = 1, ... */
#define TDC_EXIT_ENUM(code, name, meaning, programs) TDC_EXIT_##name = code,
typedef enum { TDC_EXIT_TABLE(TDC_EXIT_ENUM) } tdc_exit_t;
#undef TDC_EXIT_ENUM

#define TDC_EXIT_ONE(code, name, meaning, programs) +1
enum { TDC_EXIT_COUNT = 0 TDC_EXIT_TABLE(TDC_EXIT_ONE) };
#undef TDC_EXIT_ONE

/* "OK", "ARGS", ... ; "?" for a value outside the table. */
const char *tdc_exit_name(int code);

/* The program name used as the first field of every message (default
 * "tdc"); set once at the top of main(). */
void tdc_tool_set_name(const char *name);
const char *tdc_tool_name(void);

/* Prints one line to stderr, "tool: cmd: what: why\n" (cmd and what may be
 * NULL: their field is left out), and returns code, so a failure is
 * `return tdc_fail(TDC_EXIT_FILE, "flash", path, "%s", strerror(errno));`. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
int tdc_fail(int code, const char *cmd, const char *what, const char *why_fmt, ...);

/* A bad option value: "tool: cmd: bad value for OPT 'VAL': WANT" -> ARGS. */
int tdc_fail_option(const char *cmd, const char *opt, const char *val, const char *want);

/* Any other bad command line: "tool: cmd: WHY: try 'tool --help'" -> ARGS
 * (one line: the usage goes to stdout on --help only). */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
int tdc_fail_usage(const char *cmd, const char *why_fmt, ...);

/* For a library function that reports to its caller rather than exiting:
 * formats one message line into err (if err and errlen) and returns -1, so
 * a refusal is `return tdc_errf(err, errlen, "...", ...)`. */
int tdc_errf(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* getopt_long() returned '?' or ':' (call it with opterr = 0 and an
 * optstring starting with ':'): the unknown option, or the one missing its
 * value, as one tdc_fail_usage() line -> ARGS. */
int tdc_fail_getopt(int c, char *const *argv);

/* An input file before it is read: 0 when path can be opened for reading
 * and is not a folder, else -1 with errno (EISDIR for a folder), so a folder
 * is FILE ("cannot read"), not a malformed (INPUT) empty file. */
int tdc_in_check(const char *path);

/* ---- numbers: the whole string, decimal (or 0x hex where noted), no sign
 * unless signed, no white space, no wrap.  Return 0 on success, -1 (and
 * leave *out alone) when the text is not a number or is outside [lo, hi]. */
int tdc_parse_u64(const char *s, uint64_t lo, uint64_t hi, uint64_t *out); /* 0x.. accepted */
int tdc_parse_u32(const char *s, uint32_t lo, uint32_t hi, uint32_t *out);
int tdc_parse_int(const char *s, int lo, int hi, int *out); /* optional '-' */
/* Finite doubles only: "nan", "inf" and overflow are refused. */
int tdc_parse_double(const char *s, double lo, double hi, double *out);
/* "WxH" with 1 <= W, H <= max each. */
int tdc_parse_size(const char *s, unsigned max, unsigned *w, unsigned *h);

/* A field inside a line (CSV, key/value files): parses an unsigned decimal
 * at s up to the first character that is not a digit, which is returned in
 * *end.  -1 when there is no digit or the value exceeds hi (never wraps). */
int tdc_parse_u64_field(const char *s, const char **end, uint64_t hi, uint64_t *out);
/* A finite double field (strtod syntax); *end after it; -1 on none/nan/inf/overflow. */
int tdc_parse_double_field(const char *s, const char **end, double *out);

/* ---- lines: reads one line of at most cap-1 bytes (without the '\n').
 * Returns 1 for a line, 0 at end of file, -1 for a line longer than the
 * buffer (the rest of that line is consumed, nothing of it is parsed) or a
 * NUL byte in it, -2 for a read error.  *lineno counts lines. */
int tdc_read_line(FILE *f, char *buf, size_t cap, unsigned *lineno);

/* ---- output files that never destroy what was there: written to
 * "PATH.tmp.PID" and renamed over PATH only by tdc_out_commit(). */
typedef struct {
    FILE *f;
    char path[4096];
    char tmp[4120];
} tdc_out_t;
/* 0 and o->f open, or -1 with errno set (nothing created). */
int tdc_out_open(tdc_out_t *o, const char *path, const char *mode);
/* fflush + fclose + rename; -1 with errno set (the temporary is removed and
 * PATH is untouched). */
int tdc_out_commit(tdc_out_t *o);
/* Closes and removes the temporary; PATH is untouched. */
void tdc_out_abort(tdc_out_t *o);

/* ---- a file name from untrusted text (scene names, frame names): 1 when
 * name is a plain file name: 1..128 bytes of [A-Za-z0-9._-], not "." or
 * "..", no '/', so OUTDIR/name stays inside OUTDIR. */
int tdc_safe_name(const char *name);

#endif
