/*
 * tdc_crt0.h - C runtime start for the Cortex-M boards: copies .data from
 * its load address, zeroes .bss and the external-RAM buffers (.tdc_ext),
 * then calls main().  Each board's startup.c owns the vector table and
 * calls tdc_crt0_start() from its Reset_Handler after clock setup.
 *
 * Linker-script symbols every board script defines (word aligned):
 *   __data_load, __data_start, __data_end   initialised data (LMA, VMA)
 *   __bss_start, __bss_end                  zero-initialised data
 *   __ext_start, __ext_end                  large buffers in external RAM
 *   __stack_top                             initial main stack pointer
 */
#ifndef TDC_CRT0_H
#define TDC_CRT0_H

#include <stdint.h>

/* Place a large static buffer (frame buffers, TRM arena) in the board's
 * external RAM region (PSRAM / SDRAM / DDR).  NOLOAD: zeroed by crt0,
 * costs nothing in the image. */
#define TDC_EXTRAM __attribute__((section(".tdc_ext"), aligned(32)))

/* Prepares memory and runs main(); returns main()'s status. */
int tdc_crt0_start(void);

/* Default handler for unused vectors: calls tdc_board_fault(). */
void tdc_crt0_default_handler(void);

/* Board hook, called on a fault or unexpected interrupt with the IPSR
 * exception number.  Emulated boards report and exit; real boards reset. */
_Noreturn void tdc_board_fault(uint32_t exception);

#endif
