/*
 * tdc_linkdump.c - checks a .tdcs link stream file with the firmware
 * decoder: lists error events (and with -v every accepted packet), then the
 * counters.  Exit status 0: clean stream, 1: errors in the stream, 2: the
 * file cannot be read / is not a stream.
 * Usage: tdc-linkdump [-v] FILE.tdcs
 */
#include <stdio.h>
#include <string.h>

#include "link/tdc_link_file.h"

int main(int argc, char **argv)
{
    int verbose = 0, a = 1;
    if (a < argc && !strcmp(argv[a], "-v")) {
        verbose = 1;
        a++;
    }
    if (a + 1 != argc) {
        fprintf(stderr, "usage: %s [-v] FILE.tdcs\n", argv[0]);
        return 2;
    }
    tdc_link_file_summary_t s;
    const int rc = tdc_link_file_check(argv[a], stdout, verbose, &s);
    if (rc < 0) {
        return 2;
    }
    printf("%s: stream %u, %ux%u x %u eye(s), flags 0x%x, r = %u/%u, %u Hz; %llu bytes, %u packets accepted\n", argv[a],
           s.stream_id, s.stream.width, s.stream.height, s.stream.eyes, (unsigned)s.stream.flags, s.stream.r_num,
           s.stream.r_den, s.stream.refresh_hz, (unsigned long long)s.bytes, s.counters.packets_ok);
    for (int k = TDC_LINK_KIND_FIRST; k <= TDC_LINK_KIND_LAST; k++) {
        if (s.counters.packets_by_kind[k]) {
            printf("  %-9s %u\n", tdc_link_kind_name((uint32_t)k), s.counters.packets_by_kind[k]);
        }
    }
    for (int e = 1; e < TDC_LINK_ERR_COUNT; e++) {
        if (s.counters.errors[e]) {
            printf("  error %-15s %u\n", tdc_link_err_name((tdc_link_err_t)e), s.counters.errors[e]);
        }
    }
    if (s.counters.garbage_bytes) {
        printf("  garbage bytes   %llu\n", (unsigned long long)s.counters.garbage_bytes);
    }
    if (s.counters.missing_reduced_frames) {
        printf("  missing reduced %u\n", s.counters.missing_reduced_frames);
    }
    return rc;
}
