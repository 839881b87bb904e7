# Layered tile assembly (issue 16): the stage, its double reference, the
# layered test stream, tests, golden vectors, benchmark.  The link kind is in
# mk/link.mk (firmware/tdc_layer_link.c).
FW_SRCS += firmware/tdc_layers.c
SIM_SRCS += ref/ref_layers.c
GOLDEN_COMMON += tests/golden/tdc_layer_content.c
GOLDEN_STAGES += layers

LASM_TESTS := test_layers test_layers_ref
TESTS += $(foreach t,$(LASM_TESTS),$(B)/tests/unit/$(t))
$(foreach t,$(LASM_TESTS),$(B)/tests/unit/$(t)): $(B)/tests/unit/%: $(B)/tests/unit/%.o \
        $(B)/tests/golden/tdc_layer_content.o $(B)/tests/golden/tdc_content.o $(B)/tests/golden/golden_common.o $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(SIMLIB) $(FWLIB) $(HOST_LIBS)

BENCHES += $(B)/tests/bench/bench_layers
$(B)/tests/bench/bench_layers: $(B)/tests/bench/bench_layers.o $(B)/tests/golden/tdc_layer_content.o $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(SIMLIB) $(FWLIB) $(HOST_LIBS)

# The layered modes on the Embree renderer's glossy floor and the simulator's
# renderer seed (tdc-sim -S) through tdc_sim_run (after mk/sim.mk's libraries).
TESTS += $(B)/tests/unit/test_sim_layers_render
$(B)/tests/unit/test_sim_layers_render: $(B)/tests/unit/test_sim_layers_render.o $$(SIMXLIB) $(SIMLIB) $(FWLIB) $(RENDERLIB)
	$(CC) $(HOST_LDFLAGS) $(SIM_OMP) $< -o $@ $(SIMXLIB) $(RENDERLIB) $(SIMLIB) $(FWLIB) $(RENDER_LDLIBS) $(HOST_LIBS)
