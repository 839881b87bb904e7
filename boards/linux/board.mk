# Linux board (Raspberry Pi 4/5 / Zero 2, Rockchip, i.MX, the test-vm VM):
# the frame loop as a user-space program, panel out through DRM/KMS, link
# stream in through a USB gadget (configfs + FunctionFS), GPIO via libgpiod.
BOARD_DESC  := Linux board: KMS panel out (libdrm), USB gadget transport (FunctionFS), GPIO (libgpiod)
BOARD_OS    := linux
BOARD_IMAGE := tdc-board
BOARD_SRCS  := firmware/board/tdc_board_linux.c firmware/board/tdc_board_linux_drm.c \
               firmware/board/tdc_board_linux_ffs.c firmware/board/tdc_board_linux_gpio.c firmware/board/tdc_ffs.c \
               firmware/board/tdc_board_linux_workers.c
BOARD_BANDS := 1
BOARD_FLASH := tdc-usb flash IMAGE (the protocol's DFU into A/B slot files), or make BOARD=linux install
# the arm64 cross build (CC=aarch64-linux-gnu-gcc) beside the host one
BOARD_BP_SUFFIX = $(if $(filter aarch64-%,$(CCNAME)),-arm64)
