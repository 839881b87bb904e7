#!/bin/sh
# Runs a checkasm image (e.g. tests/checkasm/checkasm_trm_mve.c) in
# qemu-system-arm with semihosting: passes when it exits 0 within the time
# limit, and prints its lines (the mismatch it found, or what it checked).
# Usage: tests/arm/run_checkasm_qemu.sh BOARD TIMEOUT_S IMAGE QEMU_ARGS...
board=$1; limit=$2; image=$3; shift 3
out=$(mktemp); err=$(mktemp)
trap 'rm -f "$out" "$err"' EXIT
timeout "$limit" qemu-system-arm "$@" -display none -nodefaults \
    -semihosting-config enable=on,target=native -kernel "$image" >"$out" 2>"$err"
status=$?
cat "$out"; grep -v 'has no peer' "$err" >&2
if [ "$status" -eq 124 ]; then echo "checkasm[$board]: QEMU timed out after ${limit} s ($image)"; exit 1; fi
if [ "$status" -ne 0 ]; then echo "checkasm[$board]: exited with status $status ($image)"; exit 1; fi
grep -q 'bit-exact' "$out" || { echo "checkasm[$board]: no result line"; exit 1; }
