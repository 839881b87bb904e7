/*
 * tdc_linkdump.c - checks a .tdcs link stream file with the firmware
 * decoder: lists error events (and with -v every accepted packet), then the
 * counters.  Exit codes (docs/tools.md): 0 OK (a clean stream), 1 ARGS,
 * 7 FILE (cannot read it), 13 INPUT (not a stream, errors in the stream,
 * or the file ends inside a packet).
 * Usage: tdc-linkdump [-v] FILE.tdcs
 */
#include <stdio.h>
#include <string.h>

#include "tdc_link_file.h"
#include "tdc_tool.h"

int main(int argc, char **argv)
{
    int verbose = 0, a = 1;
    tdc_tool_set_name("tdc-linkdump");
    if (a < argc && (!strcmp(argv[a], "-h") || !strcmp(argv[a], "--help"))) {
        printf("usage: tdc-linkdump [-v] FILE.tdcs\n"
               "Decodes a .tdcs link stream with the firmware decoder; lists error events\n"
               "(-v: every accepted packet) and the counters.\n"
               "exit codes (docs/tools.md): 0 OK (clean), 1 ARGS, 7 FILE, 13 INPUT (not a stream,\n"
               "  errors in it, or it ends inside a packet)\n");
        return TDC_EXIT_OK;
    }
    if (a < argc && !strcmp(argv[a], "-v")) {
        verbose = 1;
        a++;
    }
    if (a < argc && argv[a][0] == '-' && argv[a][1] != '\0') {
        return tdc_fail_usage(NULL, "unknown option '%s'", argv[a]);
    }
    if (a + 1 != argc) {
        return tdc_fail_usage(NULL, "usage: tdc-linkdump [-v] FILE.tdcs");
    }
    tdc_link_file_summary_t s;
    const int rc = tdc_link_file_check(argv[a], stdout, verbose, &s);
    if (rc < 0) {
        return tdc_fail(rc == -2 ? TDC_EXIT_FILE : TDC_EXIT_INPUT, NULL, argv[a], "%s", s.err);
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
    if (s.truncated_bytes) {
        return tdc_fail(TDC_EXIT_INPUT, NULL, argv[a], "the file ends inside a packet or with garbage (%u bytes)",
                        s.truncated_bytes);
    }
    if (rc != 0) {
        return tdc_fail(TDC_EXIT_INPUT, NULL, argv[a], "the stream has errors (listed above)");
    }
    return TDC_EXIT_OK;
}
