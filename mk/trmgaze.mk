# Gaze-aware TRM (issue 15): the strength stage, its double reference, the
# fixed-point-vs-reference and bad-input tests, golden vectors of the on-state
# (the off-state is TRM's own vectors, unchanged).
FW_SRCS += firmware/tdc_trm_gaze.c
SIM_SRCS += ref/ref_trm_gaze.c
TESTS += $(B)/tests/unit/test_trm_gaze
GOLDEN_STAGES += trmgaze

# The TRM modes of issue 15 through tdc_sim_run (reduced50, trm50g, the
# renderer's REDUCED frames) and the temporal model's terr: links the
# simulator and the Embree renderer.
TESTS += $(B)/tests/unit/test_sim_trm_modes
$(B)/tests/unit/test_sim_trm_modes: $(B)/tests/unit/test_sim_trm_modes.o $(SIMXLIB) $(SIMLIB) $(FWLIB) $(RENDERLIB)
	$(CC) $(HOST_LDFLAGS) $(SIM_OMP) $< -o $@ $(SIMXLIB) $(RENDERLIB) $(SIMLIB) $(FWLIB) $(RENDER_LDLIBS) $(HOST_LIBS)
