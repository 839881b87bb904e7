# AArch64, the CPU of the Linux boards (Raspberry Pi 4/5 and Zero 2,
# Rockchip, i.MX; boards/linux): a bit-exact target like the Cortex-M
# boards.  The golden vectors and checkasm cross-built with Debian's
# gcc-aarch64-linux-gnu (static: no arm64 libraries needed) and run under
# qemu-aarch64 (qemu-user) in `make test`: the same checksums as x86-64.
# checkasm there checks the NEON kernels (firmware/tdc_trm_neon.c, compiled
# into every AArch64 build) against C; `make bench-aarch64` (mk/neon.mk)
# counts their instructions per pixel under qemu-aarch64.
DEPS_PKGS += gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user

A64 := $(BUILD)/aarch64-linux-gnu-gcc-O2
A64_MAKE := $(MAKE) --no-print-directory -j2 CC=aarch64-linux-gnu-gcc OPT=-O2 SAN= \
            HOST_LIBS="-lm -lpthread" HOST_LDFLAGS=-static
TEST_EXTRA += test-aarch64
.PHONY: test-aarch64
test-aarch64:
	@if $(A64_MAKE) $(A64)/tests/tdc_golden $(A64)/tests/checkasm/checkasm > $(BUILD)/.a64log 2>&1 || \
	    { cat $(BUILD)/.a64log; false; }; then \
	    printf '#!/bin/sh\nexec tests/golden/check.sh aarch64-O2 -- qemu-aarch64 %s\n' $(A64)/tests/tdc_golden > $(A64)/golden-qemu; \
	    printf '#!/bin/sh\nexec qemu-aarch64 %s\n' $(A64)/tests/checkasm/checkasm > $(A64)/checkasm-qemu; \
	    printf '#!/bin/sh\nexec tests/rules/check_simd_nofloat.sh aarch64-linux-gnu-objdump %s\n' "$$(echo $(A64)/firmware/*.o)" > $(A64)/fw-nofloat; \
	    chmod +x $(A64)/golden-qemu $(A64)/checkasm-qemu $(A64)/fw-nofloat; \
	    tests/run_tests.sh aarch64-O2 $(A64)/golden-qemu $(A64)/checkasm-qemu $(A64)/fw-nofloat || :; \
	else echo "[aarch64-O2] FAIL build"; echo "aarch64-O2 build FAIL" >> "$(RESULTS)"; fi

