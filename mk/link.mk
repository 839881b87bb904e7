# Link protocol (docs/link-protocol.md): firmware decoder, CRC-32, pixel
# formats; host encoder and .tdcs stream files; tests, golden, fuzz, bench.

# CRC-32 tables generated at build time (never typed by hand).
CRC32_GEN := $(BUILD)/tools/tdc-crc32-gen
$(CRC32_GEN): sim/link/tdc_crc32_gen.c | $(BUILD)/tools
	gcc -std=c11 -Wall -Wextra -Werror -O2 $< -o $@
$(GEN)/tdc_crc32_tables.h: $(CRC32_GEN) | $(GEN)
	$(CRC32_GEN) $@
# Every firmware object already depends on tdc_panels.h; ordering the table
# before it makes the header exist for any build rule (host or board).
$(GEN)/tdc_panels.h: | $(GEN)/tdc_crc32_tables.h
$(B)/firmware/tdc_crc32.o: $(GEN)/tdc_crc32_tables.h

FW_SRCS += firmware/tdc_crc32.c firmware/tdc_pixfmt.c firmware/tdc_link.c
SIM_SRCS += sim/link/tdc_link_encode.c sim/link/tdc_link_file.c sim/link/tdc_pixfmt_ref.c sim/link/tdc_link_gen.c

# ---------------------------------------------------------------------------
# Fuzzing (docs/fuzzing.md): libFuzzer + ASan + UBSan, clang 14.
#   make fuzz FUZZ_SECONDS=600     long run, new inputs kept in build/fuzz/corpus
#   make fuzz-smoke                bounded run (FUZZ_SMOKE_SECONDS, >= 30 s), part of make test
#   make fuzz-seeds                regenerate tests/fuzz/corpus (deliberately)
# ---------------------------------------------------------------------------
FUZZ_CC ?= clang
FUZZ_SECONDS ?= 600
FUZZ_SMOKE_SECONDS ?= 35
FUZZ_DIR := $(BUILD)/fuzz
FUZZ_BIN := $(FUZZ_DIR)/fuzz_link
LINK_FW_SRCS := firmware/tdc_link.c firmware/tdc_pixfmt.c firmware/tdc_crc32.c

$(FUZZ_BIN): tests/fuzz/fuzz_link.c $(LINK_FW_SRCS) $(wildcard firmware/tdc_link.h firmware/tdc_pixfmt.h firmware/tdc_crc32.h) $(GEN)/tdc_crc32_tables.h
	@mkdir -p $(@D)
	$(FUZZ_CC) -std=c11 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
	    -Ifirmware -I$(GEN) tests/fuzz/fuzz_link.c $(LINK_FW_SRCS) -o $@

.PHONY: fuzz fuzz-smoke fuzz-seeds
fuzz: $(FUZZ_BIN)
	@mkdir -p $(FUZZ_DIR)/corpus $(FUZZ_DIR)/artifacts
	$(FUZZ_BIN) -max_total_time=$(FUZZ_SECONDS) -timeout=10 -print_final_stats=1 \
	    -artifact_prefix=$(FUZZ_DIR)/artifacts/ $(FUZZ_DIR)/corpus tests/fuzz/corpus

$(FUZZ_DIR)/fuzz-smoke: $(FUZZ_BIN) tests/fuzz/smoke.sh mk/link.mk
	@printf '#!/bin/sh\nexec tests/fuzz/smoke.sh "%s" "%s" "%s"\n' "$(FUZZ_BIN)" "$(FUZZ_SMOKE_SECONDS)" "$(abspath $(FUZZ_DIR))/artifacts" > $@
	@chmod +x $@

fuzz-smoke: $(FUZZ_DIR)/fuzz-smoke
	@tests/run_tests.sh "clang-fuzz" $(FUZZ_DIR)/fuzz-smoke

FUZZ_SEEDS_BIN := $(FUZZ_DIR)/make_seeds
$(FUZZ_SEEDS_BIN): tests/fuzz/make_seeds.c sim/link/tdc_link_gen.c sim/link/tdc_link_encode.c $(LINK_FW_SRCS) $(GEN)/tdc_crc32_tables.h
	@mkdir -p $(@D)
	gcc -std=c11 -D_GNU_SOURCE -Wall -Wextra -Werror -O2 -Ifirmware -Isim -I$(GEN) $(filter %.c,$^) -o $@
fuzz-seeds: $(FUZZ_SEEDS_BIN)
	@mkdir -p tests/fuzz/corpus
	$(FUZZ_SEEDS_BIN) tests/fuzz/corpus
	@ls tests/fuzz/corpus | wc -l

# ---------------------------------------------------------------------------
# Tests, golden vectors, benchmark.
# ---------------------------------------------------------------------------
TESTS += $(B)/tests/unit/test_link $(B)/tests/unit/test_link_pixfmt $(B)/tests/unit/test_link_file $(B)/tests/unit/test_link_mask
GOLDEN_STAGES += link
BENCHES += $(B)/tests/bench/bench_link
TEST_EXTRA += fuzz-smoke

# tdc-linkdump: check a .tdcs stream file with the firmware decoder.
LINKDUMP := $(B)/tdc-linkdump
$(LINKDUMP): $(B)/sim/link/tdc_linkdump.o $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $< -o $@ $(SIMLIB) $(FWLIB) $(HOST_LIBS)
HOST_PROGS += $(LINKDUMP)
