# The Linux board (boards/linux, docs/boards.md "Linux board"): the frame
# loop as a user-space program, tdc-board, behind tdc_board.h with KMS panel
# out (libdrm), a USB gadget transport (configfs + FunctionFS) and GPIO
# (libgpiod).
#   make BOARD=linux [PANEL=p]     -> build/linux-<panel>/tdc-board (static)
# The loop and the firmware are the objects of the host build of the frame
# loop (tdc_main.c and the panel-sized decoder built for this panel and these
# stages, the gcc -O2 firmware library), so the board shows the bytes the
# host double (tests/arm/tdc_board_host.c) prints; make test-vm compares them.

DEPS_PKGS += libdrm-dev libgpiod-dev
# the arm64 cross build (make linux-arm64, mk/aarch64.mk's compiler): the
# same libraries for arm64 from Debian multiarch, beside the amd64 ones
DEPS_ARCHS += arm64
DEPS_PKGS += libdrm-dev:arm64 libgpiod-dev:arm64

ifeq ($(BOARD_OS),linux)
LX_CFLAGS := -std=c11 -D_GNU_SOURCE -Wall -Wextra -Werror -Wvla -Wshadow $(OPT) -g \
             -Ifirmware -Ifirmware/board -I$(GEN) $(shell pkg-config --cflags libdrm 2>/dev/null || echo -I/usr/include/libdrm) \
             -include $(PANEL_CONFIG)
LX_LIBS := -static -ldrm -lgpiod -lpthread
# the loop's objects for this panel and these stages (mk/boards.mk fw_host_loop),
# with row workers (TDC_LX_MAX_WORKERS, tdc_board_linux.h: TRM's rows in bands
# on up to 4 threads, --threads)
$(eval $(call fw_host_loop,$(BP)/loop,$(BANDS),$(FW_CFG_BASE) -DTDC_CFG_ROW_WORKERS=4))
LX_LOOP_OBJS = $(patsubst firmware/board/%.c,$(BP)/loop/board/%.o,$(FW_LOOP_SRCS)) $(patsubst firmware/%.c,$(BP)/loop/fw/%.o,$(FWH_PANEL_SRCS))
LX_BOARD_OBJS = $(patsubst firmware/board/%.c,$(BP)/board/%.o,$(BOARD_SRCS))
$(BP)/board/%.o: firmware/board/%.c firmware/board/tdc_board_linux.h firmware/board/tdc_board.h $(PANEL_CONFIG) $(GEN)/tdc_panels.h
	@mkdir -p $(@D)
	$(CC) $(LX_CFLAGS) -MMD -MP -c $< -o $@
$(BP)/tdc-board: $$(LX_BOARD_OBJS) $$(LX_LOOP_OBJS) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ $(LX_LIBS)
	@echo "board program: $@ (panel $(PANEL), stages: $(or $(strip $(STAGES)),link only), bands $(BANDS))"
endif

# make test-vm (mk/hosttools.mk): the board for htc-vive, the host double of
# its very loop objects, and the streams it shows in the VM: TRM, foveated
# (a corrupted payload and a refused foveation header inside), banded TRM
# with a corrupted band (frame 2: that picture dropped whole, its eye kept).
# (The plain stream, 34 MB at this size, passed too but doubled the VM's
# time; its corrupted/RGB565/lost cases run on the host: test_fw_loop.sh.)
VM_DISPLAY_PANEL := htc-vive
VM_DISPLAY_MODES := trm fov trm-bands-crc
# a board whose panel (2560x1440) the VM's display (EDID up to 2160x1200)
# has no mode for: "mode not available" named
VM_NOMODE_PANEL := pg279q
ifeq ($(BOARD_OS),linux)
FW_FRAMES_trm-bands-crc := 3
.PHONY: linux-vm-inputs
linux-vm-inputs: $(BP)/tdc-board $(BP)/loop/tdc_fw_host $(foreach m,$(VM_DISPLAY_MODES),$(STREAMS)/$(PANEL)-$(m).tdcs)
endif

# make bench: the board's frame loop against the 90 Hz budget at Vive size
# (tests/linux/bench_board_rt.sh): frames/s and the share of the budget per
# part, the TRM stream on 1 thread (the baseline) and 2 (row workers) in one
# run beside the goal (real time on <= 2 cores).
BENCH_BOARD_PANEL := htc-vive
$(B)/bench-linux-board: FORCE
	@$(MAKE) --no-print-directory -j2 BOARD=linux PANEL=$(BENCH_BOARD_PANEL) CC=gcc OPT=-O2 SAN= \
	    $(BUILD)/linux-$(BENCH_BOARD_PANEL)/tdc-board $(BUILD)/gcc-O2/tests/fw_stream
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/linux/bench_board_rt.sh %s %s %s\n' $(BUILD)/linux-$(BENCH_BOARD_PANEL)/tdc-board \
	    $(BUILD)/gcc-O2/tests/fw_stream "$$(awk '$$1 == "width" { w = $$2 } $$1 == "height" { h = $$2 } \
	    $$1 == "eyes" { e = $$2 } $$1 == "refresh_hz" { r = $$2 } END { print w, h, e, r }' boards/panels/$(BENCH_BOARD_PANEL).panel)" > $@
	@chmod +x $@
BENCHES += $(B)/bench-linux-board

# make BOARD=linux install [DESTDIR=..] [PREFIX=/usr/local]: the program, its
# launcher (A/B slots with roll-back, boards/linux/tdc-board-launch) and the
# systemd unit (boards/linux/tdc-board.service; enable it with
# systemctl enable --now tdc-board).  Not run in CI (root, systemd).
PREFIX ?= /usr/local
ifeq ($(BOARD_OS),linux)
.PHONY: install
install: $(BP)/tdc-board
	install -D -m 755 $< $(DESTDIR)$(PREFIX)/bin/tdc-board
	sed 's|/usr/local/bin/tdc-board|$(PREFIX)/bin/tdc-board|' boards/linux/tdc-board-launch > $(BP)/tdc-board-launch
	install -D -m 755 $(BP)/tdc-board-launch $(DESTDIR)$(PREFIX)/bin/tdc-board-launch
	sed 's|/usr/local/bin/tdc-board|$(PREFIX)/bin/tdc-board|' boards/linux/tdc-board.service > $(BP)/tdc-board.service
	install -D -m 644 $(BP)/tdc-board.service $(DESTDIR)/etc/systemd/system/tdc-board.service
endif

# make test (TEST_EXTRA): the board program cross-built for arm64 (make
# linux-arm64) runs under qemu-aarch64 and shows the frames of the x86-64
# build, byte for byte (tests/linux/arm64_board_check.sh).  disco-dsi
# (800x480, 60 Hz) keeps qemu-user's time to ~4 s: its plain and foveated
# streams (TRM refuses a 60 Hz panel; TRM runs under qemu-aarch64 in the
# golden runner).
A64_BOARD_PANEL := disco-dsi
# (build/fw-streams: mk/boards.mk STREAMS, which a host build does not define)
A64_BOARD_STREAMS := $(BUILD)/fw-streams/$(A64_BOARD_PANEL)-plain.tdcs $(BUILD)/fw-streams/$(A64_BOARD_PANEL)-fov.tdcs
.PHONY: linux-arm64 test-linux-arm64
linux-arm64:
	@$(A64_MAKE) BOARD=linux $(BUILD)/linux-$(PANEL)-arm64/tdc-board
TEST_EXTRA += test-linux-arm64
test-linux-arm64:
	@mkdir -p $(BUILD)/linux-$(A64_BOARD_PANEL)-arm64; if $(A64_MAKE) BOARD=linux PANEL=$(A64_BOARD_PANEL) $(BUILD)/linux-$(A64_BOARD_PANEL)-arm64/tdc-board > $(BUILD)/.a64blog 2>&1 && \
	    $(MAKE) --no-print-directory -j2 BOARD=linux PANEL=$(A64_BOARD_PANEL) CC=gcc OPT=-O2 SAN= \
	        $(BUILD)/linux-$(A64_BOARD_PANEL)/tdc-board $(A64_BOARD_STREAMS) >> $(BUILD)/.a64blog 2>&1 || \
	    { cat $(BUILD)/.a64blog; false; }; then \
	    printf '#!/bin/sh\nexec tests/linux/arm64_board_check.sh %s %s %s\n' $(BUILD)/linux-$(A64_BOARD_PANEL)/tdc-board \
	        $(BUILD)/linux-$(A64_BOARD_PANEL)-arm64/tdc-board "$(A64_BOARD_STREAMS)" > $(BUILD)/linux-$(A64_BOARD_PANEL)-arm64/board-check; \
	    chmod +x $(BUILD)/linux-$(A64_BOARD_PANEL)-arm64/board-check; \
	    tests/run_tests.sh linux-arm64 $(BUILD)/linux-$(A64_BOARD_PANEL)-arm64/board-check || :; \
	else echo "[linux-arm64] FAIL build"; echo "linux-arm64 build FAIL" >> "$(RESULTS)"; fi

# make test (TEST_EXTRA: once, not per variant): the board's row workers show
# the bytes of the one-threaded loop (tests/linux/test_board_threads.sh,
# htc-vive TRM and foveated TRM streams with 2 and 3 threads against the
# host double; ~5 s of CPU after the board build the bench and test-vm share)
TEST_EXTRA += test-board-threads
.PHONY: test-board-threads
test-board-threads:
	@$(MAKE) --no-print-directory -j2 BOARD=linux PANEL=$(BENCH_BOARD_PANEL) CC=gcc OPT=-O2 SAN= \
	    $(BUILD)/linux-$(BENCH_BOARD_PANEL)/tdc-board $(BUILD)/linux-$(BENCH_BOARD_PANEL)/loop/tdc_fw_host \
	    $(BUILD)/gcc-O2/tests/fw_stream > $(BUILD)/.thrblog 2>&1 || { cat $(BUILD)/.thrblog; false; }
	@printf '#!/bin/sh\nexec tests/linux/test_board_threads.sh %s %s %s %s\n' $(BUILD)/linux-$(BENCH_BOARD_PANEL)/tdc-board \
	    $(BUILD)/linux-$(BENCH_BOARD_PANEL)/loop/tdc_fw_host $(BUILD)/gcc-O2/tests/fw_stream \
	    "$$(awk '$$1 == "width" { w = $$2 } $$1 == "height" { h = $$2 } $$1 == "eyes" { e = $$2 } \
	    END { print w, h, e }' boards/panels/$(BENCH_BOARD_PANEL).panel)" > $(BUILD)/linux-$(BENCH_BOARD_PANEL)/threads-check
	@chmod +x $(BUILD)/linux-$(BENCH_BOARD_PANEL)/threads-check
	@tests/run_tests.sh linux-threads $(BUILD)/linux-$(BENCH_BOARD_PANEL)/threads-check || :

# make test: the launcher's A/B roll-back logic with stand-in programs (~1 s;
# the real program's DFU install and confirmation run in make test-vm)
$(B)/test-board-launch: tests/linux/test_board_launch.sh boards/linux/tdc-board-launch
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/linux/test_board_launch.sh boards/linux/tdc-board-launch\n' > $@
	@chmod +x $@
TESTS += $(B)/test-board-launch
