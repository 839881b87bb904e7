# Zeng et al. (temporally reliable motion vectors) evaluated as the paper
# does: the double-precision reference pipeline and its analytic scenes
# (sim/zeng/README.md), tdc-zeng, its unit test, and the experiment group
# sim/experiments/zeng-reliable (which runs tdc-zeng itself).
ZENG_SRCS := sim/zeng/zeng_scene.c sim/zeng/zeng_filter.c sim/zeng/zeng_pipe.c sim/zeng/zeng_eval.c
ZENG_OBJS = $(patsubst %.c,$(B)/%.o,$(ZENG_SRCS))
TDC_ZENG := $(B)/tdc-zeng
HOST_PROGS += $(TDC_ZENG)

# the ground truth (1024 rays a pixel) runs threaded over rows
$(ZENG_OBJS): HOST_CFLAGS += $(SIM_OMP)
# --jod: FovVideoVDP from the host library, whose loop threshold
# (tdc_par_min_work) lives in tdc_filter.o
$(TDC_ZENG): $(B)/sim/zeng/zeng_main.o $(ZENG_OBJS) $$(ZENG_METRICS) $(SIMLIB)
	$(CC) $(HOST_LDFLAGS) $(SIM_OMP) $^ -o $@ $(HOST_LIBS)

TESTS += $(B)/tests/unit/test_zeng
# tdc_ssim from the simulator's metrics (the SSIM map is checked against it)
ZENG_METRICS = $(B)/sim/metrics/tdc_metrics.o $(B)/sim/metrics/tdc_filter.o $(B)/sim/metrics/tdc_powtab.o
$(B)/tests/unit/test_zeng: $(B)/tests/unit/test_zeng.o $(ZENG_OBJS) $$(ZENG_METRICS) $(SIMLIB)
	$(CC) $(HOST_LDFLAGS) $(SIM_OMP) $^ -o $@ $(HOST_LIBS)

experiments demo-experiments experiments-report: $(TDC_ZENG)
experiments demo-experiments experiments-report: export TDC_ZENG := $(abspath $(TDC_ZENG))
.PHONY: tdc-zeng
tdc-zeng: $(TDC_ZENG)

# The controller's side: exponential history per layer (eq. 2/4) in fixed
# point, its double reference, the reference test, golden vectors.
FW_SRCS += firmware/tdc_layer_hist.c
SIM_SRCS += ref/ref_layer_hist.c
GOLDEN_STAGES += lhist
TESTS += $(B)/tests/unit/test_layer_hist
$(B)/tests/unit/test_layer_hist: $(B)/tests/unit/test_layer_hist.o $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(HOST_LIBS)
BENCHES += $(B)/tests/bench/bench_layer_hist
$(B)/tests/bench/bench_layer_hist: $(B)/tests/bench/bench_layer_hist.o $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(HOST_LIBS)
$(B)/test-zeng-cli: tests/unit/test_zeng_cli.sh $(TDC_ZENG)
	@printf '#!/bin/sh\nexec tests/unit/test_zeng_cli.sh %s\n' "$(TDC_ZENG)" > $@
	@chmod +x $@
TESTS += $(B)/test-zeng-cli
