# The one tool convention (issue 12 item 4, docs/tools.md): exit-code table,
# "tool: command: what: why" messages, overflow-checked number parsing,
# bounded line reading and rename-on-success output files, shared by every
# host program: common/tdc_tool.c, in the common library (mk/common.mk);
# tdc-usb, tdc-gpio and the table generator name the object or source.
TESTS += $(B)/tests/unit/test_tool

# Error paths of tdc-linkdump, tdc-render and the table generator (both
# variants; LeakSanitizer on in the ASan one).
$(B)/test-tool-errors: tests/unit/test_tool_errors.sh $(B)/tdc-render $(B)/tdc-linkdump $(B)/tdc-sim $(TABLEGEN)
	@printf '#!/bin/sh\nexec tests/unit/test_tool_errors.sh %s %s\n' "$(B)" "$(TABLEGEN)" > $@
	@chmod +x $@
TESTS += $(B)/test-tool-errors

# Every program the project builds against the convention (docs/tools.md):
# --help exits 0, a bad option, a folder as input and an output that cannot
# be written each give one line and ARGS/FILE.  A program added to
# HOST_PROGS without cases in the script fails it.  ~3 s.
$(B)/test-tool-conventions: tests/unit/test_tool_conventions.sh tests/unit/tool_expect.sh $$(HOST_PROGS) $(TABLEGEN)
	@printf '#!/bin/sh\nexec tests/unit/test_tool_conventions.sh %s\n' "$(HOST_PROGS) $(TABLEGEN)" > $@
	@chmod +x $@
TESTS += $(B)/test-tool-conventions

# The one exit-code table (common/tdc_exit.h) against its copies:
# docs/tools.md, README, every code named in the docs, the Python tools.
$(TABLEGEN): common/tdc_exit.h
$(B)/test-exit-table: tests/unit/test_exit_table.py tests/unit/tdc_check.py common/tdc_exit.h common/tdc_exit.py
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec /usr/bin/python3 tests/unit/test_exit_table.py\n' > $@
	@chmod +x $@
TESTS += $(B)/test-exit-table

# docs/design.md's paths exist, its "where is X" symbols are in the files it
# names, and README links the table (0.1 s).
$(B)/test-design-refs: tests/unit/test_design_refs.py tests/unit/tdc_check.py docs/design.md README.md
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec /usr/bin/python3 tests/unit/test_design_refs.py\n' > $@
	@chmod +x $@
TESTS += $(B)/test-design-refs
