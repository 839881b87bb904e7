# Tile-ordered frame assembly (issue 5): orderings, assembly, reference, tests, bench.
FW_SRCS += firmware/tdc_ordering.c
