/*
 * golden_arm_main.c - golden-vector runner for the emulated Cortex-M boards.
 * Runs every registered stage (golden_list.h, the same list the host runner
 * uses) and writes its lines to the host's stdout through semihosting;
 * tests/arm/run_golden_qemu.sh compares them with tests/golden/STAGE.expected.
 * The exit status (SYS_EXIT_EXTENDED) is 0 only if every stage ran and
 * wrote at least one line.
 */
#include <stdint.h>

#include "board.h"
#include "golden.h"
#include "golden_list.h"
#include "tdc_semihost.h"
#include "tdc_text.h"

/* Lines are batched: one semihosting trap per 2 KiB instead of per line. */
static char g_out[2048];
static uint32_t g_fill;

static void flush_out(void)
{
    if (g_fill) {
        tdc_semihost_write(1, g_out, g_fill);
        g_fill = 0;
    }
}

static void write_semihost(tdc_golden_ctx_t *ctx, const char *line)
{
    (void)ctx;
    while (*line) {
        if (g_fill == sizeof g_out) {
            flush_out();
        }
        g_out[g_fill++] = *line++;
    }
}

static void put_u32(uint32_t v)
{
    char s[12];
    *tdc_text_u32(s, s + sizeof s - 1, v) = 0;
    tdc_semihost_puts(2, s);
}

#define DECLARE(stage) void tdc_golden_##stage(tdc_golden_ctx_t *ctx);
TDC_GOLDEN_LIST(DECLARE)

int main(void)
{
    tdc_golden_ctx_t ctx = {write_semihost, 0, 0};
    uint32_t stages = 0, silent = 0;
#define RUN(stage)                                                                                    \
    {                                                                                                 \
        uint32_t before = ctx.lines;                                                                  \
        tdc_golden_##stage(&ctx);                                                                     \
        stages++;                                                                                     \
        if (ctx.lines == before) {                                                                    \
            flush_out();                                                                              \
            tdc_semihost_puts(2, "[" TDC_BOARD_NAME "] golden stage " #stage " wrote no checksum\n"); \
            silent++;                                                                                 \
        }                                                                                             \
    }
    TDC_GOLDEN_LIST(RUN)
    flush_out();
    tdc_semihost_puts(2, "[" TDC_BOARD_NAME "] golden runner: ");
    put_u32(stages);
    tdc_semihost_puts(2, " stages, ");
    put_u32(ctx.lines);
    tdc_semihost_puts(2, " checksums\n");
    return silent ? 1 : 0;
}
