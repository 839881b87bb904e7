#!/bin/sh
# Runs the ARM golden-vector runner in qemu-system-arm with semihosting and
# compares its output with tests/golden/*.expected (tests/golden/check.sh,
# or $GOLDEN_CHECK).  Fails when QEMU times out, the runner faults or exits
# non-zero (SYS_EXIT_EXTENDED status), or any checksum differs; a mismatch
# line names the board, the stage/vector and the frame.
# Usage: tests/arm/run_golden_qemu.sh BOARD TIMEOUT_S IMAGE QEMU_ARGS...
board=$1; limit=$2; image=$3; shift 3
check=${GOLDEN_CHECK:-$(dirname "$0")/../golden/check.sh}
out=$(mktemp); err=$(mktemp)
trap 'rm -f "$out" "$err"' EXIT
timeout "$limit" qemu-system-arm "$@" -display none -nodefaults \
    -semihosting-config enable=on,target=native -kernel "$image" >"$out" 2>"$err"
status=$?
grep -v 'has no peer' "$err" >&2
if [ "$status" -eq 124 ]; then
    echo "golden[$board]: QEMU timed out after ${limit} s ($image)"; exit 1
elif [ "$status" -ne 0 ]; then
    echo "golden[$board]: runner exited with status $status ($image)"
    "$check" "$board" "$out" | grep -v 'MISSING' | head -20
    exit 1
fi
exec "$check" "$board" "$out"
