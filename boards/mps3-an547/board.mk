# ARM MPS3 FPGA board with the AN547 image: Cortex-M55 (Helium), run by qemu-system-arm.
BOARD_DESC  := ARM MPS3 AN547 (Cortex-M55, 32 MHz FPGA), emulated by qemu-system-arm -M mps3-an547
BOARD_CPU   := -mcpu=cortex-m55 -mthumb -mfloat-abi=soft
# Helium (MVE) kernels for TRM's rows (firmware/tdc_trm_mve.c), bit-exact with C
BOARD_MVE   := 1
BOARD_LDS   := boards/mps3-an547/mps3-an547.ld
# name:origin:length:attributes, Secure aliases (the core starts Secure; QEMU hw/arm/mps2-tz.c)
BOARD_MEM   := ITCM:0x10000000:512K:rx DTCM:0x30000000:512K:rwx DDR:0x70000000:256M:rw
BOARD_QEMU  := -M mps3-an547
