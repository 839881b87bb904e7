# checkasm (tests/checkasm/, dav1d style): every registered optimised kernel
# (today TRM's AVX2 row kernels) against its portable C reference, bit for
# bit, in `make test`; `checkasm --bench` times both in `make bench`.  The
# core (checkasm.c) is plain C with an optional timer; a stage's kernels are
# a module (checkasm_<stage>.c) listed in the core's module table.
CHECKASM := $(B)/tests/checkasm/checkasm
CHECKASM_OBJS = $(patsubst %.c,$(B)/%.o,tests/checkasm/checkasm.c tests/checkasm/checkasm_trm.c tests/checkasm/checkasm_lcd.c tests/checkasm/checkasm_fov.c)
$(CHECKASM): $(CHECKASM_OBJS) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $(CHECKASM_OBJS) -o $@ $(FWLIB) $(HOST_LIBS)
TESTS += $(CHECKASM)
$(B)/bench-checkasm: $(CHECKASM)
	@printf '#!/bin/sh\nexec %s --bench\n' "$<" > $@
	@chmod +x $@
BENCHES += $(B)/bench-checkasm

# The core and the modules must stay buildable for every Cortex-M target:
# compile them for M7 and M55 with the firmware's warnings as errors (the
# M55 also runs them in QEMU with its Helium kernels: checkasm-mve in
# mk/boards.mk).
$(B)/test-checkasm-arm-build: tests/checkasm/checkasm.c tests/checkasm/checkasm_trm.c tests/checkasm/checkasm_lcd.c tests/checkasm/checkasm_fov.c tests/checkasm/checkasm.h $(GEN)/tdc_panels.h
	@printf '#!/bin/sh\nset -e\nd=$$(mktemp -d); trap "rm -rf $$d" EXIT\nfor cpu in cortex-m7 cortex-m55; do for f in tests/checkasm/checkasm.c tests/checkasm/checkasm_trm.c tests/checkasm/checkasm_lcd.c tests/checkasm/checkasm_fov.c; do\n  %s -mcpu=$$cpu -mthumb -O2 -std=c11 -Wall -Wextra -Werror -Wvla -DCHECKASM_NO_MAIN -Ifirmware -Ifirmware/board -I%s -c $$f -o $$d/o.o\ndone; echo "checkasm: core, TRM, LCD and fov modules compile for $$cpu"; done\n' "$(ARM_CC)" "$(GEN)" > $@
	@chmod +x $@
TESTS += $(B)/test-checkasm-arm-build
