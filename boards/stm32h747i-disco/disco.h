/* disco.h - the STM32H747I-DISCO's drivers, called by startup.c and the
 * board interface (firmware/board/tdc_board_stm32h7.c). */
#ifndef TDC_DISCO_H
#define TDC_DISCO_H

#include <stdint.h>

/* clocks.c: supply, VOS1, 400 MHz; 1 when every ready bit came. */
int tdc_disco_clocks_init(void);
/* clocks.c: MPU region for the SDRAM, I- and D-cache invalidated and on. */
void tdc_disco_caches_on(void);
/* clocks.c: clean [p, p + bytes) from the D-cache to memory (DCCMVAC). */
void tdc_disco_dcache_clean(const void *p, uint32_t bytes);

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
