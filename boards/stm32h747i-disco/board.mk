# ST STM32H747I-DISCO: STM32H747XI (Cortex-M7 at 400 MHz on its SMPS supply + Cortex-M4, held), 32 MiB SDRAM, MIPI-DSI, USB HS.
BOARD_DESC  := ST STM32H747I-DISCO (Cortex-M7 core, 400 MHz; 1 MiB SRAM, 32 MiB SDRAM, MIPI-DSI, USB HS)
BOARD_CPU   := -mcpu=cortex-m7 -mthumb -mfloat-abi=soft
BOARD_LDS   := boards/stm32h747i-disco/stm32h747i-disco.ld
# name:origin:length:attributes (RM0399 memory map; SDRAM on FMC bank 2 as wired on the DISCO)
BOARD_MEM   := FLASH:0x08000000:1M:rx DTCM:0x20000000:128K:rw AXISRAM:0x24000000:512K:rwx SDRAM:0xD0000000:32M:rw
BOARD_SRCS  := $(addprefix boards/stm32h747i-disco/,startup.c clocks.c sdram.c log_uart.c ltdc.c dsi_panel.c panel_tables.c flash.c usb_hs.c) firmware/board/tdc_board_stm32h7.c
# Default stages (docs/boards.md, memory fit): TRM (rho recomputed, 4.5 B/px)
# and the LCD inverse fit the 32 MiB SDRAM for htc-vive, rift-cv1 and
# lcd-240; tile assembly (23 B/px) only for the board's own 800x480 panel,
# which runs at 60 Hz, so TRM is compiled in there but refused at run time.
BOARD_STAGES := trm lcd
BOARD_STAGES_disco-dsi := trm assemble lcd fovtaa
# 2560x1440: not even the LCD inverse fits (frame buffer + staging 22 MB +
# 6-bit history 16.6 MB): link decode and panel out only.
BOARD_STAGES_pg279q :=
# LCD history at 6 bits per sample (4.5 B/px instead of 6: lcd-240's "trm
# lcd" fits with it), and no RGB30 link format (staging 3 B/px, not 4).
BOARD_FW_CFG := -DTDC_CFG_LCD_PREV_BITS=6u -DTDC_LINK_FORMAT_MASK=0x16u
# Rows in flight (docs/boards.md): pictures as row bands of 16 rows, one band
# staged (92 KB for lcd-240 instead of 6.2 MB), so a front/back frame buffer
# pair fits every default pair: the panel never scans out a buffer being
# written, and a frame with a bad band is never swapped in.
BOARD_BANDS := 1
BOARD_FLASH := make flash (openocd through the on-board ST-LINK), make flash-uart (stm32flash, ROM bootloader on USART1, BOOT0 high); tdc-usb flash for updates through the running image's USB HS port
