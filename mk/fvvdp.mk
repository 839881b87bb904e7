# FovVideoVDP, written from the paper (Mantiuk et al. 2021): the simulator's
# visual model.  See docs/visual-model.md.
#
# The metric lives in the host simulation library (its thread threshold,
# tdc_par_min_work, in the simulator's archive); its row loops run
# threaded with gcc's OpenMP (sim/tdc_par.h), so programs that link it link
# with -fopenmp too.
FVVDP_SRCS := sim/simulator/tdc_sim_jod.c sim/simulator/tdc_sim_heatmap.c sim/metrics/tdc_fvvdp.c sim/metrics/tdc_fvvdp_display.c sim/metrics/tdc_fvvdp_pyr.c \
              sim/metrics/tdc_fvvdp_temporal.c sim/metrics/tdc_fvvdp_csf.c
SIM_SRCS += $(FVVDP_SRCS)
FVVDP_OMP := $(if $(filter gcc,$(CCNAME)),-fopenmp)
FVVDP_OBJS = $(patsubst %.c,$(B)/%.o,$(FVVDP_SRCS))
$(FVVDP_OBJS): HOST_CFLAGS += $(FVVDP_OMP) $(if $(filter gcc,$(CCNAME)),-fno-trapping-math -fno-math-errno)

# The validation set (sim/metrics/validation): its generators, the tool that
# dumps its frames for the reference and prints the table, the stored
# reference numbers.
FVVDP_VAL_OBJ := $(B)/sim/metrics/validation/fvvdp_conditions.o
TDC_FVVDP_VALIDATE := $(B)/bin/tdc-fvvdp-validate
HOST_PROGS += $(TDC_FVVDP_VALIDATE)
$(TDC_FVVDP_VALIDATE): $(B)/sim/metrics/validation/fvvdp_validate.o $(FVVDP_VAL_OBJ) $$(SIMXLIB) $(SIMLIB) $(FWLIB)
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $(FVVDP_OMP) $(filter %.o,$^) -o $@ -Wl,--start-group $(SIMXLIB) $(SIMLIB) $(FWLIB) -Wl,--end-group $(HOST_LIBS)

# Running the reference beside the project: `make fvvdp-reference
# FVVDP_REF=/path/to/FovVideoVDP` rewrites the stored table.  It needs
# Debian's python3-torch and python3-scipy, deliberately not in DEPS_PKGS:
# the reference is never a build or test dependency (make test compares with
# the stored table), and torch is a large install nothing else needs.
FVVDP_REF ?=
fvvdp-reference: $(TDC_FVVDP_VALIDATE)
	@test -n "$(FVVDP_REF)" || { echo "fvvdp-reference: set FVVDP_REF to a FovVideoVDP checkout"; exit 2; }
	@/usr/bin/python3 -c 'import torch, scipy' 2>/dev/null || \
	    { echo "fvvdp-reference: needs Debian's python3-torch and python3-scipy (apt-get install python3-torch python3-scipy)"; exit 2; }
	rm -rf $(B)/fvvdp-frames
	$(TDC_FVVDP_VALIDATE) dump $(B)/fvvdp-frames
	{ echo "# FovVideoVDP reference implementation (github.com/gfxdisp/FovVideoVDP) at" \
	    "$$(git -C $(FVVDP_REF) rev-parse --short HEAD 2>/dev/null || echo '(not a git checkout)'), CPU, one torch thread"; \
	  echo "# made by: make fvvdp-reference FVVDP_REF=<checkout>; seconds: the reference's predict() wall time"; \
	  FVVDP_THREADS=1 /usr/bin/python3 sim/metrics/validation/fvvdp_reference.py $(FVVDP_REF) $(B)/fvvdp-frames; } \
	    > $(B)/fvvdp_reference.csv.tmp
	mv $(B)/fvvdp_reference.csv.tmp sim/metrics/validation/fvvdp_reference.csv
	$(TDC_FVVDP_VALIDATE) table sim/metrics/validation/fvvdp_reference.csv
.PHONY: fvvdp-reference

# Tests: the stages (exact properties) and the stored-reference comparison.
FVVDP_TESTS := test_fvvdp test_fvvdp_valid test_sim_heatmap
TESTS += $(foreach t,$(FVVDP_TESTS),$(B)/tests/unit/$(t))
$(B)/tests/unit/test_fvvdp_valid.o: HOST_CFLAGS += -DFVVDP_REFERENCE_CSV='"sim/metrics/validation/fvvdp_reference.csv"'
$(foreach t,$(FVVDP_TESTS),$(B)/tests/unit/$(t)): $(B)/tests/%: $(B)/tests/%.o $(FVVDP_VAL_OBJ) $$(SIMXLIB) $(SIMLIB) $(FWLIB)
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $(FVVDP_OMP) $(filter %.o,$^) -o $@ -Wl,--start-group $(SIMXLIB) $(SIMLIB) $(FWLIB) -Wl,--end-group $(HOST_LIBS)

# Part of `make bench-sim`: the metric's throughput against the reference's
# on the same frames (FVVDP_REF to run the reference in the same run, else
# its stored seconds), and tdc-sim's headline configuration with and without
# the judge (tests/bench/bench_fvvdp.sh).
.PHONY: bench-fvvdp
bench-fvvdp: $(TDC_FVVDP_VALIDATE) $$(TDC_SIM)
	@tests/bench/bench_fvvdp.sh $(TDC_FVVDP_VALIDATE) $(TDC_SIM) $(FVVDP_REF)
bench-sim: bench-fvvdp

# tdc-sim --jod end to end (the optimised build only: a simulator run under
# ASan would add a minute; the metric itself runs in the sanitizer build's
# unit tests).
$(B)/tests/unit/test_sim_jod: $$(TDC_SIM) tests/unit/test_sim_jod.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/unit/test_sim_jod.sh %s\n' "$(TDC_SIM)" > $@
	@chmod +x $@
ifeq ($(SAN),)
TESTS += $(B)/tests/unit/test_sim_jod
endif
