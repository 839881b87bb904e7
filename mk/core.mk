# Firmware backbone: fixed-point core, gamma, TRM, golden vectors, tdc-run.
FW_SRCS += firmware/tdc_math.c
TESTS += $(B)/tests/test_math
SIM_SRCS += sim/tdc_png.c
