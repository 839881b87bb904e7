# Firmware backbone: fixed-point core, gamma, TRM, golden vectors, tdc-run.
FW_SRCS += firmware/tdc_math.c
TESTS += $(B)/tests/test_math
SIM_SRCS += sim/tdc_png.c
FW_SRCS += firmware/tdc_trm.c
SIM_SRCS += sim/ref_trm.c
TESTS += $(B)/tests/test_trm_ref
TESTS += $(B)/tests/test_trm
TESTS += $(B)/tests/test_trm_stability
TESTS += $(B)/tests/test_trm_loss
GOLDEN_STAGES += trm

# tdc-run: the firmware on anyone's frames.  Other modes add their sources
# to TDCRUN_SRCS (e.g. tile assembly: hosttools/tdcrun/run_assemble.c).
TDCRUN := $(B)/bin/tdc-run
TDCRUN_OBJS = $(patsubst %.c,$(B)/%.o,hosttools/tdcrun/tdc_run.c $(TDCRUN_SRCS)) $(B)/tests/golden/tdc_content.o
$(B)/hosttools/tdcrun/tdc_run.o: HOST_CFLAGS += $(if $(filter hosttools/tdcrun/run_assemble.c,$(TDCRUN_SRCS)),-DTDC_RUN_WITH_ASSEMBLE)
# the mode list comes from the fragments: rebuild when they change
$(B)/hosttools/tdcrun/tdc_run.o: $(wildcard mk/*.mk)
$(TDCRUN): $(TDCRUN_OBJS) $(SIMLIB) $(FWLIB)
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $(TDCRUN_OBJS) -o $@ $(SIMLIB) $(FWLIB) $(HOST_LIBS)
HOST_PROGS += $(TDCRUN)
$(B)/test-tdc-run: $(TDCRUN) tests/test_tdc_run.sh
	@printf '#!/bin/sh\nexec tests/test_tdc_run.sh %s\n' "$(TDCRUN)" > $@
	@chmod +x $@
TESTS += $(B)/test-tdc-run
TESTS += $(B)/tests/test_png
BENCHES += $(B)/tests/bench_trm

# make demo, TRM part: tdc-run on built-in contents -> report/trm/index.md
REPORT ?= report
DEMO_TRM_CONTENTS := edge text checker gradient primaries
demo: deps demo-trm
demo-trm: $(TDCRUN) $(B)/tests/test_trm_ref
	@rm -rf $(BUILD)/demo-trm; mkdir -p $(REPORT)/trm
	@for c in $(DEMO_TRM_CONTENTS); do \
	    $(TDCRUN) -q -o $(BUILD)/demo-trm/$$c --builtin $$c --count 8 --size 320x200 --frames auto \
	        --save-input --perceived || exit 1; done
	/usr/bin/python3 sim/trm_report.py $(REPORT)/trm $(addprefix $(BUILD)/demo-trm/,$(DEMO_TRM_CONTENTS))
	@{ echo; echo '## Fixed point against the double-precision reference'; echo; \
	   echo 'Output of `$(B)/tests/test_trm_ref` (max abs error in output LSB, share within 1 LSB):'; \
	   echo; echo '```'; $(B)/tests/test_trm_ref 2>&1 | grep -E '^  (D|full|reduced) '; echo '```'; } >> $(REPORT)/trm/index.md
	@[ -f $(REPORT)/index.md ] || { echo '# tdc demo report'; echo; echo '- [TRM on built-in contents](trm/index.md)'; } > $(REPORT)/index.md
	@echo "demo-trm: wrote $(REPORT)/trm/index.md"
.PHONY: demo-trm

# TRM row kernels: portable C (boards, the reference) and AVX2 (x86-64 hosts;
# the file compiles to the C kernels elsewhere).  The AVX2 object is built
# without -mgeneral-regs-only, so every firmware object's machine code is
# checked for floating-point instructions instead.
FW_SRCS += firmware/tdc_trm_rows.c firmware/tdc_trm_avx2.c
$(B)/firmware/tdc_trm_avx2.o: FW_CFLAGS := $(filter-out -mgeneral-regs-only,$(FW_CFLAGS))
ifeq ($(shell uname -m),x86_64)
$(B)/test-fw-nofloat-insn: $(FWLIB) tests/check_simd_nofloat.sh
	@printf '#!/bin/sh\nexec tests/check_simd_nofloat.sh objdump %s\n' "$(FW_OBJS)" > $@
	@chmod +x $@
TESTS += $(B)/test-fw-nofloat-insn
endif
TESTS += $(B)/tests/checkasm_trm
$(B)/bench-checkasm-trm: $(B)/tests/checkasm_trm
	@printf '#!/bin/sh\nexec %s --bench\n' "$<" > $@
	@chmod +x $@
BENCHES += $(B)/bench-checkasm-trm

# test_math again with the Cortex-M arithmetic (TDC_HW_DIV64=0: long
# division with 32-bit divides in the reciprocal and the square root), so
# the boards' paths are checked on the host too, not only through QEMU.
$(B)/tests/portable/tdc_math.o: firmware/tdc_math.c $(GEN)/tdc_panels.h
	@mkdir -p $(@D)
	$(CC) $(FW_CFLAGS) -DTDC_HW_DIV64=0 -c $< -o $@
$(B)/tests/portable/test_math.o: tests/test_math.c $(GEN)/tdc_panels.h
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) -DTDC_HW_DIV64=0 -c $< -o $@
$(B)/tests/test_math_portable: $(B)/tests/portable/test_math.o $(B)/tests/portable/tdc_math.o $(TEST_SUPPORT_OBJS) $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $(filter %.o,$^) -o $@ $(SIMLIB) $(FWLIB) $(HOST_LIBS)
TESTS += $(B)/tests/test_math_portable
