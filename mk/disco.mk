# The STM32H747I-DISCO's board code executed (tests/disco): the linked
# firmware ELF runs on an emulated Cortex-M7 (python3-unicorn) against
# register models of RM0399's peripherals.  About 15 s.
#   make test-disco
DEPS_PKGS += python3-unicorn
TEST_EXTRA += test-disco

DISCO_ELF := $(BUILD)/stm32h747i-disco-disco-dsi/tdc-firmware.elf
.PHONY: test-disco
test-disco:
	@$(MAKE) --no-print-directory -j2 BOARD=stm32h747i-disco PANEL=disco-dsi firmware >/dev/null
	@mkdir -p $(BUILD)
	@printf '#!/bin/sh\nexec /usr/bin/python3 tests/disco/test_disco.py %s\n' "$(DISCO_ELF)" > $(BUILD)/test-disco
	@chmod +x $(BUILD)/test-disco
	@tests/run_tests.sh disco $(BUILD)/test-disco

# Flashing (docs/boards.md "STM32H747I-DISCO"): through the on-board
# ST-LINK with openocd (its board/stm32h747i-disco.cfg), or, as the
# fall-back, ST's ROM bootloader on USART1 (PA9/PA10, reached through the
# ST-LINK's virtual COM port) with stm32flash, BOOT0 held high at reset.
DEPS_PKGS += openocd stm32flash
DISCO_TTY ?= /dev/ttyACM0
.PHONY: flash flash-uart
ifeq ($(BOARD),stm32h747i-disco)
flash: firmware
	openocd -f board/stm32h747i-disco.cfg -c "program $(BP)/tdc-firmware.elf verify reset exit"
flash-uart: firmware
	stm32flash -b 115200 -w $(BP)/tdc-firmware.bin -v -S 0x08000000 -g 0x08000000 $(DISCO_TTY)
else
flash flash-uart:
	@echo "make: flash: BOARD=$(BOARD) is not flashed: $(BOARD_FLASH)"; exit 2
endif


# Instructions of the DISCO's own board code per unit of work (USB HS
# interrupt and ring, transport_read, scan-out flip), counted on the
# emulated M7: docs/boards.md "DISCO real-time table".  About 15 s.
.PHONY: bench-disco
bench-disco:
	@$(MAKE) --no-print-directory -j2 BOARD=stm32h747i-disco PANEL=disco-dsi firmware >/dev/null
	@/usr/bin/python3 tests/disco/disco_cost.py $(DISCO_ELF)
