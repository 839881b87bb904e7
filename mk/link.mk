# Link protocol (docs/link-protocol.md): firmware decoder, CRC-32, pixel
# formats; host encoder (.tdcs stream files: mk/common.mk); tests, golden, fuzz, bench.

# CRC-32 tables generated at build time (never typed by hand).
CRC32_GEN := $(BUILD)/tools/tdc-crc32-gen
$(CRC32_GEN): sim/link/tdc_crc32_gen.c firmware/tdc_crc32.h | $(BUILD)/tools
	gcc -std=c11 -Wall -Wextra -Werror -O2 -Ifirmware $< -o $@
$(GEN)/tdc_crc32_tables.h: $(CRC32_GEN) | $(GEN)
	$(CRC32_GEN) $@
FW_GEN_HEADERS += $(GEN)/tdc_crc32_tables.h

FW_SRCS += firmware/tdc_crc32.c firmware/tdc_pixfmt.c firmware/tdc_wire.c firmware/tdc_link.c firmware/tdc_link_encode.c firmware/tdc_layer_link.c \
            firmware/tdc_band_link.c
SIM_SRCS += sim/link/tdc_pixfmt_ref.c sim/link/tdc_link_gen.c

# Fuzzing of the decoder (and of every other parser), and the decoder's
# source list LINK_FW_SRCS: mk/fuzz.mk.

# ---------------------------------------------------------------------------
# Tests, golden vectors, benchmark.
# ---------------------------------------------------------------------------
TESTS += $(B)/tests/unit/test_wire $(B)/tests/unit/test_link $(B)/tests/unit/test_layer_link $(B)/tests/unit/test_band_link $(B)/tests/unit/test_link_pixfmt $(B)/tests/unit/test_link_file $(B)/tests/unit/test_link_mask
GOLDEN_STAGES += link
BENCHES += $(B)/tests/bench/bench_link

# tdc-linkdump: check a .tdcs stream file with the firmware decoder.
LINKDUMP := $(B)/tdc-linkdump
$(LINKDUMP): $(B)/sim/link/tdc_linkdump.o $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $< -o $@ $(SIMLIB) $(FWLIB) $(HOST_LIBS)
HOST_PROGS += $(LINKDUMP)
