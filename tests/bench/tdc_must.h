/*
 * tdc_must.h - for benchmarks and tools-like tests that run a firmware stage
 * outside cmocka: TDC_MUST(call) evaluates a call returning tdc_status_t and,
 * unless it is TDC_OK, prints "FILE:LINE: call: TDC_ERR_x (text)" and exits 1
 * (a benchmark that times a refused call would time nothing).  cmocka tests
 * use assert_int_equal(call, TDC_OK) instead.
 */
#ifndef TDC_MUST_H
#define TDC_MUST_H

#include <stdio.h>
#include <stdlib.h>

#include "tdc_status.h"

static inline void tdc_must_impl(tdc_status_t st, const char *call, const char *file, int line)
{
    if (st != TDC_OK) {
        fprintf(stderr, "%s:%d: %s: %s (%s)\n", file, line, call, tdc_status_name(st), tdc_status_text(st));
        exit(1);
    }
}

#define TDC_MUST(call) tdc_must_impl((call), #call, __FILE__, __LINE__)

#endif /* TDC_MUST_H */
