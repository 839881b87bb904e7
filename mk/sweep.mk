# Sweeps of tdc-sim on existing engines (issue 13 item 6): sim/sweep/tdc_sweep.py
# expands a sweep file to one job per configuration, runs them under GNU
# parallel (local) or as a Slurm job array (one configuration per index) and
# merges one CSV + report, naming failed jobs.  docs/sweeps.md.
#
#   make sweep SWEEP=sim/sweep/examples/small.sweep [SWEEP_OUT=build/sweep] [ENGINE=local|slurm] [JOBS=2]
DEPS_PKGS += parallel slurmctld slurmd slurm-client munge
TEST_EXTRA += test-sweep

SWEEP ?= sim/sweep/examples/small.sweep
SWEEP_OUT ?= $(BUILD)/sweep
ENGINE ?= local
JOBS ?= $(shell nproc)

.PHONY: sweep test-sweep
sweep: $(TDC_SIM)
	/usr/bin/python3 sim/sweep/tdc_sweep.py $(ENGINE) $(SWEEP) $(SWEEP_OUT) --sim $(TDC_SIM) \
	    $(if $(filter local,$(ENGINE)),-j $(JOBS),--wait)

# Run once (not per sanitizer variant): GNU parallel and a one-node Slurm
# cluster the test starts and stops itself (~30 s).
$(B)/test-sweep: tests/unit/test_sweep.sh $(TDC_SIM)
	@printf '#!/bin/sh\nexec tests/unit/test_sweep.sh %s\n' "$(TDC_SIM)" > $@
	@chmod +x $@
test-sweep: $(B)/test-sweep
	@tests/run_tests.sh sweep $(B)/test-sweep
