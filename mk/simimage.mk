# Photographs as simulator content (issue 13 item 5): tdc-sim --image FILE,
# PNG (libpng) and JPEG (libjpeg), exact area-sampled ground truth.  The demo
# uses the photographs of Debian's mate-backgrounds package.
SIMIMG_OBJS = $(patsubst %.c,$(B)/%.o,sim/image/tdc_image_read.c sim/image/tdc_image_source.c)
# into the simulator archive (its rule takes every prerequisite: ar rcs $@ $^)
$(SIMXLIB): $(SIMIMG_OBJS)
HOST_LIBS += -ljpeg
DEPS_PKGS += libjpeg62-turbo-dev mate-backgrounds time
DEMO_PHOTOS := /usr/share/backgrounds/mate/nature

TESTS += $(B)/tests/unit/test_image_source $(B)/test-sim-image
$(B)/tests/unit/test_image_source: $(B)/tests/unit/test_image_source.o $(SIMXLIB) $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(HOST_LIBS)
$(B)/test-sim-image: tests/unit/test_sim_image.sh $(TDC_SIM)
	@printf '#!/bin/sh\nexec tests/unit/test_sim_image.sh %s %s\n' "$(TDC_SIM)" "$(DEMO_PHOTOS)" > $@
	@chmod +x $@
