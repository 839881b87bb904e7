# Companion CPU renderer on Embree 3 (issue 6): library, tdc-render, tests, bench.
# Other components link it with: $(RENDERLIB) ... $(RENDER_LDLIBS)
DEPS_PKGS += libembree-dev
RENDER_SRCS := render/tdc_scene_parse.c render/tdc_scene_anim.c render/tdc_scene_builtin.c \
               render/tdc_render_core.c render/tdc_render_geom.c render/tdc_render_texture.c \
               render/tdc_render_trace.c render/tdc_render_frame.c render/tdc_render_stream.c \
               render/tdc_render_fov.c render/tdc_render_cones.c render/tdc_render_indirect.c
RENDER_OBJS = $(patsubst %.c,$(B)/%.o,$(RENDER_SRCS))
RENDER_LDLIBS := -lembree3

$(B)/libtdcrender.a: $(RENDER_OBJS)
	@rm -f $@
	ar rcs $@ $^

HOST_PROGS += $(TDC_RENDER)
$(TDC_RENDER): $(B)/render/tdc_render_main.o $(B)/libtdcrender.a $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $< -o $@ $(RENDERLIB) $(SIMLIB) $(FWLIB) $(RENDER_LDLIBS) $(HOST_LIBS)

RENDER_TESTS := test_render_scene test_render_mv test_render_gt test_render_stream test_render_fov test_render_cones test_render_texture
TESTS += $(foreach t,$(RENDER_TESTS),$(B)/tests/unit/$(t))
BENCHES += $(B)/tests/bench/bench_render
# test_render_hash: output hash of every built-in/mode (a tool for pixel-identical optimisations, not in TESTS)
RENDER_EXES = $(foreach t,$(RENDER_TESTS) test_render_hash,$(B)/tests/unit/$(t)) $(B)/tests/bench/bench_render
$(RENDER_EXES): $(B)/tests/%: $(B)/tests/%.o $(B)/libtdcrender.a $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $< -o $@ $(RENDERLIB) $(SIMLIB) $(FWLIB) $(RENDER_LDLIBS) $(HOST_LIBS)
