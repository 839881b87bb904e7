# The papers' own experiments as named tdc-sim sweeps (issue 15):
# sim/experiments/<group>/ holds each group's sweeps and its claims script;
# sim/experiments/tdc_experiments.py runs them on GNU parallel (through
# sim/sweep/tdc_sweep.py), writes <group>/claims.csv and merges every group
# into the paper-vs-tdc table (report/experiments.md, docs/results.md).
# docs/experiments.md: budgets, scales, how a group is added.
#
#   make experiments [EXP_GROUPS="trm-fixation ..."] [EXP_SCALE=headset|dev|demo] [JOBS=2]
#   make experiments-report        the table again from the cached results
# Every finished tdc-sim job is cached in $(EXP_OUT)/.cache (key: its full
# arguments, the binary's SHA-256, the files it names): an interrupted
# `make experiments` resumes where it stopped when run again, and prints the
# jobs left and their estimated CPU seconds before every group.
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

# `make demo`: the demo-scale results, summarised (the counts line and a
# per-group table on stdout, the full table in report/experiments.md):
#  - when $(EXP_DEMO_OUT) holds results: those (an earlier make demo, or
#    make experiments EXP_SCALE=demo EXP_OUT=$(EXP_DEMO_OUT));
#  - with EXP_DEMO=run: every group at demo scale first (455 jobs, ~2,100
#    CPU s: longer than the demo's 10-minute budget; jobs cached in
#    $(EXP_DEMO_OUT)/.cache, an interrupted run resumes);
#  - else the groups of EXP_DEMO_LIVE run at demo scale (~135 CPU s:
#    zeng-reliable's reference pipeline on its six scenes, lcd-modes), beside
#    the other groups' committed demo-scale results, $(EXP_DEMO_SAVED) (each
#    group's claims.csv, meta.json and extra.md, copied from a demo-scale run
#    by `make experiments-save-demo`), which docs/results.md's block is made of.
# DEMO_SCALE=ci (the newcomer check of make test) runs one group, lcd-modes
# (50 jobs, ~14 CPU s), in its own folder: the framework's whole path (plan,
# sweep, claims, report) in a fresh tree.
EXP_DEMO_GROUPS := $(if $(filter ci,$(DEMO_SCALE)),lcd-modes)
EXP_DEMO_OUT ?= $(BUILD)/experiments-demo$(if $(EXP_DEMO_GROUPS),-ci)
EXP_DEMO_SAVED := sim/experiments/demo-results
EXP_DEMO_LIVE ?= lcd-modes zeng-reliable
EXP_DEMO ?=
demo: demo-experiments
demo-experiments: $(TDC_SIM)
	@if ! ls $(EXP_DEMO_OUT)/*/claims.csv >/dev/null 2>&1; then \
	    if [ -n "$(EXP_DEMO_GROUPS)" ] || [ "$(EXP_DEMO)" = run ]; then \
	        $(EXP_PY) run $(EXP_DEMO_GROUPS) --scale demo --out $(EXP_DEMO_OUT) -j $(JOBS) --sim $(TDC_SIM) || rc=$$?; \
	    else \
	        echo "demo: the papers' experiments: $(EXP_DEMO_LIVE) run now at demo scale, the other groups' committed demo-scale results ($(EXP_DEMO_SAVED)); all of them: make demo EXP_DEMO=run (~2,100 CPU s)"; \
	        mkdir -p $(EXP_DEMO_OUT); for d in $(EXP_DEMO_SAVED)/*/; do g=$$(basename $$d); \
	            case " $(EXP_DEMO_LIVE) " in *" $$g "*) ;; *) cp -r $$d $(EXP_DEMO_OUT)/ ;; esac; done; \
	        $(EXP_PY) run $(EXP_DEMO_LIVE) --scale demo --out $(EXP_DEMO_OUT) -j $(JOBS) --sim $(TDC_SIM) || rc=$$?; \
	    fi; \
	fi; \
	$(EXP_PY) report --out $(EXP_DEMO_OUT) --report $(or $(REPORT),report)/experiments.md --results - && exit $${rc:-0}

# Copies a run's per-group results (claims, meta, extra tables) into the
# committed results of its scale, then rewrites docs/results.md's block of
# that scale from them (tdc_experiments.py report writes the headset and the
# demo block apart): the block is made of files in the tree, and one group
# re-run at a scale replaces only that group's files.
#   make experiments-save-demo      $(EXP_DEMO_OUT) -> $(EXP_DEMO_SAVED)
#   make experiments-save-headset   $(EXP_OUT) -> $(EXP_HEADSET_SAVED)
EXP_HEADSET_SAVED := sim/experiments/headset-results
define save-results
	@for d in $(1)/*/; do g=$$(basename $$d); [ -f $$d/claims.csv ] || continue; \
	    mkdir -p $(2)/$$g; cp $$d/claims.csv $$d/meta.json $(2)/$$g/; \
	    if [ -f $$d/extra.md ]; then cp $$d/extra.md $(2)/$$g/; fi; done
	$(EXP_PY) report --out $(2) --report $(or $(REPORT),report)/experiments.md
endef
.PHONY: experiments-save-demo experiments-save-headset
experiments-save-demo:
	$(call save-results,$(EXP_DEMO_OUT),$(EXP_DEMO_SAVED))
experiments-save-headset:
	$(call save-results,$(EXP_OUT),$(EXP_HEADSET_SAVED))

# The framework and the statistics helper on a temporary two-job group (~5 s).
$(B)/test-experiments: tests/unit/test_experiments.sh $(TDC_SIM)
	@printf '#!/bin/sh\nexec tests/unit/test_experiments.sh %s\n' "$(TDC_SIM)" > $@
	@chmod +x $@
test-experiments: $(B)/test-experiments
	@tests/run_tests.sh experiments $(B)/test-experiments

# tdc_stats on synthetic data with known answers, against scipy.stats (~2 s).
test-tdc-stats:
	@tests/run_tests.sh experiments tests/unit/test_tdc_stats.py
