# ST STM32H747I-DISCO: STM32H747XI (Cortex-M7 at 480 MHz + Cortex-M4), 32 MiB SDRAM, MIPI-DSI, USB HS.
BOARD_DESC  := ST STM32H747I-DISCO (Cortex-M7 core, 480 MHz; 1 MiB SRAM, 32 MiB SDRAM, MIPI-DSI, USB HS)
BOARD_CPU   := -mcpu=cortex-m7 -mthumb -mfloat-abi=soft
BOARD_LDS   := boards/stm32h747i-disco/stm32h747i-disco.ld
# name:origin:length:attributes (RM0399 memory map; SDRAM on FMC bank 2 as wired on the DISCO)
BOARD_MEM   := FLASH:0x08000000:1M:rx DTCM:0x20000000:128K:rw AXISRAM:0x24000000:512K:rwx SDRAM:0xD0000000:32M:rw
BOARD_SRCS  := boards/stm32h747i-disco/startup.c boards/stm32h747i-disco/sdram.c firmware/board/tdc_board_stm32h7.c
# Default stages (see docs/boards.md: TRM and assembly of a 1080x1200-per-eye panel need more than 32 MiB)
BOARD_STAGES := lcd
BOARD_FLASH := dfu: hosttools USB DFU path (tdc-usb flash), or dfu-util -a 0 -s 0x08000000:leave -D IMAGE.bin (BOOT0 high), or STM32CubeProgrammer over ST-LINK
