# ARM MPS2+ FPGA board with the AN500 image: Cortex-M7, run by qemu-system-arm.
BOARD_DESC  := ARM MPS2+ AN500 (Cortex-M7, 25 MHz FPGA), emulated by qemu-system-arm -M mps2-an500
BOARD_CPU   := -mcpu=cortex-m7 -mthumb -mfloat-abi=soft
BOARD_LDS   := boards/mps2-an500/mps2-an500.ld
# name:origin:length:attributes (QEMU hw/arm/mps2.c; above 4 MiB SRAM is a mirror)
BOARD_MEM   := CODE:0x00000000:4M:rx SRAM:0x20000000:4M:rwx PSRAM:0x60000000:16M:rw
BOARD_QEMU  := -M mps2-an500
