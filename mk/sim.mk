# Host simulator (issue 7): tdc-sim, eye model, metrics, panel simulation,
# reports, `make demo`.  See docs/results.md.
#
# The simulator has its own archive so that a problem in it never breaks the
# shared host library other components' tests link.

SIMX_SRCS := sim/simulator/tdc_sim_scene.c sim/simulator/tdc_sim_modes.c sim/simulator/tdc_sim_run.c \
             sim/simulator/tdc_sim_mode.c sim/simulator/tdc_sim_mode_plain.c sim/simulator/tdc_sim_mode_trm.c \
             sim/simulator/tdc_sim_mode_warp.c sim/simulator/tdc_sim_blockmatch.c sim/simulator/tdc_sim_mode_asm.c sim/simulator/tdc_sim_mode_layers.c sim/simulator/tdc_sim_stage_lcd.c \
             sim/simulator/tdc_sim_mode_fov.c sim/simulator/tdc_sim_mode_fovtrm.c sim/simulator/tdc_sim_gaze.c sim/metrics/tdc_fov_metrics.c \
             sim/simulator/tdc_sim_link.c sim/eye/tdc_eye.c sim/eye/tdc_eye_temporal.c sim/eye/tdc_retina.c \
             sim/simulator/tdc_sim_retina.c sim/simulator/tdc_sim_dump.c sim/metrics/tdc_metrics.c sim/metrics/tdc_flip.c sim/metrics/tdc_filter.c \
             sim/metrics/tdc_powtab.c \
             sim/panel/tdc_panel_sim.c sim/report/tdc_report.c sim/simulator/tdc_sim_render.c
SIMX_OBJS = $(patsubst %.c,$(B)/%.o,$(SIMX_SRCS))

HOST_PROGS += $(TDC_SIM_BIN)
DEPS_PKGS += python3-scipy # test_metrics: the flip v1.6 transcription (scipy.signal.convolve2d)
SIM_TESTS := test_sim_smoke test_sim_eye test_metrics test_eye_temporal test_sim_blockmatch test_sim_retina
TESTS += $(foreach t,$(SIM_TESTS),$(B)/tests/unit/$(t)) $(B)/test-sim-dump

# tdc-sim --dump: files, sizes, exit codes (a few seconds at 32x32)
$(B)/test-sim-dump: tests/unit/test_sim_dump.sh $(TDC_SIM)
	@printf '#!/bin/sh\nexec tests/unit/test_sim_dump.sh %s\n' "$(TDC_SIM)" > $@
	@chmod +x $@

# The simulator's own stages run threaded over rows with gcc's OpenMP
# (sim/tdc_par.h says why); other compilers build them serial.
SIM_OMP := $(if $(filter gcc,$(CCNAME)),-fopenmp)
# -fno-trapping-math: gcc 12 if-converts a select (a < b ? p : q) in a
# vector loop only when comparisons may not trap; -fno-math-errno: sqrt
# becomes the instruction, without the errno branch.  Neither changes a
# value (no reassociation, no contraction: C11 mode); they let the
# element-wise row kernels (FLIP's L*a*b* and error rows, SSIM's map row,
# the panorama samples) vectorise.  clang does not trap by default.
SIM_VEC := $(if $(filter gcc,$(CCNAME)),-fno-trapping-math -fno-math-errno)
$(SIMX_OBJS) $(B)/sim/simulator/tdc_sim_main.o: HOST_CFLAGS += $(SIM_OMP) $(SIM_VEC)

$(SIMXLIB): $(SIMX_OBJS)
	@rm -f $@; mkdir -p $(@D)
	ar rcs $@ $^

# tdc-sim links the renderer (--renderer SCENE).
$(TDC_SIM_BIN): $(B)/sim/simulator/tdc_sim_main.o $(SIMXLIB) $(SIMLIB) $(FWLIB) $(RENDERLIB)
	$(CC) $(HOST_LDFLAGS) $(SIM_OMP) $< -o $@ $(SIMXLIB) $(RENDERLIB) $(SIMLIB) $(FWLIB) $(RENDER_LDLIBS) $(HOST_LIBS)

$(foreach t,$(SIM_TESTS),$(B)/tests/unit/$(t)): $(B)/tests/%: $(B)/tests/%.o $(SIMXLIB) $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $(SIM_OMP) $^ -o $@ $(HOST_LIBS)

.PHONY: tdc-sim demo-sim
tdc-sim: $(TDC_SIM_BIN)

# `make demo`: prerequisites only (other fragments add theirs).
demo: deps demo-sim

# The default comparison on built-in scenes (< 5 minutes on 2 cores).
demo-sim: $(TDC_SIM)
	@sim/report/tdc_demo.sh $(TDC_SIM) $(or $(REPORT),report)

# `make bench-sim`: simulated pixel-refreshes/s, peak memory and the stage
# breakdown at headset scale (docs/simulator-performance.md).
.PHONY: bench-sim
bench-sim: deps $(TDC_SIM)
	@tests/bench/bench_sim.sh $(TDC_SIM)
