# Firmware layers without circles (tests/rules/check_include_cycles.sh): no
# two firmware modules include each other, directly or around a circle; the
# test first shows that it finds one planted in a copy of the tree.
$(B)/check-include-cycles: tests/rules/check_include_cycles.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/rules/check_include_cycles.sh --selftest firmware firmware/board\n' > $@
	@chmod +x $@
TESTS += $(B)/check-include-cycles

# Host layers point one way (tests/rules/check_include_dirs.py, docs/design.md
# §10): common/ below ref/ below render/ and sim/, hosttools/ on common/ and
# ref/ only; sim/ and hosttools/ never include each other.  It first proves
# on a planted tree that it finds a reach in each direction.
$(B)/check-include-dirs: tests/rules/check_include_dirs.py
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/rules/check_include_dirs.py --selftest .\n' > $@
	@chmod +x $@
TESTS += $(B)/check-include-dirs
