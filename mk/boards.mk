# Boards (issue 8): Cortex-M firmware images, the golden vectors under QEMU,
# memory fit, the firmware rules on the linked target images, sizes and
# per-pixel cost on the target.  See docs/boards.md.
#
#   make BOARD=<b> PANEL=<p>        firmware image build/<b>-<p>/tdc-firmware.elf
#   make BOARD=<b> PANEL=<p> run-arm STREAM=f.tdcs   run it in QEMU on a link stream
#   make test-arm                   (part of make test) golden run in QEMU, image rules, fit test
#   make size                       arm-none-eabi-size of every board/panel pair
#   make bench-arm                  instructions per output pixel on Cortex-M7 / M55 (QEMU)
#   make profile-arm [GROUP=trm]    which functions those instructions are spent in (M7)
#
# A board folder holds board.mk (BOARD_CPU, BOARD_LDS, BOARD_MEM, BOARD_FLASH,
# BOARD_QEMU for emulated boards), board.h, startup.c (or BOARD_STARTUP: the QEMU boards share firmware/board/tdc_startup_qemu.c) and the linker script.

# What every QEMU board shares, so its board.mk is the machine and memory map:
# QEMU loads the ELF, and the start-up, emulated board layer and semihosting
# come from firmware/board/.
ifneq ($(BOARD_QEMU),)
BOARD_FLASH ?= none: QEMU loads the ELF (qemu-system-arm $(BOARD_QEMU) -kernel IMAGE)
BOARD_STARTUP ?= firmware/board/tdc_startup_qemu.c
BOARD_SRCS ?= $(BOARD_STARTUP) firmware/board/tdc_board_emulated.c firmware/board/tdc_semihost.c
endif

DEPS_PKGS += gcc-arm-none-eabi binutils-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
TEST_EXTRA += test-arm

ARM_CROSS := arm-none-eabi-
ARM_CC := $(ARM_CROSS)gcc
ARM_NM := $(ARM_CROSS)nm
ARM_SIZE := $(ARM_CROSS)size
ARM_OBJCOPY := $(ARM_CROSS)objcopy
ARM_OPT ?= -O2
QEMU_TIMEOUT ?= 600
# The instruction-counting TCG plugin (make bench-arm, below): defined before
# the first rule that names it as a prerequisite (arm-bench, arm-loop-cost),
# since prerequisites are expanded when make reads the rule.
INSN_PLUGIN := $(BUILD)/tools/tdc-insn-count.so

# Cortex-M boards: those with a linker script (the host and the Linux board
# build programs for an operating system; make size has nothing to say of them).
ARM_BOARDS := $(sort $(patsubst boards/%/board.mk,%,$(shell grep -l '^BOARD_LDS' boards/*/board.mk)))
# Emulated boards: those whose board.mk names a QEMU machine.
QEMU_BOARDS := $(sort $(patsubst boards/%/board.mk,%,$(shell grep -l '^BOARD_QEMU' boards/*/board.mk)))
# The board frame loop: tdc_main.c and one file per stream family, output
# stage and transport property (firmware/board/tdc_fw_family.h), each empty
# unless its stage is in the build.
FW_LOOP_SRCS := firmware/board/tdc_main.c $(sort $(wildcard firmware/board/tdc_fw_*.c))

.PHONY: arm-fw-layers-check arm-fw-fov-check arm-fw-loop-check arm-fw-refuse-check arm-fw-bands-check arm-loop-cost run-arm firmware-size test-arm size bench-arm arm-bench profile-arm arm-profile arm-golden arm-golden-check arm-image-check arm-fit-check arm-fw-check


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
PANEL_TYPE := $(shell awk '$$1 == "type" { print $$2 }' boards/panels/$(PANEL).panel)

ARM_CFLAGS := $(BOARD_CPU) $(ARM_OPT) -g -ffunction-sections -fdata-sections -fno-common \
              -Ifirmware -Ifirmware/board -Iboards/$(BOARD) -I$(GEN)
# Helium boards (BOARD_MVE := 1): every object knows (TDC_TRM_MVE selects the
# MVE row kernels, the start-up enables CP10/CP11); the MVE object itself is
# built with integer MVE and no FPU (+nofp) under the softfp ABI, which MVE
# needs and which passes arguments in core registers like soft.
ifeq ($(BOARD_MVE),1)
ARM_CFLAGS += -DTDC_TRM_MVE=1
ARM_MVE_FIX = $(subst -mfloat-abi=soft,-mfloat-abi=softfp,$(subst -mcpu=cortex-m55,-mcpu=cortex-m55+nofp,$(1)))
endif
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

ARM_BOARD_SRCS := $(or $(BOARD_STARTUP),boards/$(BOARD)/startup.c) firmware/board/tdc_crt0.c \
                  $(if $(BOARD_QEMU),firmware/board/tdc_semihost.c)
ARM_LDDEPS := $(BA)/memory.ld $(BOARD_LDS) firmware/board/tdc_cortexm_sections.ld

# Compiler flags are part of the objects: rebuild when they change (ARM_OPT).
$(BA)/cflags: FORCE
	@mkdir -p $(@D); echo '$(ARM_TEST_CFLAGS)' | cmp -s - $@ || echo '$(ARM_TEST_CFLAGS)' > $@
$(BA)/firmware/%.o: firmware/%.c $(GEN)/tdc_panels.h $(BA)/cflags | $$(FW_GEN_HEADERS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_FW_CFLAGS) -MMD -MP -c $< -o $@
$(BA)/boards/%.o: boards/%.c $(BA)/cflags
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_FW_CFLAGS) -MMD -MP -c $< -o $@
$(BA)/gen/%.o: $(GEN)/%.c $(BA)/cflags
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_FW_CFLAGS) -c $< -o $@
$(BA)/tests/%.o: tests/%.c $(GEN)/tdc_panels.h $(GEN)/golden_list.h $(BA)/cflags
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

ifeq ($(BOARD_MVE),1)
$(BA)/firmware/tdc_trm_mve.o: ARM_FW_CFLAGS := $(call ARM_MVE_FIX,$(ARM_FW_CFLAGS))
$(BA)/firmware/tdc_fov_mve.o: ARM_FW_CFLAGS := $(call ARM_MVE_FIX,$(ARM_FW_CFLAGS))
endif

# Link an image; a region overflow becomes the memory-fit verdict ($(1) names
# what was linked).
ARM_LINK = $(ARM_CC) $(ARM_LDFLAGS) -Wl,-Map=$(basename $@).map $(filter %.o %.a,$^) $(ARM_LIBS) -o $@ \
           2> $@.log || { cat $@.log; tools/fit_report.sh "$(BOARD)" "$(1)" $@.log $(ARM_NM) $(filter %.o,$^); rm -f $@; exit 1; }; \
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

# An image that breaks the rules on purpose: the image check must catch it.
ARM_BAD_OBJS = $(patsubst %.c,$(BA)/%.o,$(ARM_BOARD_SRCS) tests/arm/bad_rules.c)
$(BA)/bad_rules.elf: $$(ARM_BAD_OBJS) $(ARM_LDDEPS)
	$(ARM_CC) $(ARM_LDFLAGS) --specs=nosys.specs -Wl,--defsym=end=__ext_end $(filter %.o,$^) $(ARM_LIBS) -o $@
$(BA)/image-rules-selftest: $(BA)/bad_rules.elf tests/arm/test_image_rules.sh
	@printf '#!/bin/sh\nexec tests/arm/test_image_rules.sh %s %s\n' "$(ARM_NM)" "$<" > $@
	@chmod +x $@

# Cost per pixel on the target: bench image (tests/arm/bench_arm_main.c).
# (The link encoder it uses is firmware/tdc_link_encode.c, in libtdcfw.a.)
ARM_BENCH_OBJS = $(patsubst %.c,$(BA)/%.o,$(ARM_BOARD_SRCS) tests/arm/bench_arm_main.c tests/golden/tdc_content.c \
                   tests/golden/tdc_layer_content.c)
$(BA)/tdc_bench.elf: $$(ARM_BENCH_OBJS) $(BA)/libtdcfw.a $(ARM_LDDEPS)
	$(call ARM_LINK,the bench image)
$(BA)/bench.tsv: $(BA)/tdc_bench.elf $(INSN_PLUGIN) tests/arm/bench_arm.sh
	tests/arm/bench_arm.sh $(ARM_NM) $(INSN_PLUGIN) $< $(BOARD_QEMU) > $@.tmp && mv $@.tmp $@
arm-bench: $(BA)/bench.tsv
# Per-function profile of one bench group: make profile-arm [BOARD=..] [GROUP=trm]
GROUP ?= trm
arm-profile: $(BA)/tdc_bench.elf $(INSN_PLUGIN)
	@tests/arm/profile_arm.sh $(ARM_NM) $(INSN_PLUGIN) $< $(GROUP) $(BOARD_QEMU)

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

# Helium boards: the checkasm core (tests/checkasm/, the host's registry and
# inputs) in QEMU, which checks the MVE row kernels against the C kernels.
ARM_CHECKASM_SRCS = tests/arm/checkasm_arm_main.c tests/checkasm/checkasm.c tests/checkasm/checkasm_trm.c tests/checkasm/checkasm_lcd.c tests/checkasm/checkasm_fov.c
ARM_CHECKASM_OBJS = $(patsubst %.c,$(BA)/%.o,$(ARM_BOARD_SRCS) $(ARM_CHECKASM_SRCS))
$(patsubst %.c,$(BA)/%.o,$(ARM_CHECKASM_SRCS)): ARM_TEST_CFLAGS += -DCHECKASM_NO_MAIN
$(BA)/checkasm_mve.elf: $$(ARM_CHECKASM_OBJS) $(BA)/libtdcfw.a $(ARM_LDDEPS)
	$(call ARM_LINK,the checkasm core (Helium kernels))
$(BA)/checkasm-mve: $(BA)/checkasm_mve.elf tests/arm/run_checkasm_qemu.sh
	@printf '#!/bin/sh\nexec tests/arm/run_checkasm_qemu.sh "%s" %s "%s" %s\n' \
	    "$(BOARD)" "$(QEMU_TIMEOUT)" "$(BA)/checkasm_mve.elf" "$(BOARD_QEMU)" > $@
	@chmod +x $@
$(BA)/mve-nofloat: $(BA)/firmware/tdc_trm_mve.o $(BA)/firmware/tdc_fov_mve.o tests/rules/check_arm_nofloat.sh
	@printf '#!/bin/sh\nexec tests/rules/check_arm_nofloat.sh %s %s\n' "$(ARM_CROSS)objdump" "$(filter %.o,$^)" > $@
	@chmod +x $@
ARM_CHECKASM = $(if $(filter 1,$(BOARD_MVE)),$(BA)/checkasm-mve $(BA)/mve-nofloat)

arm-golden-check: $(BA)/golden-check $(BA)/harness-check $(ARM_CHECKASM)
	@tests/run_tests.sh "arm-$(BOARD)" $(BA)/harness-check $(BA)/golden-check $(ARM_CHECKASM)

# ---------------------------------------------------------------------------
# Firmware image of a board/panel pair: the frame loop (firmware/board/
# tdc_main.c and its stream families, $(FW_LOOP_SRCS)) over the firmware sources, compiled with the panel's config
# header.  STAGES picks the pipeline stages (default: the board's
# BOARD_STAGES, else all); the LCD inverse only on LCD panels, and its
# sources ($(FW_LCD_SRCS)) are left out of every other build.
# ---------------------------------------------------------------------------
# fov: the foveation stage (FOVEATED streams, docs/foveation.md) without
# peripheral TAA; fovtaa: with it (12 B/px of history per eye).  layers: the
# layered assembly (SUBFRAMES | LAYERS streams, 148 B/px per eye with its
# history), in no board's defaults: STAGES=layers.
ALL_STAGES := trm assemble lcd fovtaa
# A board may name other default stages for a panel: BOARD_STAGES_<panel>.
STAGES_DEFAULT := $(if $(filter-out undefined,$(origin BOARD_STAGES_$(PANEL))),$(BOARD_STAGES_$(PANEL)),$(if \
                  $(filter undefined,$(origin BOARD_STAGES)),$(ALL_STAGES),$(BOARD_STAGES)))
STAGES ?= $(STAGES_DEFAULT)
# The image of a pair: build/<board>-<panel>, or build/<board>-<panel>-<stages>
# when STAGES differs from the board's default (e.g. -link for STAGES=);
# BOARD_BP_SUFFIX: a board built for more than one CPU names the CPU.
space := $(eval) $(eval)
STAGES_TAG := $(or $(subst $(space),+,$(sort $(STAGES))),link)
BP := $(BUILD)/$(BOARD)-$(PANEL)$(BOARD_BP_SUFFIX)$(if $(filter-out $(sort $(STAGES)),$(sort $(STAGES_DEFAULT)))$(filter-out $(sort $(STAGES_DEFAULT)),$(sort $(STAGES))),-$(STAGES_TAG))$(if $(filter-out $(or $(BOARD_BANDS),0),$(BANDS)),-bands$(BANDS))
FW_LCD_ON := $(if $(and $(filter lcd,$(PANEL_TYPE)),$(filter lcd,$(STAGES))),1,0)
# BOARD_FW_CFG: the board's own configuration defines (e.g. LCD history
# bits, the link formats it accepts), for every object of its images.
# FOV_TRM=0 (with trm and fov in STAGES): no foveated TRM, whose decoder
# buffers and stage arenas sit beside TRM's arena (docs/boards.md, "Foveated
# streams"): the mode arena as without it, such a stream refused by name.
# BANDS=1 (default: the board's BOARD_BANDS): pictures as row bands, one band
# staged, a front/back frame buffer pair (docs/boards.md, "Rows in flight").
BANDS ?= $(or $(BOARD_BANDS),0)
FW_CFG_BASE := -DTDC_CFG_TRM=$(if $(filter trm,$(STAGES)),1,0) -DTDC_CFG_ASSEMBLE=$(if $(filter assemble,$(STAGES)),1,0) \
          -DTDC_CFG_FOV=$(if $(filter fov fovtaa,$(STAGES)),1,0) -DTDC_CFG_FOV_TAA=$(if $(filter fovtaa,$(STAGES)),1,0) \
          -DTDC_CFG_LCD=$(FW_LCD_ON) $(if $(filter 0,$(FOV_TRM)),-DTDC_CFG_FOV_TRM=0) \
          -DTDC_CFG_LAYERS=$(if $(filter layers,$(STAGES)),1,0) $(BOARD_FW_CFG)
FW_CFG := $(FW_CFG_BASE) -DTDC_CFG_BANDS=$(BANDS)
PANEL_CONFIG := $(GEN)/tdc_panel_$(PANEL)_config.h
ARM_IMG_CFLAGS := $(ARM_FW_CFLAGS) -include $(PANEL_CONFIG) $(FW_CFG)
FW_IMG_SRCS = $(filter-out $(if $(filter 1,$(FW_LCD_ON)),,$(FW_LCD_SRCS)),$(FW_SRCS)) \
              $(BOARD_SRCS) firmware/board/tdc_crt0.c $(FW_LOOP_SRCS)
FW_IMG_OBJS = $(patsubst %.c,$(BP)/%.o,$(FW_IMG_SRCS)) $(BP)/gen/tdc_panel_$(PANEL).o

# The stage selection and flags are part of the objects: rebuild when they change.
$(BP)/stages: FORCE
	@mkdir -p $(@D); echo '$(ARM_IMG_CFLAGS)' | cmp -s - $@ || echo '$(ARM_IMG_CFLAGS)' > $@
ifeq ($(BOARD_MVE),1)
$(BP)/firmware/tdc_trm_mve.o: ARM_IMG_CFLAGS := $(call ARM_MVE_FIX,$(ARM_IMG_CFLAGS))
$(BP)/firmware/tdc_fov_mve.o: ARM_IMG_CFLAGS := $(call ARM_MVE_FIX,$(ARM_IMG_CFLAGS))
endif
$(BP)/%.o: %.c $(GEN)/tdc_panels.h $(PANEL_CONFIG) $(BP)/stages | $$(FW_GEN_HEADERS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_IMG_CFLAGS) -MMD -MP -c $< -o $@
$(BP)/gen/%.o: $(GEN)/%.c $(BP)/stages
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_IMG_CFLAGS) -c $< -o $@

$(BP)/tdc-firmware.elf: $$(FW_IMG_OBJS) $(ARM_LDDEPS)
	$(call ARM_LINK,panel $(PANEL) (stages: $(or $(strip $(STAGES)),link only)))
	@$(ARM_OBJCOPY) -O binary $@ $(BP)/tdc-firmware.bin
	@echo "firmware: $@ ($(BOARD), panel $(PANEL), stages: $(or $(strip $(STAGES)),link only))"
	@$(ARM_SIZE) $@

# (a hosted board names its own program: BOARD_IMAGE, e.g. mk/linuxboard.mk)
firmware: $(BP)/$(or $(BOARD_IMAGE),tdc-firmware.elf)

# Sections and region use of this pair's image, or its memory-fit verdict
# (a pair that does not fit is a finding, exit 0); any other failure fails.
firmware-size:
	@echo "== $(BOARD) / $(PANEL) (stages: $(or $(strip $(STAGES)),link only))"
	@mkdir -p $(BUILD); if $(MAKE) --no-print-directory firmware > $(BUILD)/.size-$(BOARD)-$(PANEL).log 2>&1; then \
	    tools/size_report.sh $(ARM_SIZE) $(BP)/tdc-firmware.elf "$(BOARD_MEM)"; \
	elif grep -q '^memory fit' $(BUILD)/.size-$(BOARD)-$(PANEL).log; then \
	    grep -A12 '^memory fit' $(BUILD)/.size-$(BOARD)-$(PANEL).log | grep -v '^make' | sed 's/^/    /'; \
	else echo "    build failed (not a memory-fit verdict):"; tail -5 $(BUILD)/.size-$(BOARD)-$(PANEL).log | sed 's/^/    /'; exit 1; fi

# Run this pair's image in QEMU on a link stream file (emulated boards):
#   make BOARD=mps3-an547 PANEL=htc-vive run-arm STREAM=file.tdcs
# prints one "frame N checksum" line per shown frame, the counters on stderr.
run-arm: $(BP)/tdc-firmware.elf
	@test -n "$(BOARD_QEMU)" || { echo "run-arm: $(BOARD) is not an emulated board"; exit 2; }
	@test -f "$(STREAM)" || { echo "run-arm: give STREAM=<file.tdcs>"; exit 2; }
	qemu-system-arm $(BOARD_QEMU) -display none -nodefaults -semihosting-config enable=on,target=native \
	    -kernel $< -append "$(STREAM)"

# Firmware rules on the linked image (not just the objects).
$(BP)/check-image-rules: $(BP)/tdc-firmware.elf tests/arm/check_image_symbols.sh
	@printf '#!/bin/sh\nexec tests/arm/check_image_symbols.sh %s %s\n' "$(ARM_NM)" "$<" > $@
	@chmod +x $@
arm-image-check: $(BP)/check-image-rules
	@tests/run_tests.sh "$(BOARD)-$(PANEL)" $(BP)/check-image-rules

# ---------------------------------------------------------------------------
# End-to-end: the frame loop in QEMU against the same loop built for the
# host (tests/arm/tdc_board_host.c), on streams from tests/arm/fw_stream.c.
# ---------------------------------------------------------------------------
PANEL_DIMS := $(shell awk '$$1 == "width" { w = $$2 } $$1 == "height" { h = $$2 } $$1 == "eyes" { e = $$2 } \
                END { print w, h, (e ? e : 1) }' boards/panels/$(PANEL).panel)
FW_MODES ?= plain $(if $(filter trm,$(STAGES)),trm) $(if $(filter assemble,$(STAGES)),subframes) \
            $(if $(filter fov fovtaa,$(STAGES)),fov fovlr) $(if $(filter fovtaa,$(STAGES)),fov-taa) \
            $(if $(and $(filter trm,$(STAGES)),$(filter fov fovtaa,$(STAGES))),trm-fov) \
            $(if $(filter layers,$(STAGES)),layers layers-hist)
FW_FRAMES_plain := 5
FW_FRAMES_fov := 9
FW_FRAMES_fovlr := 9
FW_FRAMES_fov-taa := 9
FW_FRAMES_fov-clean := 5
FW_FRAMES_fovlr-clean := 5
FW_FRAMES_fov-taa-clean := 5
FW_FRAMES_trm-fov := 8
FW_FRAMES_trm-fov-clean := 5
# The loop-cost rows (make bench-arm) run the foveated streams without their
# damaged packets, so that every frame costs what a foveated frame costs.
FW_LOOP_MODES = $(patsubst trm-fov,trm-fov-clean,$(patsubst fov%,fov%-clean,$(filter-out plain,$(FW_MODES))))
FW_FRAMES_trm := 4
FW_FRAMES_subframes := 6
FW_FRAMES_layers := 6
FW_FRAMES_layers-hist := 6
# The host build of the loop, with and without bands (fw-bands-check compares
# the two): build/<variant>/fw-host/<board>-<panel>-<stages>[-bands].
FWH_B0 := $(B)/fw-host/$(BOARD)-$(PANEL)-$(STAGES_TAG)
FWH_B1 := $(B)/fw-host/$(BOARD)-$(PANEL)-$(STAGES_TAG)-bands
FWH := $(FWH_B$(BANDS))
STREAMS := $(BUILD)/fw-streams
# Firmware sources whose compiled code depends on the panel config (the link
# decoder's compile-time maximum size): built for this panel, linked before
# the host library so its panel-independent copies are not used.
FWH_PANEL_SRCS := $(shell grep -l '"tdc_link.h"' $(filter firmware/%.c,$(wildcard firmware/*.c)))
# $(1): directory, $(2): TDC_CFG_BANDS, $(3): the stage defines
define fw_host_loop
$(1)/board/%.o: firmware/board/%.c $(GEN)/tdc_panels.h $(PANEL_CONFIG) | $$$$(FW_GEN_HEADERS)
	@mkdir -p $$(@D)
	$(CC) $(FW_CFLAGS) -Ifirmware/board -include $(PANEL_CONFIG) $(3) -DTDC_CFG_BANDS=$(2) -DTDC_FW_NO_MAIN -MMD -MP -c $$< -o $$@
$(1)/%.o: tests/arm/%.c firmware/board/tdc_board.h
	@mkdir -p $$(@D)
	$(CC) $(HOST_CFLAGS) -Ifirmware/board -MMD -MP -c $$< -o $$@
$(1)/fw/%.o: firmware/%.c $(GEN)/tdc_panels.h $(PANEL_CONFIG) | $$$$(FW_GEN_HEADERS)
	@mkdir -p $$(@D)
	$(CC) $(FW_CFLAGS) -include $(PANEL_CONFIG) $(3) -DTDC_CFG_BANDS=$(2) -MMD -MP -c $$< -o $$@
$(1)/tdc_fw_host: $(patsubst firmware/board/%.c,$(1)/board/%.o,$(FW_LOOP_SRCS)) $(1)/tdc_board_host.o $(1)/tdc_board_stub.o $(patsubst firmware/%.c,$(1)/fw/%.o,$(FWH_PANEL_SRCS)) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $$^ -o $$@ $(HOST_LIBS)
endef
$(eval $(call fw_host_loop,$(FWH_B0),0,$(FW_CFG_BASE)))
$(eval $(call fw_host_loop,$(FWH_B1),1,$(FW_CFG_BASE)))
# fw-fov's builds that must refuse a foveated TRM stream: without the
# foveation stage, without TRM, and with both but TDC_CFG_FOV_TRM=0 (a
# board short of memory)
FWH_FOVX := $(B)/fw-host/$(BOARD)-$(PANEL)-fovcheck
FW_CFG_NOSTAGE := -DTDC_CFG_ASSEMBLE=0 -DTDC_CFG_FOV_TAA=0 -DTDC_CFG_LCD=0 $(BOARD_FW_CFG)
$(eval $(call fw_host_loop,$(FWH_FOVX)-trm,0,-DTDC_CFG_TRM=1 -DTDC_CFG_FOV=0 $(FW_CFG_NOSTAGE)))
$(eval $(call fw_host_loop,$(FWH_FOVX)-fov,0,-DTDC_CFG_TRM=0 -DTDC_CFG_FOV=1 $(FW_CFG_NOSTAGE)))
$(eval $(call fw_host_loop,$(FWH_FOVX)-optout,0,-DTDC_CFG_TRM=1 -DTDC_CFG_FOV=1 -DTDC_CFG_FOV_TRM=0 $(FW_CFG_NOSTAGE)))

$(B)/tests/arm/fw_stream.o: tests/arm/fw_stream.c $(GEN)/tdc_panels.h
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) -Isim/link -Itests/golden -MMD -MP -c $< -o $@
$(B)/tests/fw_stream: $(B)/tests/arm/fw_stream.o $(B)/tests/golden/tdc_content.o $(B)/tests/golden/tdc_layer_content.o \
                     $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(HOST_LIBS)

$(STREAMS)/$(PANEL)-%.tdcs: $(B)/tests/fw_stream
	@mkdir -p $(@D)
	$(B)/tests/fw_stream $* $(PANEL_DIMS) $(FW_FRAMES_$*) $@ $(if $(filter plain fov fovlr fov-taa trm-fov,$*),$(if \
	    $(filter lcd,$(PANEL_TYPE)),,$@.expected $(if $(filter trm-fov,$*),$(PANEL)))) \
	    $(if $(filter layers layers-hist,$*),$(if $(and $(filter lcd,$(PANEL_TYPE)),$(filter lcd,$(STAGES))),,$@.expected $(PANEL)))

$(BP)/fw-check: $(BP)/tdc-firmware.elf $(FWH)/tdc_fw_host $(foreach m,$(FW_MODES),$(STREAMS)/$(PANEL)-$(m).tdcs) \
                tests/arm/run_fw_qemu.sh tests/run_par.sh
	@{ $(foreach m,$(filter trm-fov,$(FW_MODES)) $(filter-out trm-fov,$(FW_MODES)),echo 'tests/arm/run_fw_qemu.sh "$(BOARD)/$(PANEL)/$(m)" $(QEMU_TIMEOUT) $(BP)/tdc-firmware.elf $(FWH)/tdc_fw_host $(STREAMS)/$(PANEL)-$(m).tdcs $(BOARD_QEMU)';) } > $@.modes
	@printf '#!/bin/sh\n# generated: every mode of this pair under QEMU, two at a time\nexec tests/run_par.sh 2 %s\n' $@.modes > $@
	@chmod +x $@
# Instructions per shown frame of the whole loop on this pair's streams.
PANEL_PIXELS = $(shell echo $(PANEL_DIMS) | awk '{ print $$1 * $$2 * $$3 }')
$(BP)/loop.tsv: $(BP)/tdc-firmware.elf $(INSN_PLUGIN) tests/arm/loop_cost.sh \
                $(foreach m,$(FW_LOOP_MODES),$(STREAMS)/$(PANEL)-$(m).tdcs)
	@for m in $(FW_LOOP_MODES); do \
	    tests/arm/loop_cost.sh $(ARM_NM) $(INSN_PLUGIN) $< $(STREAMS)/$(PANEL)-$$m.tdcs $(PANEL_PIXELS) \
	        "frame loop, $(PANEL) $$m stream" $(BOARD_QEMU) || exit 1; done > $@.tmp && mv $@.tmp $@
arm-loop-cost: $(BP)/loop.tsv

arm-fw-check: $(BP)/fw-check
	@tests/run_tests.sh "$(BOARD)-$(PANEL)" $(BP)/fw-check

# Host-build checks of the loop on crafted streams (issue 17): fw-loop
# (tests/arm/test_fw_loop.sh: after loss, against clean streams),
# fw-refuse (tests/arm/test_fw_refuse.sh: a 60 Hz panel refuses TRM) and
# fw-fov (tests/arm/test_fw_fov.sh, with STAGES="trm fov": foveated streams
# on a build without TAA).
$(BP)/fw-%-check: $(FWH)/tdc_fw_host $(B)/tests/fw_stream tests/arm/test_fw_%.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/arm/test_fw_$*.sh %s %s %s\n' "$(FWH)/tdc_fw_host" "$(B)/tests/fw_stream" "$(PANEL_DIMS)" > $@
	@chmod +x $@
# (fw-fov also runs the streams through the loop with bands: front/back
# buffers, and the foveated TRM stream through the builds that refuse it)
FWH_FOVX_ALL := $(FWH_FOVX)-trm/tdc_fw_host $(FWH_FOVX)-fov/tdc_fw_host $(FWH_FOVX)-optout/tdc_fw_host
$(BP)/fw-fov-check: $(FWH_B0)/tdc_fw_host $(FWH_B1)/tdc_fw_host $(FWH_FOVX_ALL) $(B)/tests/fw_stream tests/arm/test_fw_fov.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/arm/test_fw_fov.sh %s %s %s %s %s %s\n' "$(FWH_B0)/tdc_fw_host" "$(B)/tests/fw_stream" "$(PANEL_DIMS)" "$(FWH_B1)/tdc_fw_host" "$(if $(filter lcd,$(PANEL_TYPE)),-,$(PANEL))" "$(FWH_FOVX_ALL)" > $@
	@chmod +x $@
# fw-layers (tests/arm/test_fw_layers.sh, with STAGES=layers): the layered
# family against tdc_layers itself, with and without history, and refused by
# a build without it (FWH_LNO: these stages but layers).  The same streams in QEMU against
# the host build: make BOARD=mps3-an547 PANEL=disco-dsi STAGES=layers
# arm-fw-check (252 s on the shared machine: not in make test).
FWH_LNO := $(B)/fw-host/$(BOARD)-$(PANEL)-$(STAGES_TAG)-nolayers
$(eval $(call fw_host_loop,$(FWH_LNO),0,$(subst -DTDC_CFG_LAYERS=1,-DTDC_CFG_LAYERS=0,$(FW_CFG_BASE))))
$(BP)/fw-layers-check: $(FWH_B0)/tdc_fw_host $(FWH_LNO)/tdc_fw_host \
                       $(B)/tests/fw_stream tests/arm/test_fw_layers.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/arm/test_fw_layers.sh %s %s %s %s %s\n' "$(FWH_B0)/tdc_fw_host" "$(FWH_LNO)/tdc_fw_host" "$(B)/tests/fw_stream" "$(PANEL_DIMS)" "$(PANEL)" > $@
	@chmod +x $@
arm-fw-layers-check: $(BP)/fw-layers-check
	@tests/run_tests.sh "fw-layers-$(PANEL)" $<
arm-fw-loop-check arm-fw-refuse-check arm-fw-fov-check: arm-fw-%-check: $(BP)/fw-%-check
	@tests/run_tests.sh "fw-$*-$(PANEL)" $<
# Rows in flight (tests/arm/test_fw_bands.sh): the banded loop on banded
# streams, clean and with each bad band, against the whole-picture loop.
$(BP)/fw-bands-check: $(FWH_B1)/tdc_fw_host $(FWH_B0)/tdc_fw_host $(B)/tests/fw_stream tests/arm/test_fw_bands.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/arm/test_fw_bands.sh %s %s %s %s\n' "$(FWH_B1)/tdc_fw_host" "$(FWH_B0)/tdc_fw_host" "$(B)/tests/fw_stream" "$(PANEL_DIMS)" > $@
	@chmod +x $@
arm-fw-bands-check: $(BP)/fw-bands-check
	@tests/run_tests.sh "fw-bands-$(BOARD)-$(PANEL)" $<

-include $(shell find $(BA) $(BP) -name '*.d' 2>/dev/null)
endif

.PHONY: FORCE
FORCE:

# ---------------------------------------------------------------------------
# make test-arm (part of make test): on every emulated board the golden
# vectors and the harness self-test in QEMU; the firmware images of the
# pairs below built, checked for float/heap symbols, and (emulated boards)
# run end to end against the host build of the frame loop; the image check
# and the memory-fit check each shown to fail when they must.  A build
# failure is recorded as a FAIL line too.
#   ARM_TEST_PAIRS: board:panel:stages[:streams] ("default" = the board's
#   default stages, "link" = STAGES= : link decode and panel output only;
#   streams: which of plain+trm+subframes+fov+fovlr+fov-taa+trm-fov to run,
#   default all the stages allow (trm-fov: foveated TRM, with trm and fov);
#   the LCD pair runs only trm to stay within the time budget; the Cortex-M7
#   runs the foveated streams on disco-dsi, the one panel whose buffers fit
#   its 16 MiB of PSRAM with them (60 Hz: no TRM, so no trm-fov on the M7))
#   ARM_FIT_FAIL: board:panel:stages:region pairs that must not fit
# ---------------------------------------------------------------------------
ARM_TEST_PAIRS ?= mps2-an500:htc-vive:link mps2-an500:disco-dsi:default:fov+fovlr+fov-taa \
                  mps3-an547:htc-vive:default mps3-an547:lcd-240:default:trm \
                  stm32h747i-disco:htc-vive:default stm32h747i-disco:lcd-240:default \
                  stm32h747i-disco:disco-dsi:default
ARM_FIT_FAIL ?= mps2-an500:htc-vive:default:PSRAM stm32h747i-disco:htc-vive:assemble:SDRAM
ARM_FAIL_LINE = echo "[$(1)] FAIL $(2)"; echo "$(1) $(2) FAIL" >> "$(RESULTS)"

test-arm:
	@for b in $(QEMU_BOARDS); do \
	    if $(MAKE) --no-print-directory -j2 BOARD=$$b arm-golden $(BUILD)/arm-$$b/image-rules-selftest; then \
	        $(MAKE) --no-print-directory BOARD=$$b arm-golden-check || :; \
	    else $(call ARM_FAIL_LINE,arm-$$b,golden-build); fi; \
	done
	@tests/run_tests.sh arm-$(firstword $(QEMU_BOARDS)) $(BUILD)/arm-$(firstword $(QEMU_BOARDS))/image-rules-selftest || :
	@for t in $(ARM_TEST_PAIRS); do \
	    b=$${t%%:*}; r=$${t#*:}; p=$${r%%:*}; r=$${r#*:}; s=$${r%%:*}; m=; [ "$$r" != "$$s" ] && m=$${r#*:}; \
	    case $$s in default) set -- ;; link) set -- 'STAGES=' ;; *) set -- "STAGES=$$(echo $$s | tr + ' ')" ;; esac; \
	    [ -n "$$m" ] && set -- "$$@" "FW_MODES=$$(echo $$m | tr + ' ')"; \
	    if $(MAKE) --no-print-directory -j2 BOARD=$$b PANEL=$$p "$$@" firmware >/dev/null 2>$(BUILD)/.fwlog-$$b || \
	       { cat $(BUILD)/.fwlog-$$b; false; }; then \
	        $(MAKE) --no-print-directory BOARD=$$b PANEL=$$p "$$@" arm-image-check || :; \
	        if grep -q '^BOARD_QEMU' boards/$$b/board.mk; then \
	            $(MAKE) --no-print-directory -j2 BOARD=$$b PANEL=$$p "$$@" arm-fw-check || :; fi; \
	    else $(call ARM_FAIL_LINE,$$b-$$p,firmware-build); fi; \
	done
	@$(MAKE) --no-print-directory -j2 BOARD=mps3-an547 PANEL=htc-vive arm-fw-loop-check || :
	@$(MAKE) --no-print-directory -j2 BOARD=mps3-an547 PANEL=htc-vive arm-fw-bands-check || :
	@$(MAKE) --no-print-directory -j2 BOARD=stm32h747i-disco PANEL=lcd-240 arm-fw-bands-check || :
	@$(MAKE) --no-print-directory -j2 BOARD=mps3-an547 PANEL=disco-dsi arm-fw-refuse-check || :
	@$(MAKE) --no-print-directory -j2 BOARD=mps3-an547 PANEL=disco-dsi STAGES=layers arm-fw-layers-check || :
	@$(MAKE) --no-print-directory -j2 BOARD=mps3-an547 PANEL=htc-vive STAGES="trm fov" arm-fw-fov-check || :
	@for t in $(ARM_FIT_FAIL); do \
	    b=$${t%%:*}; r=$${t#*:}; p=$${r%%:*}; r=$${r#*:}; s=$${r%%:*}; g=$${r#*:}; \
	    printf '#!/bin/sh\nexec tests/arm/test_fit.sh %s %s %s %s\n' $$b $$p $$s $$g > $(BUILD)/fit-$$b-$$p; \
	    chmod +x $(BUILD)/fit-$$b-$$p; MAKE="$(MAKE)" tests/run_tests.sh "fit-$$b" $(BUILD)/fit-$$b-$$p || :; \
	done

# ---------------------------------------------------------------------------
# make bench-arm: instructions per output pixel of each firmware stage on
# the Cortex-M7 (mps2-an500) and Cortex-M55 (mps3-an547) under QEMU, counted
# by a TCG plugin built here against the plugin API of Debian's QEMU.
# ---------------------------------------------------------------------------
$(INSN_PLUGIN): tests/arm/tdc_insn_plugin.c | $(BUILD)/tools
	gcc -std=c11 -Wall -Wextra -Werror -O2 -shared -fPIC $< -o $@

profile-arm: $(INSN_PLUGIN)
	@$(MAKE) --no-print-directory -j2 BOARD=$(if $(filter host,$(BOARD)),$(firstword $(QEMU_BOARDS)),$(BOARD)) arm-profile

# Whole frame loop per shown frame (mps3-an547: the board whose DDR holds
# every stage at these panel sizes).
# board:panel[:streams]: streams as in ARM_TEST_PAIRS (default all the
# stages allow); the Cortex-M7's foveated rows on disco-dsi (60 Hz: no TRM).
ARM_LOOP_PAIRS ?= mps3-an547:htc-vive mps3-an547:lcd-240 mps2-an500:disco-dsi:fov+fovlr+fov-taa
bench-arm: deps $(INSN_PLUGIN)
	@for b in $(QEMU_BOARDS); do $(MAKE) --no-print-directory -j2 BOARD=$$b arm-bench >/dev/null || exit 1; done
	@ARM_OPT="$(ARM_OPT)" tests/arm/bench_table.sh $(foreach b,$(QEMU_BOARDS),$(b)=$(BUILD)/arm-$(b)/bench.tsv)
	@for t in $(ARM_LOOP_PAIRS); do \
	    b=$${t%%:*}; r=$${t#*:}; p=$${r%%:*}; set --; [ "$$r" != "$$p" ] && set -- "FW_MODES=$$(echo $${r#*:} | tr + ' ')"; \
	    $(MAKE) --no-print-directory -j2 BOARD=$$b PANEL=$$p "$$@" arm-loop-cost >/dev/null || exit 1; done
	@echo; echo "whole frame loop per shown frame (link decode + stages; frames 1.., without the panel checksum):"
	@printf '%-44s %8s %16s %12s\n' stream board "instructions" "per pixel"
	@for t in $(ARM_LOOP_PAIRS); do b=$${t%%:*}; r=$${t#*:}; \
	    awk -F '\t' -v b=$$b '{ printf "%-44s %8s %16s %12s\n", $$1, b, $$2, $$3 }' $(BUILD)/$$b-$${r%%:*}/loop.tsv; done

# make size: every board/panel pair with the board's default stages.
size:
	@rc=0; for b in $(ARM_BOARDS); do for p in $(PANELS); do \
	    $(MAKE) --no-print-directory -j2 BOARD=$$b PANEL=$$p firmware-size || rc=1; done; done; \
	[ $$rc = 0 ] || echo "size: some images failed to build (not a memory-fit verdict): see above"; exit $$rc
