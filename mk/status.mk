# The one status vocabulary of the firmware (firmware/tdc_status.h): names
# and texts of every tdc_status_t, and their test.
FW_SRCS += firmware/tdc_status.c
TESTS += $(B)/tests/unit/test_status
