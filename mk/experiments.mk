# The papers' own experiments as named tdc-sim sweeps (issue 15):
# sim/experiments/<group>/ holds each group's sweeps and its claims script;
# sim/experiments/tdc_experiments.py runs them on GNU parallel (through
# sim/sweep/tdc_sweep.py), writes <group>/claims.csv and merges every group
# into the paper-vs-tdc table (report/experiments.md, docs/results.md).
# docs/experiments.md: budgets, scales, how a group is added.
#
#   make experiments [EXP_GROUPS="trm-fixation ..."] [EXP_SCALE=headset|dev|demo] [JOBS=2]
#   make experiments-report        the table again from the cached results
EXP_SCALE ?= headset
EXP_OUT ?= $(BUILD)/experiments
EXP_GROUPS ?=
EXP_PY := /usr/bin/python3 sim/experiments/tdc_experiments.py
TEST_EXTRA += test-experiments test-tdc-stats

.PHONY: experiments experiments-report demo-experiments test-experiments test-tdc-stats
# Group zeng-cost times the renderer's own passes with tdc-render (no sweep).
experiments demo-experiments experiments-report: $(TDC_RENDER)
experiments demo-experiments experiments-report: export TDC_RENDER := $(abspath $(TDC_RENDER))
experiments: deps $(TDC_SIM)
	$(EXP_PY) run $(EXP_GROUPS) --scale $(EXP_SCALE) --out $(EXP_OUT) -j $(JOBS) --sim $(TDC_SIM); \
	    rc=$$?; $(EXP_PY) report --out $(EXP_OUT) --report $(or $(REPORT),report)/experiments.md; exit $$rc

experiments-report:
	$(EXP_PY) report --out $(EXP_OUT) --report $(or $(REPORT),report)/experiments.md

# `make demo`: the cached results of `make experiments` when there are any,
# else every group at the demo scale (small sizes, minutes); docs/results.md
# is only rewritten by `make experiments`.
demo: demo-experiments
demo-experiments: $(TDC_SIM)
	@if ls $(EXP_OUT)/*/claims.csv >/dev/null 2>&1; then \
	    echo "demo: summarising the cached experiments in $(EXP_OUT) (make experiments)"; \
	    $(EXP_PY) report --out $(EXP_OUT) --report $(or $(REPORT),report)/experiments.md --results -; \
	else \
	    $(EXP_PY) run --scale demo --out $(B)/experiments-demo -j $(JOBS) --sim $(TDC_SIM); rc=$$?; \
	    $(EXP_PY) report --out $(B)/experiments-demo --report $(or $(REPORT),report)/experiments.md --results -; \
	    exit $$rc; \
	fi

# The framework and the statistics helper on a temporary two-job group (~5 s).
$(B)/test-experiments: tests/unit/test_experiments.sh $(TDC_SIM)
	@printf '#!/bin/sh\nexec tests/unit/test_experiments.sh %s\n' "$(TDC_SIM)" > $@
	@chmod +x $@
test-experiments: $(B)/test-experiments
	@tests/run_tests.sh experiments $(B)/test-experiments

# tdc_stats on synthetic data with known answers, against scipy.stats (~2 s).
test-tdc-stats:
	@tests/run_tests.sh experiments tests/unit/test_tdc_stats.py
