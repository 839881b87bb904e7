# A newcomer's first commands: the fragments' read order
# (tests/rules/check_make_order.py) and a copy of the working tree running
# the README's commands as a fresh clone does (tests/fresh/test_fresh_clone.sh:
# `make -n` shows deps first, board images from a clean tree, `make demo`
# with every run at DEMO_SCALE=ci).  FRESH_PAIRS: the board/panel images the
# README and docs/boards.md say build (the pairs ARM_FIT_FAIL lists do not
# fit their board; mk/boards.mk tests that verdict).
FRESH_PAIRS ?= stm32h747i-disco:disco-dsi stm32h747i-disco:lcd-240 \
               mps2-an500:disco-dsi mps3-an547:htc-vive mps3-an547:lcd-240
TEST_EXTRA += test-newcomer
.PHONY: test-newcomer
test-newcomer:
	@mkdir -p $(BUILD)
	@printf '#!/bin/sh\nexec tests/rules/check_make_order.py .\n' > $(BUILD)/make-order
	@printf '#!/bin/sh\nexec tests/fresh/test_fresh_clone.sh %s\n' "$(FRESH_PAIRS)" > $(BUILD)/fresh-clone
	@chmod +x $(BUILD)/make-order $(BUILD)/fresh-clone
	@tests/run_tests.sh newcomer $(BUILD)/make-order $(BUILD)/fresh-clone
