# ARM MPS2+ FPGA board with the AN500 image: Cortex-M7, run by qemu-system-arm.
BOARD_DESC  := ARM MPS2+ AN500 (Cortex-M7, 25 MHz FPGA), emulated by qemu-system-arm -M mps2-an500
BOARD_CPU   := -mcpu=cortex-m7 -mthumb -mfloat-abi=soft
BOARD_LDS   := boards/mps2-an500/mps2-an500.ld
# name:origin:length:attributes (QEMU hw/arm/mps2.c; above 4 MiB SRAM is a mirror)
BOARD_MEM   := CODE:0x00000000:4M:rx SRAM:0x20000000:4M:rwx PSRAM:0x60000000:16M:rw
BOARD_QEMU  := -M mps2-an500
BOARD_FLASH := none: QEMU loads the ELF (qemu-system-arm -M mps2-an500 -kernel IMAGE)
BOARD_STARTUP := firmware/board/tdc_startup_qemu.c
BOARD_SRCS  := $(BOARD_STARTUP) firmware/board/tdc_board_emulated.c firmware/board/tdc_semihost.c
