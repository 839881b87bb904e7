#!/bin/sh
# Runs the checkasm core's Cortex-M image (tests/arm/checkasm_arm_main.c) in
# qemu-system-arm with semihosting: passes when it exits 0 within the time
# limit having checked at least one kernel, and prints its lines (the
# mismatch it found with its replay command, or what it checked).
# Extra arguments for the core go in CHECKASM_ARGS (QEMU's -append).
# Usage: tests/arm/run_checkasm_qemu.sh BOARD TIMEOUT_S IMAGE QEMU_ARGS...
board=$1; limit=$2; image=$3; shift 3
out=$(mktemp); err=$(mktemp)
trap 'rm -f "$out" "$err"' EXIT
timeout "$limit" qemu-system-arm "$@" -display none -nodefaults \
    -semihosting-config enable=on,target=native -kernel "$image" \
    ${CHECKASM_ARGS:+-append "$CHECKASM_ARGS"} >"$out" 2>"$err"
status=$?
cat "$out"; grep -v 'has no peer' "$err" >&2
if [ "$status" -eq 124 ]; then echo "checkasm[$board]: QEMU timed out after ${limit} s ($image)"; exit 1; fi
if [ "$status" -ne 0 ]; then echo "checkasm[$board]: exited with status $status ($image)"; exit 1; fi
grep -Eq 'checkasm: [1-9][0-9]* kernels checked, 0 failed' "$out" || { echo "checkasm[$board]: no kernel checked"; exit 1; }
