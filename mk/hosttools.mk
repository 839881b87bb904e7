# Host tools (issue 9): tdc-usb (libusb-1.0), tdc-gpio (libgpiod 1.6), the
# board side of the USB protocol, and their tests against emulated devices.
# Docs: docs/usb-protocol.md, docs/hosttools.md.

DEPS_PKGS += libusb-1.0-0-dev libgpiod-dev gpiod umockdev libumockdev-dev libglib2.0-dev dfu-util usbutils

FW_SRCS += firmware/tdc_usbproto.c

LIBUSB_CFLAGS := $(shell pkg-config --cflags libusb-1.0 2>/dev/null)
LIBUSB_LIBS := $(or $(shell pkg-config --libs libusb-1.0 2>/dev/null),-lusb-1.0)
UMOCKDEV_CFLAGS := $(shell pkg-config --cflags umockdev-1.0 2>/dev/null)
UMOCKDEV_LIBS := $(or $(shell pkg-config --libs umockdev-1.0 glib-2.0 gobject-2.0 2>/dev/null),-lumockdev -lgobject-2.0 -lglib-2.0)
GPIOD_LIBS := $(or $(shell pkg-config --libs libgpiod 2>/dev/null),-lgpiod)

TDC_USB := $(B)/bin/tdc-usb
TDC_GPIO := $(B)/bin/tdc-gpio
HOST_PROGS += $(TDC_USB) $(TDC_GPIO)

# Pattern-specific flags: only the objects that include libusb/umockdev headers.
$(B)/hosttools/usb/%.o: HOST_CFLAGS += $(LIBUSB_CFLAGS)
$(B)/tests/usb/%.o: HOST_CFLAGS += $(UMOCKDEV_CFLAGS) -DTDC_USB_BIN='"$(abspath $(TDC_USB))"'

TDC_USB_OBJS = $(B)/hosttools/usb/tdc_usb.o $(B)/hosttools/usb/tdc_usb_dev.o $(B)/hosttools/usb/tdc_usb_dfu.o \
               $(B)/hosttools/usb/tdc_usb_reply.o \
               $(B)/common/tdc_tool.o
$(TDC_USB): $(TDC_USB_OBJS) $(FWLIB)
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $(TDC_USB_OBJS) -o $@ $(FWLIB) $(LIBUSB_LIBS)

TDC_GPIO_OBJS = $(B)/hosttools/gpio/tdc_gpio.o $(B)/hosttools/gpio/tdc_gpio_chip.o \
                $(B)/hosttools/gpio/tdc_vsync_stats.o $(B)/common/tdc_tool.o
$(TDC_GPIO): $(TDC_GPIO_OBJS)
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $(TDC_GPIO_OBJS) -o $@ $(GPIOD_LIBS) -lm

# The protocol state machine request by request (pattern rule build).
TESTS += $(B)/tests/usb/test_usbproto

# umockdev tests: the emulated board plus the real tdc-usb binary.
USB_EMUL_OBJS = $(B)/tests/usb/tdc_usb_run.o $(B)/tests/usb/tdc_usb_emul.o $(B)/tests/usb/tdc_link_sink.o
$(B)/tests/usb/test_usb_emul: $(B)/tests/usb/test_usb_emul.o $(USB_EMUL_OBJS) $(SIMLIB) $(FWLIB) $(TDC_USB)
	$(CC) $(HOST_LDFLAGS) $< $(USB_EMUL_OBJS) -o $@ $(SIMLIB) $(FWLIB) $(UMOCKDEV_LIBS) -lcmocka -lpthread -lm
TESTS += $(B)/tests/usb/test_usb_emul
# Debian's dfu-util and lsusb (independent clients) against the same boards.
$(B)/tests/usb/test_usb_clients: $(B)/tests/usb/test_usb_clients.o $(USB_EMUL_OBJS) $(SIMLIB) $(FWLIB) $(TDC_USB)
	$(CC) $(HOST_LDFLAGS) $< $(USB_EMUL_OBJS) -o $@ $(SIMLIB) $(FWLIB) $(UMOCKDEV_LIBS) -lcmocka -lpthread -lm
TESTS += $(B)/tests/usb/test_usb_clients

# tdc-usb's parsing of board replies (pure code, also fuzzed: tests/fuzz/fuzz_usbreply.c).
$(B)/tests/usb/test_usb_reply: $(B)/tests/usb/test_usb_reply.o $(B)/hosttools/usb/tdc_usb_reply.o
	$(CC) $(HOST_LDFLAGS) $^ -o $@ -lcmocka
$(B)/tests/usb/test_usb_reply.o: HOST_CFLAGS += -Ihosttools/usb
TESTS += $(B)/tests/usb/test_usb_reply

# The vsync statistics (pure code) and tdc-gpio's error paths without a chip.
$(B)/tests/usb/test_gpio_vsync: $(B)/tests/usb/test_gpio_vsync.o $(B)/hosttools/gpio/tdc_vsync_stats.o $(TDC_GPIO)
	$(CC) $(HOST_LDFLAGS) $(B)/tests/usb/test_gpio_vsync.o $(B)/hosttools/gpio/tdc_vsync_stats.o -o $@ -lcmocka -lm
$(B)/tests/usb/test_gpio_vsync.o: HOST_CFLAGS += -Ihosttools/gpio -DTDC_GPIO_BIN='"$(abspath $(TDC_GPIO))"'
TESTS += $(B)/tests/usb/test_gpio_vsync

# ---------------------------------------------------------------------------
# make test-vm: the real kernel stacks (tests/vm/run-vm.sh, tests/vm/README.md).
# Always the gcc -O2 tools; the gadget board and the vsync generator are
# static (the initramfs has no libc of its own for them).
# ---------------------------------------------------------------------------
DEPS_PKGS += qemu-system-x86 busybox-static linux-image-amd64 linux-headers-amd64 linux-source cpio kmod
VM_BIN := $(BUILD)/gcc-O2/bin
VM_BOARD_SRCS := tests/vm/tdc_ffs_board.c firmware/board/tdc_ffs.c tests/usb/tdc_link_sink.c firmware/tdc_usbproto.c $(LINK_FW_SRCS)
$(VM_BIN)/tdc_ffs_board: $(VM_BOARD_SRCS) $(wildcard firmware/*.h) firmware/board/tdc_ffs.h $(GEN)/tdc_crc32_tables.h $(GEN)/tdc_fov_tables.h
	@mkdir -p $(@D)
	gcc -std=c11 -D_GNU_SOURCE -Wall -Wextra -Werror -O2 -Ifirmware -Ifirmware/board -I$(GEN) -Itests/usb -static \
	    $(VM_BOARD_SRCS) -o $@ -lpthread
# The .tdcs streams the VM sends, from the link generator (host program).
$(VM_BIN)/tdc_vm_mkstream: $(B)/tests/vm/tdc_vm_mkstream.o $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $< -o $@ $(SIMLIB) $(FWLIB) -lm
$(VM_BIN)/tdc_vsync_gen: tests/vm/tdc_vsync_gen.c
	@mkdir -p $(@D)
	gcc -std=c11 -D_GNU_SOURCE -Wall -Wextra -Werror -O2 -static $< -o $@

# In `make test`: 5 of 5 and then (with the link-decoder checks) 4 of 4
# consecutive runs passed on a 2-core host at load average 6-9.6 (other
# builds running), 44-64 s each (+ ~20 s the first time for the gpio-sim
# module).  TCG only: it does not depend on KVM.  At load average 15-23 (six
# engineers) a run takes 425-1305 s: every wait in init.sh is on an event with
# a generous bound (docs/boards.md "In `make test-vm`").
TEST_EXTRA += test-vm
.PHONY: test-vm
test-vm:
	@$(MAKE) --no-print-directory CC=gcc OPT=-O2 SAN= $(VM_BIN)/tdc-usb $(VM_BIN)/tdc-gpio \
	    $(VM_BIN)/tdc_ffs_board $(VM_BIN)/tdc_vsync_gen $(VM_BIN)/tdc_vm_mkstream
	@$(MAKE) --no-print-directory -j2 BOARD=linux PANEL=$(VM_DISPLAY_PANEL) CC=gcc OPT=-O2 SAN= linux-vm-inputs
	@$(MAKE) --no-print-directory -j2 BOARD=linux PANEL=$(VM_NOMODE_PANEL) CC=gcc OPT=-O2 SAN= \
	    $(BUILD)/linux-$(VM_NOMODE_PANEL)/tdc-board
	@if tests/vm/run-vm.sh $(VM_BIN) $(BUILD)/vm $(BUILD)/linux-$(VM_DISPLAY_PANEL)/tdc-board \
	        $(BUILD)/linux-$(VM_DISPLAY_PANEL)/loop/tdc_fw_host \
	        $$(awk '$$1 == "width" { w = $$2 } $$1 == "height" { h = $$2 } $$1 == "eyes" { e = $$2 } \
	               $$1 == "refresh_hz" { r = $$2 } END { print w * e, h, r }' boards/panels/$(VM_DISPLAY_PANEL).panel) \
	        $(BUILD)/linux-$(VM_NOMODE_PANEL)/tdc-board \
	        $(foreach m,$(VM_DISPLAY_MODES),$(m)=$(BUILD)/fw-streams/$(VM_DISPLAY_PANEL)-$(m).tdcs); then r=PASS; else r=FAIL; fi; \
	    echo "[vm] $$r test-vm"; [ -z "$$RESULTS" ] || echo "vm test-vm $$r" >> "$$RESULTS"; \
	    [ $$r = PASS ]
