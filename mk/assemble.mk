# Tile-ordered frame assembly (issue 5): orderings, assembly, double reference,
# tests, golden vectors, benchmark, `tdc-run assemble`.
FW_SRCS += firmware/tdc_ordering.c firmware/tdc_assemble.c
SIM_SRCS += ref/ref_assemble.c

# Own link rules (only the objects these programs need), so the assembly
# tests do not depend on every other component of the libraries.
ASM_FW_OBJS = $(B)/firmware/tdc_ordering.o $(B)/firmware/tdc_assemble.o $(B)/firmware/tdc_math.o $(B)/firmware/tdc_status.o
ASM_SIM_OBJS = $(B)/ref/ref_assemble.o
ASM_TESTS := test_ordering test_assemble_ref test_assemble test_assemble_long

TESTS += $(foreach t,$(ASM_TESTS),$(B)/tests/unit/$(t))

$(foreach t,$(ASM_TESTS),$(B)/tests/unit/$(t)): $(B)/tests/%: $(B)/tests/%.o $(ASM_SIM_OBJS) $(ASM_FW_OBJS)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(HOST_LIBS)

GOLDEN_STAGES += assemble

# Benchmark: Mpixel/s at 1920x1080 vs the memcpy-bandwidth bound (make bench).
BENCHES += $(B)/tests/bench/bench_assemble
$(B)/tests/bench/bench_assemble: $(B)/tests/bench/bench_assemble.o $(ASM_SIM_OBJS) $(ASM_FW_OBJS)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(HOST_LIBS)

# tdc-run assemble (hosttools/tdcrun/run_assemble.c)
TDCRUN_SRCS += hosttools/tdcrun/run_assemble.c
# End-to-end test of `tdc-run assemble` (needs the tdc-run program).
TESTS += $(B)/tests/unit/test_assemble_tdcrun
$(B)/tests/unit/test_assemble_tdcrun.o: HOST_CFLAGS += -DTDC_RUN_PATH='"$(B)/bin/tdc-run"'
$(B)/tests/unit/test_assemble_tdcrun: $(B)/tests/unit/test_assemble_tdcrun.o $(ASM_SIM_OBJS) $(ASM_FW_OBJS) $(B)/common/tdc_png.o | $(B)/bin/tdc-run
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(HOST_LIBS)
