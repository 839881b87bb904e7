# make bench-aarch64: what the NEON kernels (firmware/tdc_trm_neon.c) save,
# in executed instructions under qemu-aarch64 (the counting plugin of make
# bench-arm; docs/boards.md "AArch64"): per kernel on checkasm's benchmark
# inputs (tests/checkasm/insn_count.sh), and for the arm64 board program's
# whole frame loop on the htc-vive TRM stream against the same program with
# the D passes bound to C (tests/linux/a64_loop_insn.sh).  About 1 min of
# QEMU after the builds.
NEON_BENCH_PANEL := htc-vive
.PHONY: bench-aarch64
bench-aarch64:
	@$(MAKE) --no-print-directory $(INSN_PLUGIN)
	@$(A64_MAKE) $(A64)/tests/checkasm/checkasm > $(BUILD)/.a64log 2>&1 || { cat $(BUILD)/.a64log; false; }
	@echo "instructions per unit under qemu-aarch64 (gcc -O2, $(A64)/tests/checkasm/checkasm --marks)"
	@tests/checkasm/insn_count.sh aarch64-linux-gnu-nm $(INSN_PLUGIN) qemu-aarch64 $(A64)/tests/checkasm/checkasm $(or $(CHECKASM_PATTERN),neon)
	@$(MAKE) --no-print-directory -j2 BOARD=linux PANEL=$(NEON_BENCH_PANEL) CC=gcc OPT=-O2 SAN= \
	    $(BUILD)/fw-streams/$(NEON_BENCH_PANEL)-trm.tdcs > $(BUILD)/.a64log 2>&1 || { cat $(BUILD)/.a64log; false; }
	@$(A64_MAKE) BOARD=linux PANEL=$(NEON_BENCH_PANEL) $(BUILD)/linux-$(NEON_BENCH_PANEL)-arm64/tdc-board \
	    $(BUILD)/linux-$(NEON_BENCH_PANEL)-arm64/tdc-board-dpass-c > $(BUILD)/.a64log 2>&1 || { cat $(BUILD)/.a64log; false; }
	@echo "arm64 board program, whole frame loop, $(NEON_BENCH_PANEL) TRM stream (A: NEON D passes, B: C)"
	@tests/linux/a64_loop_insn.sh $(INSN_PLUGIN) $(BUILD)/linux-$(NEON_BENCH_PANEL)-arm64/tdc-board \
	    $(BUILD)/linux-$(NEON_BENCH_PANEL)-arm64/tdc-board-dpass-c $(BUILD)/fw-streams/$(NEON_BENCH_PANEL)-trm.tdcs \
	    $$(awk '$$1 == "width" { w = $$2 } $$1 == "height" { h = $$2 } $$1 == "eyes" { e = $$2 } END { print w * e * h }' \
	       boards/panels/$(NEON_BENCH_PANEL).panel)

ifeq ($(BOARD_OS),linux)
# the board program with the NEON D-pass names bound to C (linked first)
$(BP)/tdc-board-dpass-c: tests/linux/trm_dpass_c.c $$(LX_BOARD_OBJS) $$(LX_LOOP_OBJS) $(FWLIB)
	$(CC) $(FW_CFLAGS) -c $< -o $(BP)/trm_dpass_c.o
	$(CC) $(HOST_LDFLAGS) $(BP)/trm_dpass_c.o $(filter-out $<,$^) -o $@ $(LX_LIBS)
endif
