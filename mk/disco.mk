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
