/* board.h - ARM MPS2+ AN500 (Cortex-M7), as emulated by qemu-system-arm. */
#ifndef TDC_BOARD_MPS2_AN500_H
#define TDC_BOARD_MPS2_AN500_H

#define TDC_BOARD_NAME "mps2-an500"
#define TDC_BOARD_EMULATED 1
#define TDC_BOARD_CPU_HZ 25000000u /* FPGA system clock: SysTick counts this */
#define TDC_BOARD_SYSTICK_BASE 0xE000E010u

/* CMSDK APB UART0 (not used for output: semihosting is). */
#define TDC_BOARD_UART0_BASE 0x40004000u

#endif
