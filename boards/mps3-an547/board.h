/* board.h - ARM MPS3 AN547 (Cortex-M55), as emulated by qemu-system-arm. */
#ifndef TDC_BOARD_MPS3_AN547_H
#define TDC_BOARD_MPS3_AN547_H

#define TDC_BOARD_NAME "mps3-an547"
#define TDC_BOARD_EMULATED 1
#define TDC_BOARD_CPU_HZ 32000000u /* AN547 FPGA clock: SysTick counts this */
#define TDC_BOARD_SYSTICK_BASE 0xE000E010u

/* CMSDK APB UART0, Secure alias (not used for output: semihosting is). */
#define TDC_BOARD_UART0_BASE 0x59303000u

#endif
