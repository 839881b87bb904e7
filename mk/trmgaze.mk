# Gaze-aware TRM (issue 15): the strength stage, its double reference, the
# fixed-point-vs-reference and bad-input tests, golden vectors of the on-state
# (the off-state is TRM's own vectors, unchanged).
FW_SRCS += firmware/tdc_trm_gaze.c
SIM_SRCS += sim/ref_trm_gaze.c
TESTS += $(B)/tests/unit/test_trm_gaze
GOLDEN_STAGES += trmgaze
