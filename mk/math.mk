# Fixed-point math core (firmware/tdc_math.c) and its exhaustive tests, also
# with the Cortex-M arithmetic on the host.
FW_SRCS += firmware/tdc_math.c firmware/tdc_math_log2.c
TESTS += $(B)/tests/unit/test_math

# test_math again with the Cortex-M arithmetic (TDC_HW_DIV64=0: long
# division with 32-bit divides in the reciprocal and the square root), so
# the boards' paths are checked on the host too, not only through QEMU.
$(B)/tests/portable/tdc_math.o: firmware/tdc_math.c $(GEN)/tdc_panels.h
	@mkdir -p $(@D)
	$(CC) $(FW_CFLAGS) -DTDC_HW_DIV64=0 -c $< -o $@
$(B)/tests/portable/test_math.o: tests/unit/test_math.c $(GEN)/tdc_panels.h
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) -DTDC_HW_DIV64=0 -c $< -o $@
$(B)/tests/unit/test_math_portable: $(B)/tests/portable/test_math.o $(B)/tests/portable/tdc_math.o $(TEST_SUPPORT_OBJS) $(SIMLIB) $(FWLIB)
	$(CC) $(HOST_LDFLAGS) $(filter %.o,$^) -o $@ $(SIMLIB) $(FWLIB) $(HOST_LIBS)
TESTS += $(B)/tests/unit/test_math_portable
