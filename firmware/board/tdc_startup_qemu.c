/*
 * tdc_startup_qemu.c - vector table and reset handler of the boards QEMU
 * runs (BOARD_STARTUP in their board.mk):
 *   mps2-an500 (Cortex-M7): QEMU resets the core with VTOR = 0, so initial
 *     SP and PC come from the table at the start of ZBT SSRAM1 (region CODE);
 *   mps3-an547 (Cortex-M55): QEMU resets with the Secure VTOR at the ITCM,
 *     so they come from the table at its start (region ITCM).
 * The linker script of each board places .vectors there.
 */
#include <stdint.h>

#include "board.h"
#include "tdc_crt0.h"
#include "tdc_semihost.h"
#include "tdc_vectors.h"

TDC_VECTORS(32);

void Reset_Handler(void)
{
#if defined(TDC_TRM_MVE)
    /* Helium (MVE) kernels: enable CP10/CP11 (CPACR, full access) before
     * the first vector instruction; otherwise it faults (NOCP). */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm volatile("dsb\n\tisb" ::: "memory");
#endif
    int status = tdc_crt0_start();
    tdc_semihost_exit((uint32_t)status);
}

_Noreturn void tdc_board_fault(uint32_t exception)
{
    static const char *const names[16] = {"thread",       "reset", "NMI",    "HardFault", "MemManage", "BusFault",
                                          "UsageFault",   "?",     "?",      "?",         "?",         "SVCall",
                                          "DebugMonitor", "?",     "PendSV", "SysTick"};
    tdc_semihost_puts(2, "[" TDC_BOARD_NAME "] fault: ");
    tdc_semihost_puts(2, exception < 16u ? names[exception] : "external interrupt");
    tdc_semihost_puts(2, "\n");
    tdc_semihost_exit(128u + (exception & 0x7fu));
}
