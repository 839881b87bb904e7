# A newcomer's first commands: the fragments' read order
# (tests/rules/check_make_order.py) and a copy of the working tree running
# the README's commands as a fresh clone does (tests/fresh/test_fresh_clone.sh:
# `make -n` shows deps first, board images from a clean tree, `make demo`
# with every run at DEMO_SCALE=ci, `make size` over every pair).  The demo
# is the one `make test` ran in place when it found the tree fresh
# (FRESH_DEMO_MARK, see the test target), else it runs in the copy.
# FRESH_PAIRS: images built alone in a copy where nothing else was built
# (the README's example pair, and one per emulated board).
FRESH_PAIRS ?= stm32h747i-disco:disco-dsi mps3-an547:htc-vive
TEST_BESIDE += test-newcomer
# The fresh clone builds demo, images and sizes from nothing: 925 s on a
# machine loaded by parallel builds, past run_tests.sh's 900 s default.
.PHONY: test-newcomer
test-newcomer:
	@mkdir -p $(BUILD)
	@printf '#!/bin/sh\nexec tests/rules/check_make_order.py .\n' > $(BUILD)/make-order
	@printf '#!/bin/sh\nFRESH_DEMO_MARK=%s exec tests/fresh/test_fresh_clone.sh %s\n' "$(FRESH_DEMO_MARK)" "$(FRESH_PAIRS)" > $(BUILD)/fresh-clone
	@chmod +x $(BUILD)/make-order $(BUILD)/fresh-clone
	@TEST_TIMEOUT=2400 tests/run_tests.sh newcomer $(BUILD)/make-order $(BUILD)/fresh-clone
