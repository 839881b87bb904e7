# Firmware layers without circles (tests/rules/check_include_cycles.sh): no
# two firmware modules include each other, directly or around a circle; the
# test first shows that it finds one planted in a copy of the tree.
$(B)/check-include-cycles: tests/rules/check_include_cycles.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/rules/check_include_cycles.sh --selftest firmware firmware/board\n' > $@
	@chmod +x $@
TESTS += $(B)/check-include-cycles
