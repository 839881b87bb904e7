# checkasm (tests/checkasm/, dav1d style): every registered optimised kernel
# (today TRM's AVX2 row kernels) against its portable C reference, bit for
# bit, in `make test`; `checkasm --bench` times both in `make bench`.  The
# core (checkasm.c) is plain C with an optional timer; a stage's kernels are
# a module (checkasm_<stage>.c) listed in the core's module table.
CHECKASM := $(B)/tests/checkasm/checkasm
CHECKASM_OBJS = $(patsubst %.c,$(B)/%.o,tests/checkasm/checkasm.c tests/checkasm/checkasm_trm.c)
$(CHECKASM): $(CHECKASM_OBJS) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $(CHECKASM_OBJS) -o $@ $(FWLIB) $(HOST_LIBS)
TESTS += $(CHECKASM)
$(B)/bench-checkasm: $(CHECKASM)
	@printf '#!/bin/sh\nexec %s --bench\n' "$<" > $@
	@chmod +x $@
BENCHES += $(B)/bench-checkasm
