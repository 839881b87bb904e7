# TRM (docs/design.md §4.1): the stage, its double reference, row kernels (C and AVX2),
# tests, golden vectors, benchmark.
FW_SRCS += firmware/tdc_trm.c
SIM_SRCS += ref/ref_trm.c
TESTS += $(B)/tests/unit/test_trm_ref
TESTS += $(B)/tests/unit/test_trm
TESTS += $(B)/tests/unit/test_trm_stability
TESTS += $(B)/tests/unit/test_trm_loss
GOLDEN_STAGES += trm
BENCHES += $(B)/tests/bench/bench_trm

# TRM row kernels: portable C (boards, the reference) and AVX2 (x86-64 hosts;
# the file compiles to the C kernels elsewhere).  The AVX2 object is built
# without -mgeneral-regs-only, so every firmware object's machine code is
# checked for floating-point instructions instead.
FW_SRCS += firmware/tdc_trm_rows.c firmware/tdc_trm_avx2.c
# TRM's exp(-x) weight table, generated (tdc-tablegen --trm) and included by
# tdc_trm_rows.c (FW_GEN_HEADERS: made before any firmware object, in every build folder).
$(GEN)/tdc_trm_tables.h: $(TABLEGEN) | $(GEN)
	$(TABLEGEN) --trm $@
FW_GEN_HEADERS += $(GEN)/tdc_trm_tables.h
$(B)/check-fw-rules: $(GEN)/tdc_trm_tables.h
# Helium (MVE) row kernels: compiled empty except for boards with BOARD_MVE
# (mk/boards.mk gives that object -mcpu=cortex-m55+nofp -mfloat-abi=softfp).
FW_SRCS += firmware/tdc_trm_mve.c
# AArch64 NEON D passes: compiled empty except for AArch64 (mk/aarch64.mk).
FW_SRCS += firmware/tdc_trm_neon.c
$(B)/firmware/tdc_trm_avx2.o: FW_CFLAGS := $(filter-out -mgeneral-regs-only,$(FW_CFLAGS))
ifeq ($(shell uname -m),x86_64)
$(B)/test-fw-nofloat-insn: $(FWLIB) tests/rules/check_simd_nofloat.sh
	@printf '#!/bin/sh\nexec tests/rules/check_simd_nofloat.sh objdump %s\n' "$(FW_OBJS)" > $@
	@chmod +x $@
TESTS += $(B)/test-fw-nofloat-insn
endif
# Their bit-exactness check and benchmark: tests/checkasm (mk/checkasm.mk).
