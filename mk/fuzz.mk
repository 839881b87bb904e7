# Fuzzing (docs/fuzzing.md): libFuzzer + ASan + UBSan, clang 14.  One
# target per parser, each with its seed corpus in tests/fuzz/corpus-<name>
# (the link decoder's: tests/fuzz/corpus).
#   make fuzz FUZZ_SECONDS=600     every target for FUZZ_SECONDS each (FUZZ_TARGETS to choose),
#                                  new inputs kept in build/fuzz/corpus-<name>
#   make fuzz-smoke                every target for FUZZ_SMOKE_SECONDS each, part of make test
#   make fuzz-seeds                regenerate the link decoder's tests/fuzz/corpus (deliberately)
# ---------------------------------------------------------------------------
FUZZ_CC ?= clang
FUZZ_SECONDS ?= 600
FUZZ_SMOKE_SECONDS ?= 8
FUZZ_DIR := $(BUILD)/fuzz
FUZZ_FLAGS := -std=c11 -D_GNU_SOURCE -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
              -fsanitize-coverage-ignorelist=tests/fuzz/nocov.txt \
              -Ifirmware -I$(GEN) -Isim -Iref -Icommon
# the link decoder and what it calls (FOVEATED packets: the foveation header and geometry)
LINK_FW_SRCS := firmware/tdc_wire.c firmware/tdc_link.c firmware/tdc_pixfmt.c firmware/tdc_crc32.c firmware/tdc_layer_link.c \
                firmware/tdc_band_link.c \
                firmware/tdc_fov.c firmware/tdc_fov_rows.c firmware/tdc_fov_lr.c firmware/tdc_fov_avx2.c firmware/tdc_fov_mve.c firmware/tdc_fov_link.c \
                firmware/tdc_math.c firmware/tdc_math_log2.c

# name: harness + sources [+ flags, libraries]
FUZZ_ALL := link usbproto usbreply panel tdcs scene frameloop meas fov layers bands
FUZZ_TARGETS ?= $(FUZZ_ALL)
FUZZ_SRCS_link := tests/fuzz/fuzz_link.c $(LINK_FW_SRCS)
FUZZ_SRCS_usbproto := tests/fuzz/fuzz_usbproto.c firmware/tdc_usbproto.c firmware/tdc_crc32.c
FUZZ_SRCS_usbreply := tests/fuzz/fuzz_usbreply.c hosttools/usb/tdc_usb_reply.c
FUZZ_CFLAGS_usbreply := -Ihosttools/usb
FUZZ_SRCS_panel := tests/fuzz/fuzz_panel.c common/tdc_tool.c
FUZZ_DEPS_panel := hosttools/tablegen/tdc_tablegen.c
FUZZ_LIBS_panel := -lm
# the .tdcs reader with a small compiled maximum (a 96 x 64 board)
FUZZ_SRCS_tdcs := tests/fuzz/fuzz_tdcs.c common/tdc_link_file.c firmware/tdc_link_encode.c $(LINK_FW_SRCS)
FUZZ_CFLAGS_tdcs := -DTDC_PANEL_WIDTH=96 -DTDC_PANEL_HEIGHT=64
FUZZ_SRCS_scene := tests/fuzz/fuzz_scene.c render/tdc_scene_parse.c common/tdc_tool.c
FUZZ_DEPS_scene := render/tdc_render_geom.c
FUZZ_CFLAGS_scene := -Irender
FUZZ_LIBS_scene := -lembree3 -lm
# the board frame loop for a 16 x 8 stereo OLED panel with TRM, tile assembly and foveation (with TAA), built as on a board:
# without the x86 AVX2 kernels (TDC_NO_SIMD), whose encode index TRM built at every stream start
# (22 % of each execution; the kernels are checked against C by checkasm)
FUZZ_SRCS_frameloop := tests/fuzz/fuzz_frameloop.c tests/arm/tdc_board_stub.c $(FW_LOOP_SRCS) $(LINK_FW_SRCS) \
                       firmware/tdc_trm_rows.c firmware/tdc_trm_avx2.c \
                       $(GEN)/tdc_panel_htc-vive.c firmware/tdc_link_encode.c firmware/tdc_fov_trm.c
FUZZ_DEPS_frameloop := $(wildcard firmware/board/*.h)
FUZZ_CFLAGS_frameloop := -Ifirmware/board -DTDC_PANEL_NAME='"fuzz"' -DTDC_PANEL_SYMBOL=tdc_panel_htc_vive \
    -DTDC_PANEL_WIDTH=16 -DTDC_PANEL_HEIGHT=8 -DTDC_PANEL_EYES=2 -DTDC_PANEL_BITS=8 -DTDC_PANEL_REFRESH_HZ=90 \
    -DTDC_PANEL_IS_LCD=0 -DTDC_CFG_TRM=1 -DTDC_CFG_ASSEMBLE=1 -DTDC_CFG_FOV=1 -DTDC_FW_NO_MAIN -DTDC_NO_SIMD
FUZZ_CORPUS_link := tests/fuzz/corpus
# the LCD measurement reader and the transition fit's checks (hosttools/calib)
FUZZ_SRCS_meas := tests/fuzz/fuzz_meas.c common/tdc_meas.c \
                  common/tdc_tool.c
FUZZ_LIBS_meas := -lm
# the foveated packet's kind-specific path: header, payload length, unpack, the stage with TAA
# (seeds: make fuzz-seeds-fov, mk/fov.mk)
FUZZ_SRCS_fov := tests/fuzz/fuzz_fov.c firmware/tdc_fov_link.c firmware/tdc_math.c firmware/tdc_math_log2.c
FUZZ_DEPS_fov := $(GEN)/tdc_fov_tables.h
# the layered subframe kind through the decoder (seeds: tests/fuzz/corpus-layers)
FUZZ_SRCS_layers := tests/fuzz/fuzz_layers.c $(LINK_FW_SRCS) firmware/tdc_link_encode.c
# the row-band mode through the decoder, with a model of each eye's picture in flight (seeds: tests/fuzz/corpus-bands)
FUZZ_SRCS_bands := tests/fuzz/fuzz_bands.c $(LINK_FW_SRCS) firmware/tdc_link_encode.c

# FUZZ_NOCMP_<name>: sources of the target that are numeric stages, not parsers,
# compiled without comparison tracing (-fno-sanitize-coverage=trace-cmp): they
# keep their edge counters (libFuzzer still sees which paths of the stage an
# input takes), AddressSanitizer and UBSan, but their per-pixel / per-sample
# compares no longer feed libFuzzer's value profile, which measured 40-70 % of
# an execution and solves no magic value (fuzz_fov, session 6, idle core:
# 2,360 -> 10,376 exec/s, and more coverage in the same 25 s: 228 edges / 713
# features against 226 / 654).  tests/fuzz/nocov.txt removes a file's
# coverage altogether; this keeps the edges.
FUZZ_NOCMP_fov := firmware/tdc_fov.c firmware/tdc_fov_rows.c firmware/tdc_fov_lr.c firmware/tdc_fov_avx2.c firmware/tdc_fov_mve.c
FUZZ_NOCMP_meas := hosttools/calib/tdc_calib_trans.c
FUZZ_NOCMP_frameloop := firmware/tdc_trm.c firmware/tdc_assemble.c firmware/tdc_ordering.c firmware/tdc_trm_gaze.c

define fuzz_target
$(FUZZ_DIR)/fuzz_$(1): $(FUZZ_SRCS_$(1)) $(FUZZ_NOCMP_$(1)) $(FUZZ_DEPS_$(1)) $(wildcard firmware/*.h sim/link/*.h render/*.h) \
                       $(GEN)/tdc_crc32_tables.h $(GEN)/tdc_fov_tables.h $(GEN)/tdc_trm_tables.h $(GEN)/tdc_panels.h \
                       tests/fuzz/nocov.txt
	@mkdir -p $$(@D)/obj-$(1)
	@for f in $(FUZZ_NOCMP_$(1)); do o=$$(@D)/obj-$(1)/$$$$(basename $$$$f .c).o; echo "$(FUZZ_CC) ... -fno-sanitize-coverage=trace-cmp -c $$$$f"; \
	    $(FUZZ_CC) $(FUZZ_FLAGS) $(FUZZ_CFLAGS_$(1)) -fno-sanitize-coverage=trace-cmp -c $$$$f -o $$$$o || exit 1; done
	$(FUZZ_CC) $(FUZZ_FLAGS) $(FUZZ_CFLAGS_$(1)) $(FUZZ_SRCS_$(1)) \
	    $(foreach f,$(FUZZ_NOCMP_$(1)),$$(@D)/obj-$(1)/$(basename $(notdir $(f))).o) -o $$@ $(FUZZ_LIBS_$(1))
$(FUZZ_DIR)/fuzz-smoke-$(1): $(FUZZ_DIR)/fuzz_$(1) tests/fuzz/smoke.sh mk/fuzz.mk
	@printf '#!/bin/sh\n%s exec tests/fuzz/smoke.sh "%s" "%s" "%s" "%s"\n' "$(FUZZ_SMOKE_ENV_$(1))" "$(FUZZ_DIR)/fuzz_$(1)" "$(FUZZ_SMOKE_SECONDS)" \
	    "$(abspath $(FUZZ_DIR))/artifacts-$(1)" "$(or $(FUZZ_CORPUS_$(1)),tests/fuzz/corpus-$(1))" > $$@
	@chmod +x $$@
endef
$(foreach t,$(FUZZ_ALL),$(eval $(call fuzz_target,$(t))))

.PHONY: fuzz fuzz-smoke fuzz-seeds
fuzz: $(foreach t,$(FUZZ_TARGETS),$(FUZZ_DIR)/fuzz_$(t))
	@for t in $(FUZZ_TARGETS); do \
	    c=tests/fuzz/corpus-$$t; [ $$t = link ] && c=tests/fuzz/corpus; \
	    mkdir -p $(FUZZ_DIR)/corpus-$$t $(FUZZ_DIR)/artifacts-$$t; echo "== fuzz $$t ($(FUZZ_SECONDS) s)"; \
	    $(FUZZ_DIR)/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -timeout=10 -close_fd_mask=2 -print_final_stats=1 \
	        -artifact_prefix=$(FUZZ_DIR)/artifacts-$$t/ $(FUZZ_DIR)/corpus-$$t $$c 2>&1 | \
	        grep -E '^(stat::|SUMMARY|==[0-9]+==|Done )|ERROR|crash-|leak|INITED|DONE' || true; \
	done

# Regression: every finding of a target (tests/fuzz/findings/<target>-*) replayed
# through its harness, which must not abort (F1: frameloop-kept-eye-overwritten*).
FUZZ_FINDING_TARGETS := $(sort $(foreach f,$(wildcard tests/fuzz/findings/*),$(firstword $(subst -, ,$(notdir $(f))))))
$(FUZZ_DIR)/fuzz-findings-%: $(FUZZ_DIR)/fuzz_% mk/fuzz.mk $(wildcard tests/fuzz/findings/*)
	@printf '#!/bin/sh\nexec %s -runs=1 %s\n' "$<" "$(wildcard tests/fuzz/findings/$*-*)" > $@
	@chmod +x $@

fuzz-smoke: $(foreach t,$(FUZZ_ALL),$(FUZZ_DIR)/fuzz-smoke-$(t)) $(foreach t,$(FUZZ_FINDING_TARGETS),$(FUZZ_DIR)/fuzz-findings-$(t))
	@tests/run_tests.sh "clang-fuzz" $^

FUZZ_SEEDS_BIN := $(FUZZ_DIR)/make_seeds
$(FUZZ_SEEDS_BIN): tests/fuzz/make_seeds.c sim/link/tdc_link_gen.c firmware/tdc_link_encode.c $(LINK_FW_SRCS) $(GEN)/tdc_crc32_tables.h \
                   $(GEN)/tdc_fov_tables.h
	@mkdir -p $(@D)
	gcc -std=c11 -D_GNU_SOURCE -Wall -Wextra -Werror -O2 -Ifirmware -Isim -Iref -I$(GEN) $(filter %.c,$^) -o $@
fuzz-seeds: $(FUZZ_SEEDS_BIN)
	@mkdir -p tests/fuzz/corpus
	$(FUZZ_SEEDS_BIN) tests/fuzz/corpus
	@ls tests/fuzz/corpus | wc -l

# Beside the extra targets (in the background): its 11 fuzzers run one after
# another for 8 s each after a clang build of its own (build/fuzz; the shared
# $(GEN) headers are made by the first run-tests), ~170 s of one core that
# sat on the serial line of QEMU runs.
TEST_BESIDE += fuzz-smoke
