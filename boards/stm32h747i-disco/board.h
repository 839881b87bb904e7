/* board.h - ST STM32H747I-DISCO, Cortex-M7 core (RM0399, UM2411). */
#ifndef TDC_BOARD_STM32H747I_DISCO_H
#define TDC_BOARD_STM32H747I_DISCO_H

#define TDC_BOARD_NAME "stm32h747i-disco"
#define TDC_BOARD_EMULATED 0
#define TDC_BOARD_CPU_HZ 480000000u /* after clock set-up: HSE 25 MHz, PLL1 M=5 N=192 P=2 */
#define TDC_BOARD_HSE_HZ 25000000u

/* Peripheral base addresses (RM0399 section 2.3.2). */
#define TDC_STM32_RCC 0x58024400u
#define TDC_STM32_PWR 0x58024800u
#define TDC_STM32_FLASH_R 0x52002000u
#define TDC_STM32_FMC 0x52004000u
#define TDC_STM32_LTDC 0x50001000u
#define TDC_STM32_DSI 0x50000000u
#define TDC_STM32_USB_OTG_HS 0x40040000u
#define TDC_STM32_GPIO(port) (0x58020000u + 0x400u * (uint32_t)(port)) /* port 0 = A .. 10 = K */
#define TDC_STM32_SDRAM_BASE 0xD0000000u
#define TDC_STM32_SDRAM_BYTES (32u * 1024u * 1024u)

/* Core debug: DWT cycle counter (present on the M7, not emulated by QEMU). */
#define TDC_CM_DEMCR 0xE000EDFCu
#define TDC_CM_DWT_CTRL 0xE0001000u
#define TDC_CM_DWT_CYCCNT 0xE0001004u
#define TDC_CM_DWT_LAR 0xE0001FB0u
#define TDC_CM_SCB_AIRCR 0xE000ED0Cu

#define TDC_REG32(addr) (*(volatile uint32_t *)(uintptr_t)(addr))

#endif
