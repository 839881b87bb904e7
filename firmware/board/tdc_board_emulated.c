/*
 * tdc_board_emulated.c - the board interface on the QEMU-emulated boards
 * (mps2-an500, mps3-an547).
 *
 *   transport: the link stream is a .tdcs file on the host, read through
 *              semihosting in 16 KiB chunks (like USB bulk transfers); its
 *              path is the last word of QEMU's -append
 *   panel:     each shown frame becomes one line "frame N fnv1a64" on the
 *              host's stdout (the bytes that would be scanned out)
 *   vsync:     none (no panel refresh to wait for)
 *   timer:     SysTick at the board clock, extended to 32 bits in software
 *              (read it at least once per 2^24 cycles)
 *   reset:     always power-on (QEMU cold-starts the machine)
 */
#include "board.h"
#include "tdc_board.h"
#include "tdc_semihost.h"
#include "tdc_text.h"

#define SYST_CSR (*(volatile uint32_t *)(uintptr_t)(TDC_BOARD_SYSTICK_BASE + 0x0u))
#define SYST_RVR (*(volatile uint32_t *)(uintptr_t)(TDC_BOARD_SYSTICK_BASE + 0x4u))
#define SYST_CVR (*(volatile uint32_t *)(uintptr_t)(TDC_BOARD_SYSTICK_BASE + 0x8u))

static int32_t g_stream = -1;
static uint32_t g_last_tick, g_cycles_hi, g_cycles_lo;

tdc_board_status_t tdc_board_init(void)
{
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0u;
    SYST_CSR = 5u; /* enable, processor clock, no interrupt */
    g_last_tick = SYST_CVR;
    static char cmd[256];
    const char *path = cmd;
    if (tdc_semihost_cmdline(cmd, sizeof cmd) < 0) {
        return TDC_BOARD_ERR_IO;
    }
    for (const char *p = cmd; *p; p++) {
        if (*p == ' ') {
            path = p + 1;
        }
    }
    g_stream = tdc_semihost_open_read(path);
    if (g_stream < 0) {
        tdc_semihost_puts(2, "[" TDC_BOARD_NAME "] cannot open the stream file given with -append\n");
        return TDC_BOARD_ERR_IO;
    }
    return TDC_BOARD_OK;
}

tdc_board_status_t tdc_board_transport_read(uint8_t *buf, uint32_t cap, uint32_t *got)
{
    const int32_t n = tdc_semihost_read(g_stream, buf, cap);
    if (n < 0) {
        *got = 0;
        return TDC_BOARD_ERR_IO;
    }
    *got = (uint32_t)n;
    return n == 0 ? TDC_BOARD_END : TDC_BOARD_OK;
}

tdc_board_status_t tdc_board_panel_show(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height,
                                        uint32_t frame_index)
{
    const uint64_t h = tdc_board_frame_checksum(fb, stride, width, height);
    char line[48]; /* "frame " + 10 digits + ' ' + 16 hex + '\n' */
    char *o = tdc_text_u32(tdc_text_str(line, NULL, "frame "), NULL, frame_index);
    *o++ = ' ';
    o = tdc_text_hex(o, NULL, h, 16u);
    *o++ = '\n';
    tdc_semihost_write(1, line, (size_t)(o - line));
    return TDC_BOARD_OK;
}

void tdc_board_vsync_wait(void)
{
}

uint32_t tdc_board_cycles(void)
{
    return 0u; /* QEMU's instruction count is not the M7's: no stage timing */
}

uint32_t tdc_board_time_us(void)
{
    /* SysTick counts down from 2^24 - 1. */
    const uint32_t now = SYST_CVR;
    const uint32_t elapsed = (g_last_tick - now) & 0x00FFFFFFu;
    g_last_tick = now;
    const uint32_t lo = g_cycles_lo + elapsed;
    g_cycles_hi += lo < g_cycles_lo;
    g_cycles_lo = lo;
    const uint64_t cycles = ((uint64_t)g_cycles_hi << 32) | g_cycles_lo;
    return (uint32_t)(cycles / (TDC_BOARD_CPU_HZ / 1000000u));
}

tdc_reset_cause_t tdc_board_reset_cause(void)
{
    return TDC_RESET_POWER_ON;
}

void tdc_board_log(const char *msg)
{
    tdc_semihost_puts(2, "[" TDC_BOARD_NAME "] ");
    tdc_semihost_puts(2, msg);
    tdc_semihost_puts(2, "\n");
}
