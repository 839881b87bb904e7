# tdc - temporally dense display controller: the one entry point.
#
#   make                      host build of firmware library, sim and tools
#   make BOARD=<b> PANEL=<p>  firmware image for a board/panel pair
#   make demo                 the main job (installs Debian packages first)
#   make test                 every test (installs Debian packages first)
#   make bench                benchmarks (performance lives here, not in tests)
#   make golden-update        regenerate golden checksums (see docs/golden-vectors.md)
#
# Components add themselves through mk/*.mk fragments, each appending to
# the variables below.  A fragment owns its sources, programs and tests.

BOARD ?= host
PANEL ?= htc-vive
BUILD ?= build

BOARDS := $(sort $(notdir $(patsubst %/board.mk,%,$(wildcard boards/*/board.mk))))
PANELS := $(sort $(basename $(notdir $(wildcard boards/panels/*.panel))))

ifeq ($(filter $(BOARD),$(BOARDS)),)
$(error unknown BOARD '$(BOARD)'; known boards: $(BOARDS))
endif
ifeq ($(filter $(PANEL),$(PANELS)),)
$(error unknown PANEL '$(PANEL)'; known panels: $(PANELS))
endif

# ---------------------------------------------------------------------------
# Debian packages before anything compiles, whatever the goal and -j: the
# first make only runs `deps`, then re-enters itself for the goals with
# TDC_DEPS=done, so no compiler line can come before apt-get (`make -n demo`
# shows the order).  Prerequisites alone cannot promise that: with -j, or with
# fragments read in file-name order, compile lines ran before `deps`.
# ---------------------------------------------------------------------------
NODEPS_GOALS := deps clean help
TDC_WRAP :=
ifneq ($(TDC_DEPS),done)
ifneq ($(filter-out $(NODEPS_GOALS),$(or $(MAKECMDGOALS),all)),)
TDC_WRAP := 1
TDC_GOALS := $(or $(MAKECMDGOALS),all)
.PHONY: $(TDC_GOALS) tdc-deps-first
$(TDC_GOALS): tdc-deps-first
	@:
tdc-deps-first:
	@$(MAKE) --no-print-directory TDC_DEPS=done deps
	@$(MAKE) --no-print-directory TDC_DEPS=done $(MAKECMDGOALS)
endif
endif
ifneq ($(TDC_WRAP),1)

include boards/$(BOARD)/board.mk

# ---------------------------------------------------------------------------
# Host toolchain variant: CC (gcc|clang), OPT (-O0|-O2), SAN=1 for
# AddressSanitizer + UndefinedBehaviorSanitizer.  Each variant builds in its
# own directory so they can coexist.
# ---------------------------------------------------------------------------
CC := $(if $(filter default,$(origin CC)),gcc,$(CC))
OPT ?= -O2
SAN ?=
CCNAME := $(notdir $(firstword $(CC)))
VARIANT := $(CCNAME)$(OPT)$(if $(SAN),-san)
B := $(BUILD)/$(VARIANT)
GEN := $(BUILD)/gen

comma := ,
SAN_FLAGS := $(if $(SAN),-fsanitize=address$(comma)undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)

# Firmware: C11, warnings are errors, no VLAs.  On x86-64 gcc builds the
# firmware with -mgeneral-regs-only so any floating-point operation is a
# compile error (the no-float rule checked by the build).
FW_WARN := -std=c11 -Wall -Wextra -Werror -Wpedantic -Wvla -Wshadow \
           -Wstrict-prototypes -Wmissing-prototypes -Wdouble-promotion -Wfloat-equal
FW_NOFLOAT := $(if $(and $(filter gcc,$(CCNAME)),$(filter x86_64,$(shell uname -m))),-mgeneral-regs-only)
FW_CFLAGS := $(FW_WARN) $(OPT) -g $(SAN_FLAGS) $(FW_NOFLOAT) -ffunction-sections -fdata-sections \
             -Ifirmware -I$(GEN)

# Host code (sim, tests, tools): may use double, libc, libraries.
HOST_CFLAGS := -std=c11 -D_GNU_SOURCE -Wall -Wextra -Werror -Wvla -Wshadow $(OPT) -g $(SAN_FLAGS) \
               -Ifirmware -I$(GEN) -Icommon -Isim -Iref -I. -Itests
HOST_LDFLAGS := $(SAN_FLAGS)
HOST_LIBS := -lcmocka -lpng -lm -lpthread

# Variables fragments append to.
FW_SRCS :=          # firmware library sources (fixed point, no float)
SIM_SRCS :=         # host simulation library sources (float reference etc.)
TESTS :=            # executables run by `make test` (exit 0 = pass)
GOLDEN_STAGES :=    # stage names with tests/golden/golden_<stage>.c
BENCHES :=          # executables run by `make bench`
HOST_PROGS :=       # programs built by plain `make`
DEPS_PKGS := gcc make clang libclang-rt-14-dev libcmocka-dev libpng-dev pkg-config \
             python3-numpy python3-matplotlib python3-skimage
DEPS_ARCHS :=       # foreign Debian architectures (multiarch) DEPS_PKGS names as PKG:ARCH
TEST_EXTRA :=       # extra phony targets `make test` runs after the host suites
TEST_BESIDE := test-variants # phony targets `make test` runs in the background beside TEST_EXTRA

.PHONY: all deps test run-tests run-golden bench demo golden-update clean firmware help
all: $(if $(filter host,$(BOARD)),host,firmware)

# Names that several fragments use, defined before the fragments are read:
# make expands a rule's prerequisites when it reads the rule, so a name set
# in a later fragment would be empty there (mk/*.mk are read in file-name
# order; tests/rules/check_make_order.py keeps it so).
FWLIB := $(B)/libtdcfw.a
SIMLIB := $(B)/libtdcsim.a
SIMXLIB := $(B)/libtdcsimulator.a
RENDERLIB := $(B)/libtdcrender.a
# TDC_SIM may name another binary (make experiments TDC_SIM=frozen/tdc-sim: a
# long run's cache keys hold the binary's SHA-256); the build rule makes only
# TDC_SIM_BIN, so a frozen copy is never rebuilt from newer sources
TDC_SIM_BIN := $(B)/tdc-sim
TDC_SIM := $(TDC_SIM_BIN)
TDC_RENDER := $(B)/tdc-render
TDCRUN := $(B)/bin/tdc-run
TABLEGEN := $(BUILD)/tools/tdc-tablegen
# test support linked into every test: deterministic contents, checksums
TEST_SUPPORT_OBJS = $(B)/tests/golden/tdc_content.o $(B)/tests/golden/golden_common.o
# Generated headers every firmware object may include, in every build folder
# (host, arm-<board>, <board>-<panel>, fw-host): order-only prerequisites of
# the object rules, so a fresh tree generates them before the first compile
# (the .d files track their contents after that).  Fragments append.
FW_GEN_HEADERS := $(GEN)/tdc_panels.h

# Rules whose prerequisites name lists that later fragments extend use $$(...).
.SECONDEXPANSION:

include $(sort $(wildcard mk/*.mk))

# Golden runner over every registered stage (GOLDEN_STAGES is complete here).
$(B)/tests/tdc_golden: $(B)/tests/golden/golden_host_main.o $(GOLDEN_OBJS) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $(filter %.o,$^) -o $@ $(FWLIB) $(HOST_LIBS)

# ---------------------------------------------------------------------------
# Debian packages: installed once, skipped when present.
# ---------------------------------------------------------------------------
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
# A foreign architecture (DEPS_ARCHS, e.g. arm64 for the arm64 libraries of
# the Linux board's cross build) is added to dpkg first; its packages are
# then missing, so the apt-get update below reads its package lists.
deps:
	@for a in $(sort $(DEPS_ARCHS)); do \
	    dpkg --print-foreign-architectures | grep -qx "$$a" || { \
	    echo "deps: adding architecture $$a (dpkg --add-architecture)"; $(SUDO) dpkg --add-architecture "$$a" || exit 1; }; \
	done; \
	missing=$$(for p in $(sort $(DEPS_PKGS)); do \
	    dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	    echo "deps: installing:" $$missing; \
	    $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get update -qq && \
	    $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	else echo "deps: all Debian packages present"; fi

# ---------------------------------------------------------------------------
# Generated tables: one C file + config header per panel profile.
# ---------------------------------------------------------------------------
$(TABLEGEN): hosttools/tablegen/tdc_tablegen.c common/tdc_tool.c firmware/tdc_math.c $(wildcard hosttools/tablegen/*.h) \
             common/tdc_tool.h | $(BUILD)/tools
	gcc -std=c11 -D_GNU_SOURCE -Wall -Wextra -Werror -O2 -Ifirmware -Icommon $(filter %.c,$^) -o $@ -lm

$(GEN)/tdc_panel_%.c $(GEN)/tdc_panel_%_config.h: boards/panels/%.panel $(TABLEGEN) | $(GEN)
	$(TABLEGEN) $< $(GEN)

PANEL_CSRCS := $(foreach p,$(PANELS),$(GEN)/tdc_panel_$(p).c)
$(GEN)/tdc_panels.h: $(PANEL_CSRCS) Makefile | $(GEN)
	@{ echo '/* generated by the Makefile: every panel profile linked into host builds */'; \
	   echo '#ifndef TDC_PANELS_H'; echo '#define TDC_PANELS_H'; echo '#include "tdc_panel.h"'; \
	   $(foreach p,$(PANELS),echo 'extern const tdc_panel_t tdc_panel_$(subst -,_,$(p));';) \
	   echo '#define TDC_PANEL_LIST(X) \'; \
	   $(foreach p,$(PANELS),echo '    X(tdc_panel_$(subst -,_,$(p))) \';) \
	   echo ''; echo '#endif'; } > $@

# ---------------------------------------------------------------------------
# Host libraries.
# ---------------------------------------------------------------------------
FW_OBJS = $(patsubst %.c,$(B)/%.o,$(FW_SRCS)) $(patsubst $(GEN)/%.c,$(B)/gen/%.o,$(PANEL_CSRCS))
SIM_OBJS = $(patsubst %.c,$(B)/%.o,$(SIM_SRCS))

$(B)/firmware/%.o: firmware/%.c $(GEN)/tdc_panels.h | $$(FW_GEN_HEADERS)
	@mkdir -p $(@D)
	$(CC) $(FW_CFLAGS) -MMD -MP -c $< -o $@
$(B)/gen/%.o: $(GEN)/%.c
	@mkdir -p $(@D)
	$(CC) $(FW_CFLAGS) -c $< -o $@
# Host code, one rule per source folder (they differ in nothing but the
# folder; a fragment adds flags per folder, e.g. $(B)/hosttools/usb/%.o).
HOST_SRC_DIRS := sim common ref render hosttools tests
define HOST_OBJ_RULE
$$(B)/$(1)/%.o: $(1)/%.c $$(GEN)/tdc_panels.h
	@mkdir -p $$(@D)
	$$(CC) $$(HOST_CFLAGS) -MMD -MP -c $$< -o $$@
endef
$(foreach d,$(HOST_SRC_DIRS),$(eval $(call HOST_OBJ_RULE,$(d))))

# The archives also depend on their object lists, so adding or removing a
# source (or building with another list) rebuilds them.
.PHONY: FORCE
$(B)/.fwobjs: FORCE
	@mkdir -p $(@D); echo '$(FW_OBJS)' | cmp -s - $@ || echo '$(FW_OBJS)' > $@
$(B)/.simobjs: FORCE
	@mkdir -p $(@D); echo '$(SIM_OBJS)' | cmp -s - $@ || echo '$(SIM_OBJS)' > $@

$(FWLIB): $(FW_OBJS) $(B)/.fwobjs
	@rm -f $@
	ar rcs $@ $(FW_OBJS)
$(SIMLIB): $(SIM_OBJS) $(B)/.simobjs
	@rm -f $@; mkdir -p $(@D)
	ar rcs $@ $(SIM_OBJS) $(if $(SIM_OBJS),,--thin)

# A test or bench program from one source file: tests/<name>.c -> $(B)/tests/<name>
$(B)/tests/%: $(B)/tests/%.o $(TEST_SUPPORT_OBJS) $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $< $(TEST_SUPPORT_OBJS) -o $@ $(SIMLIB) $(FWLIB) $(HOST_LIBS)

-include $(shell find $(B) -name '*.d' 2>/dev/null)

$(BUILD)/tools $(GEN):
	@mkdir -p $@

host: $(FWLIB) $(SIMLIB) $(HOST_PROGS)

# ---------------------------------------------------------------------------
# Build-enforced firmware rules on the host objects: no float, no heap.
# ---------------------------------------------------------------------------
$(B)/check-fw-rules: $(FW_OBJS) tests/rules/check_fw_symbols.sh tests/rules/check_no_recursion.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\n# generated: firmware objects must not reference float or heap symbols, no recursion\ntests/rules/check_fw_symbols.sh nm %s || exit 1\nexec tests/rules/check_no_recursion.sh -std=c11 -I%s -I%s -- %s\n' "$(FW_OBJS)" "$(abspath firmware)" "$(abspath $(GEN))" "$(FW_SRCS)" > $@
	@chmod +x $@

# ---------------------------------------------------------------------------
# Tests.  `make test` runs the whole suite with gcc -O2, again under
# ASan+UBSan, the golden vectors with gcc/clang at -O0/-O2, then the extra
# targets fragments register (ARM under QEMU, fuzz smoke, ...).  Every run
# appends to $(BUILD)/test-results.txt; the summary line decides the exit.
# ---------------------------------------------------------------------------
RESULTS := $(abspath $(BUILD))/test-results.txt
export RESULTS

# The runner records each test's verdict in $(RESULTS) and never fails the
# recipe itself, so a non-zero sub-make below means the build failed, which
# is recorded as a failure of its own (a broken build must not pass quietly).
run-tests: $(TESTS) $(B)/check-fw-rules $(B)/golden-check
	@tests/run_tests.sh "$(VARIANT)" $(B)/check-fw-rules $(TESTS) $(B)/golden-check || true

run-golden: $(B)/golden-check
	@tests/run_tests.sh "$(VARIANT)" $(B)/golden-check || true

define run_step
	@$(MAKE) --no-print-directory -j2 $(1) || { echo "$(2) build FAIL" >> $(RESULTS); echo "*** $(2): build or target failed"; }
endef

# The first variant builds what every variant shares ($(GEN), $(BUILD)/tools);
# the other four build only in their own folders, so they run in the
# background (test-variants, a TEST_BESIDE target) beside the extra targets,
# whose QEMU runs are single-threaded: run one after another the steps kept
# one of the two cores idle (23 min wall for 22.7 min of CPU at 694afb3).
# Each background step's output is printed when it ends, its verdicts go to
# $(RESULTS), and every step prints its wall time.
# In a fresh tree (CI's clean clone: no build/ yet) the newcomer's demo runs
# first, in place (tests/fresh/demo_in_tree.sh): test-newcomer reports it
# instead of building the whole host tree a second time in its copy.
FRESH_DEMO_MARK := $(abspath $(BUILD))/fresh-demo.mark
test: deps
	@fresh=; [ -d $(BUILD) ] || fresh=1; mkdir -p $(BUILD); rm -f $(RESULTS) $(FRESH_DEMO_MARK); \
	if [ -n "$$fresh" ]; then tests/timed.sh "demo DEMO_SCALE=ci (fresh tree, in place)" tests/fresh/demo_in_tree.sh $(FRESH_DEMO_MARK); fi
	@tests/timed.sh "gcc-O2 run-tests" $(MAKE) --no-print-directory -j2 run-tests CC=gcc OPT=-O2 || \
	    { echo "gcc-O2 run-tests build FAIL" >> $(RESULTS); echo "*** gcc-O2 run-tests: build or target failed"; }
	@mkdir -p $(BUILD); for t in $(TEST_BESIDE); do { tests/timed.sh "$$t (background)" $(MAKE) --no-print-directory $$t || \
	    { echo "$$t target FAIL" >> $(RESULTS); echo "*** $$t: target failed"; }; } \
	    > $(BUILD)/beside-$$t.log 2>&1 & echo $$! > $(BUILD)/beside-$$t.pid; done
	@for t in $(TEST_EXTRA); do tests/timed.sh "$$t" $(MAKE) --no-print-directory $$t || \
	    { echo "$$t target FAIL" >> $(RESULTS); echo "*** $$t: target failed"; }; done
	@for t in $(TEST_BESIDE); do while kill -0 $$(cat $(BUILD)/beside-$$t.pid) 2>/dev/null; do sleep 2; done; \
	    cat $(BUILD)/beside-$$t.log; done
	@tests/summary.sh $(RESULTS)

.PHONY: test-variants
test-variants:
	$(call run_step,run-tests CC=gcc OPT=-O1 SAN=1,gcc-O1-san run-tests)
	$(call run_step,run-golden CC=gcc OPT=-O0,gcc-O0 run-golden)
	$(call run_step,run-golden CC=clang OPT=-O0,clang-O0 run-golden)
	$(call run_step,run-golden CC=clang OPT=-O2,clang-O2 run-golden)

bench: deps $(BENCHES)
	@for b in $(BENCHES); do echo "== $$b"; $$b || exit 1; done

clean:
	rm -rf $(BUILD)

help:
	@sed -n '2,12p' Makefile
	@echo "boards: $(BOARDS)"; echo "panels: $(PANELS)"

endif # TDC_WRAP
