/*
 * startup.c - STM32H747I-DISCO, Cortex-M7 core: vector table, then supply
 * and clocks (clocks.c), the log UART (log_uart.c), the FMC SDRAM
 * (sdram.c), the MPU region and caches (clocks.c), and only then crt0,
 * which zeroes the buffers placed in the SDRAM, and main().
 *
 * Executed in tests/disco on an emulated Cortex-M7 against register models
 * of RM0399's peripherals; not yet run on a board.
 */
#include <stdint.h>

#include "board.h"
#include "disco.h"
#include "sdram.h"
#include "tdc_crt0.h"
#include "tdc_vectors.h"

#define STM32H747_IRQS 150
/* faults: the fault registers to the log, then a reset (disco.h); the
 * OTG_HS global interrupt (RM0399 vector table, position 77) serves USB
 * (usb_hs.c). */
TDC_VECTORS_FAULT_IRQ(STM32H747_IRQS, tdc_disco_fault_entry, TDC_STM32_OTG_HS_IRQN, tdc_disco_usb_irq);

#define FLASH_OPTSR_CUR TDC_REG32(TDC_STM32_FLASH_R + 0x1Cu)

/* The Cortex-M4: this image gives it no code.  With the option bit BCM4
 * clear (docs/boards.md: how to clear it) the M4 stays gated until
 * RCC_GCR.BOOT_C2 is set, which nothing here does; with BCM4 set it boots
 * from BOOT_CM4_ADD0 (bank 2, not programmed by this image), so say so. */
static void m4_check(void)
{
    if (FLASH_OPTSR_CUR & (1u << 22)) { /* FLASH_OPTSR_CUR.BCM4 */
        tdc_disco_log("stm32h747i-disco: option bit BCM4 is set: the Cortex-M4 boots from bank 2 (clear BCM4)");
    }
}

void Reset_Handler(void)
{
    const int clocks_ok = tdc_disco_clocks_init();
    tdc_disco_log_init();
    if (!clocks_ok) {
        tdc_disco_log("stm32h747i-disco: a supply or clock ready bit never came: running on HSI 64 MHz");
    }
    m4_check();
    tdc_stm32_sdram_init();
    tdc_disco_caches_on();
    (void)tdc_crt0_start();
    /* main() returns only when the transport fails (USB did not come up);
     * keep the last image on the panel and sleep. */
    for (;;) {
        __asm__ volatile("wfi");
    }
}

/* Unexpected interrupt (crt0's default handler): logged like a fault. */
_Noreturn void tdc_board_fault(uint32_t exception)
{
    tdc_disco_fault_report(0, exception);
}
