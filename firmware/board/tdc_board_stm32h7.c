/*
 * tdc_board_stm32h7.c - the board interface on the STM32H747I-DISCO
 * (Cortex-M7 core).  What is real and what is a stub:
 *
 *   timer        REAL  DWT cycle counter at TDC_BOARD_CPU_HZ
 *   reset cause  REAL  RCC_RSR flags (cleared after reading)
 *   panel out    REAL  LTDC layer 1 frame-buffer address + shadow reload on
 *                      vertical blanking (RM0399 section 35) ...
 *                STUB  ... the LTDC timing, DSI host/PHY and OTM8009A panel
 *                      initialisation are not written: tdc_board_init()
 *                      reports TDC_BOARD_ERR_NOT_IMPLEMENTED for them in the
 *                      log and the LTDC is left disabled
 *   vsync        REAL  polls LTDC_CDSR.VSYNCS (returns at once while the
 *                      LTDC is disabled)
 *   transport    STUB  USB OTG HS bulk OUT endpoint (ULPI PHY) not written:
 *                      reads return nothing; hosttools' USB path targets it
 *   log          STUB  dropped (no UART on the DISCO's ST-LINK VCP yet)
 *
 * Nothing here has run on hardware: it builds, links and is checked in CI.
 */
#include "board.h"
#include "tdc_board.h"

#define RCC_RSR TDC_REG32(TDC_STM32_RCC + 0xD0u)
#define LTDC(off) TDC_REG32(TDC_STM32_LTDC + (off))
#define LTDC_SRCR 0x24u
#define LTDC_GCR 0x18u
#define LTDC_CDSR 0x48u
#define LTDC_L1CFBAR 0xACu
#define LTDC_L1CFBLR 0xB0u

static uint32_t g_last_cycles, g_us, g_frac;

tdc_board_status_t tdc_board_init(void)
{
    /* DWT cycle counter: trace enable, unlock (M7), start. */
    TDC_REG32(TDC_CM_DEMCR) |= 1u << 24;
    TDC_REG32(TDC_CM_DWT_LAR) = 0xC5ACCE55u;
    TDC_REG32(TDC_CM_DWT_CYCCNT) = 0u;
    TDC_REG32(TDC_CM_DWT_CTRL) |= 1u;
    g_last_cycles = 0u;
    /* STUB: LTDC clocks/timings, DSI host + D-PHY PLL and the OTM8009A
     * command sequence; USB OTG HS core + ULPI PHY and the bulk endpoint. */
    tdc_board_log("stm32h747i-disco: DSI panel and USB HS transport are stubs (not implemented)");
    return TDC_BOARD_OK;
}

tdc_board_status_t tdc_board_transport_read(uint8_t *buf, uint32_t cap, uint32_t *got)
{
    (void)buf;
    (void)cap;
    *got = 0u; /* STUB: USB HS bulk OUT endpoint */
    return TDC_BOARD_ERR_NOT_IMPLEMENTED;
}

tdc_board_status_t tdc_board_panel_show(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height,
                                        uint32_t frame_index)
{
    (void)height;
    (void)frame_index;
    /* Layer 1 scans out fb from the next vertical blanking: address,
     * pitch / line length (bytes, +7 per RM0399), then reload on VBR. */
    LTDC(LTDC_L1CFBAR) = (uint32_t)(uintptr_t)fb;
    LTDC(LTDC_L1CFBLR) = (stride << 16) | (width * 3u + 7u);
    LTDC(LTDC_SRCR) = 1u << 1; /* VBR: reload shadow registers at vertical blanking */
    return (LTDC(LTDC_GCR) & 1u) ? TDC_BOARD_OK : TDC_BOARD_ERR_NOT_IMPLEMENTED;
}

void tdc_board_vsync_wait(void)
{
    if (!(LTDC(LTDC_GCR) & 1u)) {
        return; /* LTDC not running (panel set-up is a stub) */
    }
    while (LTDC(LTDC_CDSR) & (1u << 2)) { /* leave the current VSYNC */
    }
    while (!(LTDC(LTDC_CDSR) & (1u << 2))) { /* wait for the next */
    }
}

uint32_t tdc_board_time_us(void)
{
    const uint32_t now = TDC_REG32(TDC_CM_DWT_CYCCNT);
    const uint32_t cycles = now - g_last_cycles; /* modulo 2^32: call at least every 8.9 s */
    g_last_cycles = now;
    const uint32_t per_us = TDC_BOARD_CPU_HZ / 1000000u;
    g_frac += cycles % per_us;
    g_us += cycles / per_us + g_frac / per_us;
    g_frac %= per_us;
    return g_us;
}

tdc_reset_cause_t tdc_board_reset_cause(void)
{
    const uint32_t rsr = RCC_RSR;
    RCC_RSR = rsr | (1u << 16); /* RMVF: clear the flags for the next reset */
    if (rsr & (1u << 21)) {
        return TDC_RESET_BROWNOUT;
    }
    if (rsr & (3u << 26) || rsr & (3u << 28)) {
        return TDC_RESET_WATCHDOG; /* IWDG1/2, WWDG1/2 */
    }
    if (rsr & (3u << 24)) {
        return TDC_RESET_SOFTWARE; /* SFT1RSTF / SFT2RSTF */
    }
    if (rsr & (3u << 30)) {
        return TDC_RESET_LOW_POWER;
    }
    if (rsr & (1u << 23)) {
        return TDC_RESET_POWER_ON;
    }
    if (rsr & (1u << 22)) {
        return TDC_RESET_PIN;
    }
    return TDC_RESET_UNKNOWN;
}

void tdc_board_log(const char *msg)
{
    (void)msg; /* STUB: no log channel yet */
}
