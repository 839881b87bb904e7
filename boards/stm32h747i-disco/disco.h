/* disco.h - the STM32H747I-DISCO's drivers, called by startup.c and the
 * board interface (firmware/board/tdc_board_stm32h7.c). */
#ifndef TDC_DISCO_H
#define TDC_DISCO_H

#include <stdint.h>

#include "tdc_usbproto.h"

/* clocks.c: supply, VOS1, 400 MHz; 1 when every ready bit came. */
int tdc_disco_clocks_init(void);
/* clocks.c: MPU region for the SDRAM, I- and D-cache invalidated and on. */
void tdc_disco_caches_on(void);
/* clocks.c: clean [p, p + bytes) from the D-cache to memory (DCCMVAC). */
void tdc_disco_dcache_clean(const void *p, uint32_t bytes);

/* ltdc.c: PLL3 pixel clock, the panel timings, layer 1 RGB888 (off until
 * the first flip), LTDC on; 1 when PLL3 locked. */
int tdc_disco_ltdc_init(void);
/* ltdc.c: clean fb from the D-cache, scan it out from the next vertical
 * blanking; 0 when the LTDC is not up. */
int tdc_disco_ltdc_flip(const uint8_t *fb, uint32_t stride, uint32_t width, uint32_t height);
/* ltdc.c: 1 during vertical sync, 0 outside, -1 when the LTDC is not up. */
int tdc_disco_ltdc_vsync(void);

/* dsi_panel.c: DSI host, PLL, D-PHY, video-mode timings (before the
 * LTDC starts); 1 when the regulator and PLL came up. */
int tdc_disco_dsi_init(void);
/* dsi_panel.c: link on, panel reset released, controller identified, its
 * command table and the DCS start-up sent, backlight on (after the LTDC
 * runs). */
int tdc_disco_panel_on(void);

/* panel_tables.c: one panel register write: reg is a DCS command (0x00-0xFF)
 * or an OTM8009A command-2 address 0xHHLL (sent as the address shift
 * 00h = LL, then HH with the parameters); n parameters; wait_ms before the
 * next row. */
typedef struct {
    uint16_t reg;
    uint8_t n;
    uint8_t wait_ms;
    uint8_t p[16];
} tdc_disco_panel_cmd_t;
extern const tdc_disco_panel_cmd_t tdc_disco_otm8009a_table[];
extern const uint32_t tdc_disco_otm8009a_rows;
extern const tdc_disco_panel_cmd_t tdc_disco_nt35510_table[];
extern const uint32_t tdc_disco_nt35510_rows;
extern const tdc_disco_panel_cmd_t tdc_disco_dcs_startup[];
extern const uint32_t tdc_disco_dcs_startup_rows;

/* flash.c: the DFU target (tdc_usbp_flash_t): offsets 1-2 MiB are the
 * bank not running (0..1 MiB, the running one, is refused); 0 = done. */
int tdc_disco_flash_write(void *ctx, uint32_t offset, const uint8_t *data, uint32_t len);
int tdc_disco_flash_read(void *ctx, uint32_t offset, uint8_t *data, uint32_t len);
/* flash.c: the bwPollTimeout a write needs (tdc_usbp_flash_t.busy_ms):
 * the erase bound for each sector it starts, else 0. */
uint32_t tdc_disco_flash_busy_ms(void *ctx, uint32_t offset, uint32_t len);
/* flash.c: swap the banks by option byte and reset; returns 0 only when
 * the option bytes did not take the new value. */
int tdc_disco_flash_activate_other_bank(void);

/* usb_hs.c: OTG HS device on the ULPI PHY with the project's protocol;
 * 1 when the core came out of reset. */
int tdc_disco_usb_init(const tdc_usbp_config_t *cfg);
/* usb_hs.c: the OTG_HS interrupt (vector table): bus reset, enumeration,
 * control requests, bulk OUT packets into the ring. */
void tdc_disco_usb_irq(void);
/* usb_hs.c: the frame loop's share, with the USB interrupt masked: a DFU
 * block's erase and program, the next status report, bulk OUT re-armed
 * once the ring has room again. */
void tdc_disco_usb_poll(void);
/* usb_hs.c: up to cap link-stream bytes received on bulk OUT 0x01. */
uint32_t tdc_disco_usb_read(uint8_t *buf, uint32_t cap);

/* log_uart.c: USART1 on PA9/PA10 at 115200 8N1 (the ST-LINK VCP). */
void tdc_disco_log_init(void);
void tdc_disco_log(const char *msg);
/* log_uart.c: "text 0x%08x" lines without printf. */
void tdc_disco_log_hex(const char *label, uint32_t value);

/* log_uart.c: fault entry (vector table: HardFault, MemManage, BusFault,
 * UsageFault): logs the exception, stacked PC/LR/xPSR and the SCB fault
 * status registers, then resets. */
void tdc_disco_fault_entry(void);
_Noreturn void tdc_disco_fault_report(const uint32_t *frame, uint32_t exception);

#endif
