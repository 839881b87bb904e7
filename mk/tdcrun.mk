# tdc-run (the firmware on anyone's PNG frames) and the TRM part of
# `make demo` (PNG I/O: mk/common.mk).

# tdc-run: the firmware on anyone's frames.  Other modes add their sources
# to TDCRUN_SRCS (e.g. tile assembly: hosttools/tdcrun/run_assemble.c).
TDCRUN_OBJS = $(patsubst %.c,$(B)/%.o,hosttools/tdcrun/tdc_run.c hosttools/tdcrun/run_gaze.c $(TDCRUN_SRCS)) $(B)/tests/golden/tdc_content.o
$(B)/hosttools/tdcrun/tdc_run.o: HOST_CFLAGS += $(if $(filter hosttools/tdcrun/run_assemble.c,$(TDCRUN_SRCS)),-DTDC_RUN_WITH_ASSEMBLE)
# the mode list comes from the fragments: rebuild when they change
$(B)/hosttools/tdcrun/tdc_run.o: $(wildcard mk/*.mk)
$(TDCRUN): $(TDCRUN_OBJS) $(SIMLIB) $(FWLIB)
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $(TDCRUN_OBJS) -o $@ $(SIMLIB) $(FWLIB) $(HOST_LIBS)
HOST_PROGS += $(TDCRUN)
$(B)/test-tdc-run: $(TDCRUN) tests/unit/test_tdc_run.sh
	@printf '#!/bin/sh\nexec tests/unit/test_tdc_run.sh %s\n' "$(TDCRUN)" > $@
	@chmod +x $@
TESTS += $(B)/test-tdc-run
TESTS += $(B)/tests/unit/test_png

# make demo, TRM part: tdc-run on built-in contents -> report/trm/index.md
REPORT ?= report
DEMO_TRM_CONTENTS := edge text checker gradient primaries
demo: deps demo-trm
demo-trm: $(TDCRUN) $(B)/tests/unit/test_trm_ref
	@rm -rf $(BUILD)/demo-trm; mkdir -p $(REPORT)/trm
	@for c in $(DEMO_TRM_CONTENTS); do \
	    $(TDCRUN) -q -o $(BUILD)/demo-trm/$$c --builtin $$c --count 8 --size 320x200 --frames auto \
	        --save-input --perceived || exit 1; done
	/usr/bin/python3 sim/trm_report.py $(REPORT)/trm $(addprefix $(BUILD)/demo-trm/,$(DEMO_TRM_CONTENTS))
	@{ echo; echo '## Fixed point against the double-precision reference'; echo; \
	   echo 'Output of `$(B)/tests/unit/test_trm_ref` (max abs error in output LSB, share within 1 LSB):'; \
	   echo; echo '```'; $(B)/tests/unit/test_trm_ref 2>&1 | grep -E '^  (D|full|reduced) '; echo '```'; } >> $(REPORT)/trm/index.md
	@[ -f $(REPORT)/index.md ] || { echo '# tdc demo report'; echo; echo '- [TRM on built-in contents](trm/index.md)'; } > $(REPORT)/index.md
	@echo "demo-trm: wrote $(REPORT)/trm/index.md"
.PHONY: demo-trm
