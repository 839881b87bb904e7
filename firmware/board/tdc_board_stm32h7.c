/*
 * tdc_board_stm32h7.c - the board interface on the STM32H747I-DISCO
 * (Cortex-M7 core).  The drivers live in boards/stm32h747i-disco/ (clocks,
 * SDRAM, caches, log UART and fault handler, LTDC, DSI and panel, flash,
 * USB HS); this file maps the narrow board interface (tdc_board.h) onto
 * them:
 *
 *   timer        DWT cycle counter at TDC_BOARD_CPU_HZ (board.h, from PLL1)
 *   reset cause  RCC_RSR, power-on tested first (a power-on reset also sets
 *                the brown-out and pin flags), then cleared
 *   log          USART1 to the ST-LINK virtual COM port (log_uart.c)
 *   panel out    LTDC (ltdc.c): pixel clock, timings, RGB888 layer 1 at
 *                the frame buffer, reloaded at vertical blanking after the
 *                buffer is cleaned from the D-cache
 *                (dsi_panel.c: DSI host and D-PHY, panel ID, the
 *                controller's register table (panel_tables.c), DCS start-up)
 *   vsync        LTDC_CDSR.VSYNCS, servicing USB while it waits
 *   transport    USB OTG HS bulk OUT through a ring (usb_hs.c), filled by
 *                the OTG_HS interrupt
 *
 * Executed in tests/disco against register models; not yet run on a board.
 */
#include "board.h"
#include "disco.h"
#include "tdc_board.h"

#define RCC_RSR TDC_REG32(TDC_STM32_RCC + 0xD0u)

static uint32_t g_last_cycles, g_us, g_frac;

tdc_board_status_t tdc_board_init(void)
{
    /* DWT cycle counter: trace enable, unlock (M7), start. */
    TDC_REG32(TDC_CM_DEMCR) |= 1u << 24;
    TDC_REG32(TDC_CM_DWT_LAR) = 0xC5ACCE55u;
    TDC_REG32(TDC_CM_DWT_CYCCNT) = 0u;
    TDC_REG32(TDC_CM_DWT_CTRL) |= 1u;
    g_last_cycles = 0u;
    tdc_disco_log_init(); /* again: crt0 zeroed its state after startup.c's early log */
    /* DSI host first, then the LTDC, then the link and the panel (the host
     * starts after the LTDC so it locks to running video timing). */
    if (tdc_disco_dsi_init() && tdc_disco_ltdc_init()) {
        (void)tdc_disco_panel_on();
    } else {
        tdc_board_log("stm32h747i-disco: DSI or LTDC clock did not come up: no panel");
    }
    /* USB HS: serial number = the 96-bit unique device ID (RM0399 "Unique
     * device ID register", 0x1FF1E800) in hex. */
    static char serial[25];
    for (uint32_t i = 0; i < 24u; i++) {
        const uint32_t w = TDC_REG32(0x1FF1E800u + 4u * (i / 8u));
        serial[i] = "0123456789abcdef"[(w >> (28u - 4u * (i % 8u))) & 0xFu];
    }
    const tdc_usbp_config_t usb = {.board_name = TDC_BOARD_NAME,
                                   .panel_name = TDC_PANEL_NAME,
                                   .serial = serial,
                                   .fw_version = 0u,
                                   /* the panel the image decodes streams for */
                                   .panel_width = TDC_PANEL_WIDTH * TDC_PANEL_EYES,
                                   .panel_height = TDC_PANEL_HEIGHT,
                                   .refresh_mhz = TDC_PANEL_REFRESH_HZ * 1000u,
                                   .rx_buffer_bytes = TDC_DISCO_USB_RING_BYTES,
                                   .max_packet_bytes = 512u,
                                   .flash = {tdc_disco_flash_write, tdc_disco_flash_read, 0, TDC_DISCO_FLASH_BANK_BYTES,
                                             tdc_disco_flash_busy_ms}};
    if (!tdc_disco_usb_init(&usb)) {
        tdc_board_log("stm32h747i-disco: USB OTG HS core did not come out of reset");
        return TDC_BOARD_ERR_IO;
    }
    return TDC_BOARD_OK;
}

tdc_board_status_t tdc_board_transport_read(uint8_t *buf, uint32_t cap, uint32_t *got)
{
    *got = tdc_disco_usb_read(buf, cap); /* bulk OUT 0x01 through the ring (usb_hs.c) */
    return TDC_BOARD_OK;
}

tdc_board_status_t tdc_board_panel_show(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height,
                                        uint32_t frame_index)
{
    (void)frame_index;
    return tdc_disco_ltdc_flip(fb, stride, width, height) ? TDC_BOARD_OK : TDC_BOARD_ERR_IO;
}

/* Leaves the current vertical sync, waits for the next, and services USB
 * meanwhile (the wait is the frame loop's idle time; bounded: one frame
 * is 16.7 ms, far fewer polls than the limit). */
void tdc_board_vsync_wait(void)
{
    uint32_t i = 0;
    while (tdc_disco_ltdc_vsync() == 1 && i++ < 10000000u) {
        tdc_disco_usb_poll();
    }
    while (tdc_disco_ltdc_vsync() == 0 && i++ < 20000000u) {
        tdc_disco_usb_poll();
    }
}

/* DWT_CYCCNT (ARMv7-M ARM C1.8: enabled by DEMCR.TRCENA and
 * DWT_CTRL.CYCCNTENA in tdc_board_init), one count per core clock. */
uint32_t tdc_board_cycles(void)
{
    return TDC_REG32(TDC_CM_DWT_CYCCNT);
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
    /* RM0399 RCC "reset source identification": a power-on reset sets
     * PORRSTF and also BORRSTF and PINRSTF; a brown-out sets BORRSTF and
     * PINRSTF; every reset drives NRST, so PINRSTF alone means the pin. */
    if (rsr & (1u << 23)) {
        return TDC_RESET_POWER_ON;
    }
    if (rsr & (1u << 21)) {
        return TDC_RESET_BROWNOUT;
    }
    if (rsr & (3u << 26) || rsr & (3u << 28)) {
        return TDC_RESET_WATCHDOG; /* IWDG1/2, WWDG1/2 */
    }
    if (rsr & (3u << 24)) {
        return TDC_RESET_SOFTWARE; /* SFT1RSTF / SFT2RSTF (also the fault handler's reset) */
    }
    if (rsr & (3u << 30)) {
        return TDC_RESET_LOW_POWER;
    }
    if (rsr & (1u << 22)) {
        return TDC_RESET_PIN;
    }
    return TDC_RESET_UNKNOWN;
}

void tdc_board_log(const char *msg)
{
    tdc_disco_log(msg);
}
