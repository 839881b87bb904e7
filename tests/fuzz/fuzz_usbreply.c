/*
 * fuzz_usbreply.c - libFuzzer harness of tdc-usb's parsing of board replies
 * (hosttools/usb/tdc_usb_reply.c): BOARD_INFO, the DFU functional
 * descriptor among an interface's extra descriptors, string descriptors
 * and the bulk IN status report, each on the input bytes as received (an
 * exact-size copy, so ASan sees any read past what arrived).
 * Aborts (besides the sanitizers) when an accepted board info has a name
 * that is not NUL-terminated within its field, a transfer size outside
 * 64..4096 (other than the default), or a decoded string longer than its
 * buffer, not terminated or with a non-printable character.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tdc_usb_reply.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > 4096) return 0;
    const uint8_t sel = data[0];
    const int n = (int)size - 1;
    uint8_t *raw = malloc(n ? (size_t)n : 1u);
    if (raw == NULL) return 0;
    memcpy(raw, data + 1, (size_t)n);
    board_info_t bi;
    if (tdc_usb_parse_info(n ? raw : NULL, n, &bi) == 0 &&
        (memchr(bi.board, 0, sizeof bi.board) == NULL || memchr(bi.panel, 0, sizeof bi.panel) == NULL))
        abort();
    const uint16_t xs = tdc_usb_dfu_transfer_size(raw, n, 1024);
    if (xs != 1024 && (xs < 64 || xs > 4096)) abort();
    char s[64];
    const int cap = 1 + sel % 64u;
    const int k = tdc_usb_string_decode(raw, n, s, cap);
    if (k >= cap || (k >= 0 && (int)strlen(s) != k)) abort();
    for (int i = 0; k > 0 && i < k; i++)
        if (s[i] < 0x20 || s[i] >= 0x7F) abort();
    tdc_usb_status_t st;
    (void)tdc_usb_parse_status(raw, n, &st);
    free(raw);
    return 0;
}
