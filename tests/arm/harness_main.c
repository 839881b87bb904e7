/*
 * harness_main.c - self-test image of the QEMU golden harness: shows that
 * the harness can fail.  The mode comes from QEMU's -append (semihosting
 * SYS_GET_CMDLINE):
 *   "lines"   writes three golden-format lines and exits 0
 *   "exit3"   writes nothing and exits with status 3
 *   "fault"   executes an undefined instruction (HardFault)
 *   "hang"    spins forever (the harness's timeout must end it)
 * tests/arm/test_harness.sh drives it.
 */
#include <stdint.h>

#include "board.h"
#include "golden.h"
#include "tdc_content.h"
#include "tdc_semihost.h"

static void write_line(tdc_golden_ctx_t *ctx, const char *line)
{
    (void)ctx;
    tdc_semihost_puts(1, line);
}

static int same(const char *a, const char *b)
{
    while (*a && *a == *b) {
        a++;
        b++;
    }
    return *a == *b;
}

static uint8_t g_frame[64 * 48 * 3];

int main(void)
{
    char cmd[256];
    const char *mode = cmd;
    if (tdc_semihost_cmdline(cmd, sizeof cmd) < 0) {
        cmd[0] = 0;
    }
    for (const char *p = cmd; *p; p++) {
        if (*p == ' ') {
            mode = p + 1;
        }
    }
    if (same(mode, "lines")) {
        tdc_golden_ctx_t ctx = {write_line, 0, 0};
        for (uint32_t t = 0; t < 3u; t++) {
            tdc_content_frame(TDC_CONTENT_TEXT, t, 1u, g_frame, 64, 48, 64 * 3);
            tdc_golden_emit(&ctx, "harness", "text", t, tdc_fnv1a64(TDC_FNV64_INIT, g_frame, sizeof g_frame));
        }
        return 0;
    }
    if (same(mode, "exit3")) {
        return 3;
    }
    if (same(mode, "fault")) {
        __asm__ volatile("udf #0");
        return 0;
    }
    if (same(mode, "hang")) {
        for (volatile uint32_t spin = 0;; spin++) {
        }
    }
    tdc_semihost_puts(2, "harness: unknown mode\n");
    return 2;
}
