#!/bin/sh
# Runs test executables one by one, prints PASS/FAIL with the time each took,
# appends "variant name PASS|FAIL" lines to $RESULTS and prints a summary.
# Usage: tests/run_tests.sh VARIANT exe...
# TEST_TIMEOUT (s, default 900) bounds each test so nothing hangs; a test
# that builds whole trees (the fresh clone) sets a longer one.
variant=$1; shift
pass=0; fail=0
for t in "$@"; do
    name=$(basename "$t")
    start=$(date +%s)
    log=$(mktemp)
    if timeout "${TEST_TIMEOUT:-900}" "$t" >"$log" 2>&1; then
        res=PASS; pass=$((pass+1))
    else
        res=FAIL; fail=$((fail+1))
    fi
    end=$(date +%s)
    # Show the test's own report (figures, cmocka summary) and our verdict.
    cat "$log"; rm -f "$log"
    echo "[$variant] $res $name ($((end-start)) s)"
    [ -n "$RESULTS" ] && echo "$variant $name $res" >> "$RESULTS"
done
echo "[$variant] $pass passed, $fail failed"
[ "$fail" -eq 0 ]
