/* board.h - ST STM32H747I-DISCO, Cortex-M7 core (RM0399, UM2411). */
#ifndef TDC_BOARD_STM32H747I_DISCO_H
#define TDC_BOARD_STM32H747I_DISCO_H

#define TDC_BOARD_NAME "stm32h747i-disco"
#define TDC_BOARD_EMULATED 0
#define TDC_BOARD_HSE_HZ 25000000u /* UM2411: X1, 25 MHz crystal on the HSE pins */

/* PLL1 (RM0399 RCC chapter, "PLL"): ref = HSE / M = 5 MHz (PLL1RGE 4-8 MHz),
 * VCO = ref * N = 800 MHz (wide range 192-960 MHz), SYSCLK = VCO / P.
 * 400 MHz is the maximum at VOS1, and VOS1 is the highest scale on the
 * DISCO's direct-SMPS supply (480 MHz needs VOS0, which needs the LDO:
 * DS12930 operating conditions).  The timer below follows from these. */
#define TDC_DISCO_PLL1_M 5u
#define TDC_DISCO_PLL1_N 160u
#define TDC_DISCO_PLL1_P 2u
#define TDC_DISCO_PLL1_Q 4u /* 200 MHz */
#define TDC_DISCO_PLL1_R 2u /* 400 MHz */
#define TDC_BOARD_CPU_HZ (TDC_BOARD_HSE_HZ / TDC_DISCO_PLL1_M * TDC_DISCO_PLL1_N / TDC_DISCO_PLL1_P)
/* AXI/AHB = CPU / 2 = 200 MHz (HPRE), every APB = AHB / 2 = 100 MHz. */
#define TDC_DISCO_HCLK_HZ (TDC_BOARD_CPU_HZ / 2u)
#define TDC_DISCO_PCLK_HZ (TDC_DISCO_HCLK_HZ / 2u)

/* The DISCO's own panel (MB1166, OTM8009A controller, landscape): the size
 * and rate of boards/panels/disco-dsi.panel, the porches of the OTM8009A
 * data sheet's video-mode timing (also NT35510-compatible).  The LTDC
 * always drives this panel, whatever PANEL the image was built for. */
#define TDC_DISCO_LCD_W 800u
#define TDC_DISCO_LCD_H 480u
#define TDC_DISCO_LCD_HZ 60u
#define TDC_DISCO_LCD_HSYNC 2u
#define TDC_DISCO_LCD_HBP 34u
#define TDC_DISCO_LCD_HFP 34u
#define TDC_DISCO_LCD_VSYNC 1u
#define TDC_DISCO_LCD_VBP 15u
#define TDC_DISCO_LCD_VFP 16u
/* Pixel clock = LTDC kernel clock = PLL3R (RM0399 RCC: ltdc_ker_ck):
 * (2+34+800+34) x (1+15+480+16) x 60 Hz = 26.73 MHz wanted; HSE / 5 = 5 MHz
 * (PLL3RGE 4-8 MHz) x 107 = 535 MHz VCO (wide) / 20 = 26.75 MHz, 60.05 Hz. */
#define TDC_DISCO_PLL3_M 5u
#define TDC_DISCO_PLL3_N 107u
#define TDC_DISCO_PLL3_R 20u
/* DSI host PLL (RM0399 DSI wrapper, DSI_WRPCR), reference = HSE:
 * lane rate = HSE x NDIV / (IDF x ODF) = 25 MHz x 100 / 5 = 500 Mbit/s per
 * lane (the D-PHY maximum), VCO = 2 x that = 1000 MHz (500-1000 MHz);
 * 2 lanes carry 1000 Mbit/s against 26.75 MHz x 24 bit = 642 Mbit/s of
 * pixels.  Lane byte clock = 500 / 8 = 62.5 MHz. */
#define TDC_DISCO_DSI_NDIV 100u
#define TDC_DISCO_DSI_IDF 5u
#define TDC_DISCO_DSI_ODF 1u
#define TDC_DISCO_DSI_LANE_HZ (TDC_BOARD_HSE_HZ / TDC_DISCO_DSI_IDF * TDC_DISCO_DSI_NDIV / TDC_DISCO_DSI_ODF)
/* Flash polls (flash.c): a 128 KiB sector erase takes up to seconds
 * (DS12930 flash characteristics), a 256-bit word program microseconds. */
#define TDC_DISCO_FLASH_BANK_BYTES (1024u * 1024u) /* one DFU slot per bank */
#define TDC_DISCO_FLASH_ERASE_MS 4000u
#define TDC_DISCO_FLASH_PROGRAM_MS 10u
/* USB HS bulk OUT ring (usb_hs.c): 32 packets of 512 bytes. */
#define TDC_DISCO_USB_RING_BYTES 16384u
#define TDC_DISCO_LCD_PCLK_HZ (TDC_BOARD_HSE_HZ / TDC_DISCO_PLL3_M * TDC_DISCO_PLL3_N / TDC_DISCO_PLL3_R)

/* Peripheral base addresses (RM0399 memory map). */
#define TDC_STM32_RCC 0x58024400u
#define TDC_STM32_PWR 0x58024800u
#define TDC_STM32_FLASH_R 0x52002000u
#define TDC_STM32_FMC 0x52004000u
#define TDC_STM32_LTDC 0x50001000u
#define TDC_STM32_DSI 0x50000000u
#define TDC_STM32_USB_OTG_HS 0x40040000u
#define TDC_STM32_USART1 0x40011000u
#define TDC_STM32_SYSCFG 0x58000400u
#define TDC_STM32_GPIO(port) (0x58020000u + 0x400u * (uint32_t)(port)) /* port 0 = A .. 10 = K */
#define TDC_STM32_SDRAM_BASE 0xD0000000u
#define TDC_STM32_SDRAM_BYTES (32u * 1024u * 1024u)

/* Core debug: DWT cycle counter (present on the M7, not emulated by QEMU). */
#define TDC_CM_DEMCR 0xE000EDFCu
#define TDC_CM_DWT_CTRL 0xE0001000u
#define TDC_CM_DWT_CYCCNT 0xE0001004u
#define TDC_CM_DWT_LAR 0xE0001FB0u
#define TDC_CM_SCB_AIRCR 0xE000ED0Cu
/* NVIC (ARMv7-M ARM B3.4): set-enable, clear-enable, priority bytes. */
#define TDC_CM_NVIC_ISER(n) (0xE000E100u + 4u * (n))
#define TDC_CM_NVIC_ICER(n) (0xE000E180u + 4u * (n))
#define TDC_CM_NVIC_IPR(n) (0xE000E400u + 4u * (n))
/* RM0399 vector table: OTG_HS global interrupt. */
#define TDC_STM32_OTG_HS_IRQN 77u

#define TDC_REG32(addr) (*(volatile uint32_t *)(uintptr_t)(addr))

#endif
