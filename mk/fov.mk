# Foveated streams (issue 14, docs/design.md §4.5): the display-side remap stage with
# peripheral TAA, its double-precision reference, tests, golden vectors.
# The stage's log/power/atan/Gaussian tables come from tdc-tablegen --fov.
FW_SRCS += firmware/tdc_fov.c firmware/tdc_fov_rows.c firmware/tdc_fov_lr.c firmware/tdc_fov_link.c firmware/tdc_fov_trm.c
# the tap kernel: AVX2 (x86-64 hosts; the C kernel elsewhere) and Helium (the
# C kernel except on BOARD_MVE boards); checked against C by tests/checkasm
FW_SRCS += firmware/tdc_fov_avx2.c firmware/tdc_fov_mve.c
$(B)/firmware/tdc_fov_avx2.o: FW_CFLAGS := $(filter-out -mgeneral-regs-only,$(FW_CFLAGS))
SIM_SRCS += ref/ref_fov.c ref/ref_fov_lr.c
# foveated error statistics (eccentricity weighting, FLIP's weighted median) for the simulator
FOV_METRICS_OBJ = $(B)/sim/metrics/tdc_fov_metrics.o $(B)/sim/metrics/tdc_filter.o
TESTS += $(B)/tests/unit/test_fov_metrics
$(B)/tests/unit/test_fov_metrics: $(B)/tests/unit/test_fov_metrics.o $(FOV_METRICS_OBJ)
	$(CC) $(HOST_LDFLAGS) $(SIM_OMP) $^ -o $@ $(HOST_LIBS)

$(GEN)/tdc_fov_tables.h: $(TABLEGEN) | $(GEN)
	$(TABLEGEN) --fov $@
FW_GEN_HEADERS += $(GEN)/tdc_fov_tables.h
# the recursion check compiles every firmware source on its own
$(B)/check-fw-rules: $(GEN)/tdc_fov_tables.h

# Own link rules: the fov tests need only these objects.
FOV_OBJS = $(B)/firmware/tdc_fov.o $(B)/firmware/tdc_fov_rows.o $(B)/firmware/tdc_fov_lr.o $(B)/firmware/tdc_fov_avx2.o $(B)/firmware/tdc_fov_mve.o \
           $(B)/firmware/tdc_fov_link.o $(B)/firmware/tdc_math.o $(B)/firmware/tdc_math_log2.o $(B)/ref/ref_fov.o \
           $(B)/ref/ref_fov_lr.o
FOV_TESTS := test_fov test_fov_ref test_fov_link test_fov_lr
TESTS += $(foreach t,$(FOV_TESTS),$(B)/tests/unit/$(t))
$(foreach t,$(FOV_TESTS),$(B)/tests/unit/$(t)): $(B)/tests/unit/%: $(B)/tests/unit/%.o $(FOV_OBJS)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(HOST_LIBS)
$(B)/tests/unit/test_fov.o $(B)/tests/unit/test_fov_ref.o $(B)/tests/unit/test_fov_lr.o: $(GEN)/tdc_fov_tables.h

# the FOVEATED kind in the link decoder (docs/link-protocol.md)
TESTS += $(B)/tests/unit/test_link_fov $(B)/tests/unit/test_link_fov_trm

GOLDEN_STAGES += fov

# make bench: rays and link bytes vs full rate per panel, eq. 5.1 curve, remap
# throughput vs the memcpy bound (docs/foveation.md)
BENCHES += $(B)/tests/bench/bench_fov

# Fuzzing: the target `fov` is registered in mk/fuzz.mk (tests/fuzz/fuzz_fov.c,
# seeds tests/fuzz/corpus-fov, regenerated deliberately by make fuzz-seeds-fov).
$(BUILD)/fuzz/make_seeds_fov: tests/fuzz/make_seeds_fov.c firmware/tdc_fov.c firmware/tdc_fov_rows.c firmware/tdc_fov_lr.c firmware/tdc_fov_avx2.c \
                              firmware/tdc_fov_mve.c firmware/tdc_fov_link.c firmware/tdc_math.c firmware/tdc_math_log2.c $(GEN)/tdc_fov_tables.h
	@mkdir -p $(@D)
	gcc -std=c11 -D_GNU_SOURCE -Wall -Wextra -Werror -O2 -Ifirmware -I$(GEN) $(filter %.c,$^) -o $@
fuzz-seeds-fov: $(BUILD)/fuzz/make_seeds_fov
	@mkdir -p tests/fuzz/corpus-fov
	$(BUILD)/fuzz/make_seeds_fov tests/fuzz/corpus-fov
.PHONY: fuzz-seeds-fov

# The simulator's fov modes (sim/simulator/tdc_sim_mode_fov.c, fov-trm: tdc_sim_mode_fovtrm.c), gaze schedules and tracker
TESTS += $(B)/tests/unit/test_sim_fov
$(B)/tests/unit/test_sim_fov: $(B)/tests/unit/test_sim_fov.o $$(SIMXLIB) $$(SIMLIB) $$(FWLIB)
	$(CC) $(HOST_LDFLAGS) $(SIM_OMP) $^ -o $@ $(HOST_LIBS)
