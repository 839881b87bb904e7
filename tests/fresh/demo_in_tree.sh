#!/bin/sh
# demo_in_tree.sh MARK - the newcomer's `make demo` in this very tree, when
# `make test` finds it fresh (no build/ yet: CI's clean clone).  Run before
# anything else compiles, it is the check test_fresh_clone.sh makes in a
# copy, and the host build it leaves is the one run-tests uses, where the
# copy's was thrown away (a second build of the whole host tree).  Writes
# one line to MARK: "ok: ..." or "FAIL: ..."; test_fresh_clone.sh reports
# it in place of its own demo.  The report goes to build/fresh-demo-report,
# not report/, which stays the user's.
mark=$1
dir=build/fresh-demo-report
log=build/fresh-demo.log
unset MAKEFLAGS MFLAGS MAKELEVEL MAKEOVERRIDES TDC_DEPS
t0=$(date +%s)
if make -j2 demo DEMO_SCALE=ci REPORT="$dir" > "$log" 2>&1 && [ -s "$dir/index.md" ]; then
    echo "ok: make -j2 demo DEMO_SCALE=ci in this fresh tree, before anything else compiled ($(( $(date +%s) - t0 )) s, $dir/index.md written)" > "$mark"
else
    { echo "FAIL: make -j2 demo DEMO_SCALE=ci in this fresh tree ($(( $(date +%s) - t0 )) s): see $log"
      grep -E 'FAILED|Error|error:' "$log" | head -8 | sed 's/^/    /'; tail -5 "$log" | sed 's/^/    /'; } > "$mark"
fi
cat "$mark"
