/*
 * tdc_meas.h - reader of the LCD measurement files (docs/lcd.md §5), shared
 * by tdc-calib and its fuzz target (tests/fuzz/fuzz_meas.c).
 *
 * Two formats, told apart by their header line:
 *   pairs (v1, paper Fig. 7):  rate_hz,channel,code_a,code_b,luminance_cd_m2
 *   transitions (v2):          rate_hz,channel,prev_code,code,run,light_cd_m2,end_cd_m2
 * '#' starts a comment line; blank lines are skipped.  Every field is parsed
 * with range and overflow checks (no atoi/sscanf wrap-around: 4294967299 is
 * an error, not 3), lines longer than TDC_MEAS_MAX_LINE are refused with
 * their number, and every message names the file, the line and the field.
 */
#ifndef TDC_MEAS_H
#define TDC_MEAS_H

#include <stddef.h>

#include "tdc_tool.h"

#define TDC_MEAS_MAX_LINE 511
#define TDC_MEAS_MAX_ROWS 2000000

enum { TDC_MEAS_PAIRS = 1, TDC_MEAS_TRANSITIONS = 2 };

typedef struct {
    int rate, ch, a, b; /* pairs: a, b; transitions: a = prev_code, b = code */
    int run;            /* transitions: repetition index (0 for pairs) */
    double lum;         /* pairs: luminance; transitions: light within the refresh */
    double end;         /* transitions: luminance of the state at the refresh's end */
    int line;           /* line in the file (for messages) */
} tdc_meas_row_t;

typedef struct {
    int kind; /* TDC_MEAS_PAIRS or TDC_MEAS_TRANSITIONS */
    tdc_meas_row_t *rows;
    size_t nrows, cap;
    int max_code; /* largest code in the file */
} tdc_meas_t;

/* Parses len bytes of text named `path` (for messages).  0 on success; else
 * -1 with one line "PATH:LINE: field NAME: what is wrong" in err.  The rows
 * are malloc'ed: tdc_meas_free() in both cases. */
int tdc_meas_parse(const char *text, size_t len, const char *path, tdc_meas_t *m, char *err, size_t errlen);

/* Reads and parses a file (at most 256 MiB); -2 when the file cannot be
 * opened or read (exit code FILE), -1 for its contents (INPUT). */
int tdc_meas_load(const char *path, tdc_meas_t *m, char *err, size_t errlen);

void tdc_meas_free(tdc_meas_t *m);

/* Numbers (options and fields) are parsed with common/tdc_tool.h
 * (tdc_parse_int, tdc_parse_double: the whole string, in range, no wrap). */

#endif /* TDC_MEAS_H */
