/*
 * fuzz_tdcs.c - libFuzzer harness of the .tdcs stream-file reader
 * (common/tdc_link_file.c: packet reader, raw reader and the whole-file
 * check behind tdc-linkdump), on any bytes as a file (a memfd).  Built with
 * a small compiled maximum (TDC_PANEL_WIDTH/HEIGHT 96 x 64, like a small
 * board), so a header claiming a large stream is refused quickly.
 * Aborts (besides the sanitizers) when:
 *   - the packet reader returns more bytes in total than the file has, or a
 *     packet larger than its buffer;
 *   - the check calls a file "clean" (0) while it counted an error, a
 *     truncated tail or fewer bytes than the file holds;
 *   - the check returns anything but -1, 0 or 1.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "tdc_link_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int fd = -1;
    static char path[64];
    static uint8_t buf[1 << 16];
    if (fd < 0) {
        fd = memfd_create("fuzz.tdcs", 0);
        if (fd < 0) abort();
        snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    }
    if (ftruncate(fd, 0) != 0 || pwrite(fd, data, size, 0) != (ssize_t)size) abort();
    tdc_link_file_t lf;
    if (tdc_link_file_open(&lf, path) == 0) {
        uint64_t total = 0;
        for (;;) {
            tdc_link_header_t f;
            long n = tdc_link_file_read_packet(&lf, buf, sizeof buf, &f);
            if (n <= 0) break;
            if ((size_t)n > sizeof buf || f.payload_len > (uint32_t)n) abort();
            total += (uint64_t)n;
            if (total > size) abort();
        }
        tdc_link_file_close(&lf);
    }
    tdc_link_file_summary_t s;
    const int rc = tdc_link_file_check(path, NULL, 0, &s);
    if (rc < -1 || rc > 1) abort();
    if (rc == 0) {
        if (s.truncated_bytes != 0 || s.bytes != size) abort();
        for (int e = 1; e < TDC_LINK_ERR_COUNT; e++)
            if (s.counters.errors[e] != 0) abort();
    }
    return 0;
}
