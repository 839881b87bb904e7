# Firmware backbone: fixed-point core, gamma, TRM, golden vectors, tdc-run.
FW_SRCS += firmware/tdc_math.c
TESTS += $(B)/tests/test_math
SIM_SRCS += sim/tdc_png.c
FW_SRCS += firmware/tdc_trm.c
SIM_SRCS += sim/ref_trm.c
TESTS += $(B)/tests/test_trm_ref
TESTS += $(B)/tests/test_trm
TESTS += $(B)/tests/test_trm_stability
GOLDEN_STAGES += trm
