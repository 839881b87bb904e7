# The stage scaffold (firmware/tdc_arena.h, header-only): get_size, init's
# layout and the compile-time *_MEM_BYTES bound agree for every stage with an
# arena (TRM, LCD, assembly), every panel and the extreme sizes.
TESTS += $(B)/tests/unit/test_arena
