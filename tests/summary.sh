#!/bin/sh
# Final line of `make test`: totals over every variant run.
f=$1
if [ ! -s "$f" ]; then echo "no test results in $f"; echo "0 passed, 1 failed"; exit 1; fi
pass=$(grep -c ' PASS$' "$f"); fail=$(grep -c ' FAIL$' "$f")
if [ "$fail" -gt 0 ]; then echo "failed:"; grep ' FAIL$' "$f" | sed 's/^/  /'; fi
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
