# Boards (issue 8): Cortex-M firmware images, the golden vectors under QEMU,
# memory fit, the firmware rules on the linked target images, sizes and
# per-pixel cost on the target.  See docs/boards.md.
#
#   make BOARD=<b> PANEL=<p>        firmware image build/<b>-<p>/tdc-firmware.elf
#   make test-arm                   (part of make test) golden run in QEMU, image rules, fit test
#   make size                       arm-none-eabi-size of every board/panel pair
#   make bench-arm                  instructions per output pixel on Cortex-M7 / M55 (QEMU)
#
# A board folder holds board.mk (BOARD_CPU, BOARD_LDS, BOARD_MEM, BOARD_FLASH,
# BOARD_QEMU for emulated boards), board.h, startup.c and the linker script.

DEPS_PKGS += gcc-arm-none-eabi binutils-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
TEST_EXTRA += test-arm

ARM_CROSS := arm-none-eabi-
ARM_CC := $(ARM_CROSS)gcc
ARM_NM := $(ARM_CROSS)nm
ARM_SIZE := $(ARM_CROSS)size
ARM_OBJCOPY := $(ARM_CROSS)objcopy
ARM_OPT ?= -O2
QEMU_TIMEOUT ?= 120

ARM_BOARDS := $(filter-out host,$(BOARDS))
# Emulated boards: those whose board.mk names a QEMU machine.
QEMU_BOARDS := $(sort $(patsubst boards/%/board.mk,%,$(shell grep -l '^BOARD_QEMU' boards/*/board.mk)))

.PHONY: test-arm size bench-arm arm-golden arm-golden-check arm-image-check arm-fit-check

.SECONDEXPANSION:

ifneq ($(BOARD),host)
# ---------------------------------------------------------------------------
# Cross build for one board.  Panel-independent objects (firmware library,
# golden runner) in build/arm-<board>; the image of a pair in build/<board>-<panel>.
# Soft-float ABI on purpose: the firmware has no floating point, and with
# -mfloat-abi=soft any float that slipped in becomes an __aeabi_f*/d* call
# that the symbol check on the linked image catches (with a hard-float ABI
# it would be silent VFP instructions).
# ---------------------------------------------------------------------------
BA := $(BUILD)/arm-$(BOARD)
BP := $(BUILD)/$(BOARD)-$(PANEL)
PANEL_TYPE := $(shell awk '$$1 == "type" { print $$2 }' boards/panels/$(PANEL).panel)

ARM_CFLAGS := $(BOARD_CPU) $(ARM_OPT) -g -ffunction-sections -fdata-sections -fno-common \
              -Ifirmware -Ifirmware/board -Iboards/$(BOARD) -I$(GEN)
ARM_FW_CFLAGS := $(FW_WARN) $(ARM_CFLAGS)
# Test code (golden stages): same warnings as the host build of tests.
ARM_TEST_CFLAGS := -std=c11 -Wall -Wextra -Werror -Wvla $(ARM_CFLAGS) -Itests -Itests/golden
ARM_LDFLAGS := $(BOARD_CPU) -nostartfiles --specs=nano.specs -Wl,--gc-sections \
               -Wl,--no-warn-rwx-segments -Lfirmware/board -L$(BA) -T $(BOARD_LDS)
ARM_LIBS := -Wl,--start-group -lc -lgcc -Wl,--end-group

# The MEMORY block of the linker script, generated from BOARD_MEM so the
# region sizes in board.mk are the ones the linker enforces.
$(BA)/memory.ld: boards/$(BOARD)/board.mk mk/boards.mk
	@mkdir -p $(@D)
	@{ echo '/* generated from BOARD_MEM in boards/$(BOARD)/board.mk: do not edit */'; echo 'MEMORY'; echo '{'; \
	   $(foreach r,$(BOARD_MEM),echo '    $(word 1,$(subst :, ,$(r))) ($(word 4,$(subst :, ,$(r)))) : ORIGIN = $(word 2,$(subst :, ,$(r))), LENGTH = $(word 3,$(subst :, ,$(r)))';) \
	   echo '}'; } > $@

ARM_BOARD_SRCS := boards/$(BOARD)/startup.c firmware/board/tdc_crt0.c \
                  $(if $(BOARD_QEMU),firmware/board/tdc_semihost.c)
ARM_LDDEPS := $(BA)/memory.ld $(BOARD_LDS) firmware/board/tdc_cortexm_sections.ld

$(BA)/firmware/%.o: firmware/%.c $(GEN)/tdc_panels.h
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_FW_CFLAGS) -MMD -MP -c $< -o $@
$(BA)/boards/%.o: boards/%.c
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_FW_CFLAGS) -MMD -MP -c $< -o $@
$(BA)/gen/%.o: $(GEN)/%.c
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_FW_CFLAGS) -c $< -o $@
$(BA)/tests/%.o: tests/%.c $(GEN)/tdc_panels.h $(GEN)/golden_list.h
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_TEST_CFLAGS) -MMD -MP -c $< -o $@

# Firmware library for the target: every firmware source and every panel
# table, as for the host library (the golden runner links it).
# Lists that later fragments extend are expanded late (second expansion):
# mk/*.mk files after this one append to FW_SRCS and GOLDEN_STAGES.
ARM_FW_OBJS = $(patsubst %.c,$(BA)/%.o,$(FW_SRCS)) $(foreach p,$(PANELS),$(BA)/gen/tdc_panel_$(p).o)
$(BA)/libtdcfw.a: $$(ARM_FW_OBJS)
	@rm -f $@
	$(ARM_CROSS)ar rcs $@ $^

# Link an image; a region overflow becomes the memory-fit verdict ($(1) names
# what was linked).
ARM_LINK = $(ARM_CC) $(ARM_LDFLAGS) -Wl,-Map=$(basename $@).map $(filter %.o %.a,$^) $(ARM_LIBS) -o $@ \
           2> $@.log || { cat $@.log; tests/arm/fit_report.sh "$(BOARD)" "$(1)" $@.log; rm -f $@; exit 1; }; \
           cat $@.log; rm -f $@.log

# ---------------------------------------------------------------------------
# Golden-vector runner: every registered stage, output by semihosting; and
# the harness self-test image (tests/arm/harness_main.c).
# ---------------------------------------------------------------------------
ARM_GOLDEN_OBJS = $(patsubst %.c,$(BA)/%.o,$(ARM_BOARD_SRCS) tests/arm/golden_arm_main.c $(GOLDEN_COMMON) \
                  $(foreach s,$(GOLDEN_STAGES),tests/golden/golden_$(s).c))
ARM_HARNESS_OBJS = $(patsubst %.c,$(BA)/%.o,$(ARM_BOARD_SRCS) tests/arm/harness_main.c $(GOLDEN_COMMON))

$(BA)/tdc_golden.elf: $$(ARM_GOLDEN_OBJS) $(BA)/libtdcfw.a $(ARM_LDDEPS)
	$(call ARM_LINK,the golden-vector runner)
$(BA)/tdc_harness.elf: $$(ARM_HARNESS_OBJS) $(ARM_LDDEPS)
	$(call ARM_LINK,the harness self-test)

arm-golden: $(BA)/tdc_golden.elf $(if $(BOARD_QEMU),$(BA)/tdc_harness.elf)

# QEMU run and comparison (only for emulated boards).
$(BA)/golden-check: $(BA)/tdc_golden.elf tests/arm/run_golden_qemu.sh
	@printf '#!/bin/sh\nexec tests/arm/run_golden_qemu.sh "%s" %s "%s" %s\n' \
	    "$(BOARD)" "$(QEMU_TIMEOUT)" "$(BA)/tdc_golden.elf" "$(BOARD_QEMU)" > $@
	@chmod +x $@
$(BA)/harness-check: $(BA)/tdc_harness.elf tests/arm/test_harness.sh
	@printf '#!/bin/sh\nexec tests/arm/test_harness.sh "%s" "%s" %s\n' \
	    "$(BOARD)" "$(BA)/tdc_harness.elf" "$(BOARD_QEMU)" > $@
	@chmod +x $@

arm-golden-check: $(BA)/golden-check $(BA)/harness-check
	@tests/run_tests.sh "arm-$(BOARD)" $(BA)/harness-check $(BA)/golden-check

-include $(shell find $(BA) -name '*.d' 2>/dev/null)
endif

# ---------------------------------------------------------------------------
# make test-arm: every emulated board runs the golden vectors in QEMU.
# A build failure counts as a FAIL line too, so it cannot go unnoticed.
# ---------------------------------------------------------------------------
test-arm:
	@for b in $(QEMU_BOARDS); do \
	    if $(MAKE) --no-print-directory -j2 BOARD=$$b arm-golden; then \
	        $(MAKE) --no-print-directory BOARD=$$b arm-golden-check; \
	    else echo "[arm-$$b] FAIL golden runner build"; echo "arm-$$b golden-build FAIL" >> "$(RESULTS)"; fi; \
	done
