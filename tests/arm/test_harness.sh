#!/bin/sh
# The QEMU golden harness must be able to fail: a wrong checksum, a non-zero
# exit status, a fault and a hang each make tests/arm/run_golden_qemu.sh
# fail with a message naming the board (and vector and frame).
# Usage: tests/arm/test_harness.sh BOARD HARNESS_IMAGE QEMU_ARGS...
board=$1; image=$2; shift 2
run=tests/arm/run_golden_qemu.sh
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bad=0

expect_fail() { # name pattern command...
    name=$1; pattern=$2; shift 2
    out=$("$@" 2>&1); rc=$?
    if [ "$rc" -eq 0 ] || ! printf '%s\n' "$out" | grep -q -- "$pattern"; then
        echo "harness[$board]: $name: expected a failure matching '$pattern', got status $rc:"
        printf '%s\n' "$out" | sed 's/^/    /'
        bad=1
    else
        echo "harness[$board]: $name fails as it must: $(printf '%s\n' "$out" | grep -- "$pattern" | head -1)"
    fi
}

# Raw output of the "lines" mode; it must exit 0 with three lines.
timeout 20 qemu-system-arm "$@" -display none -nodefaults -semihosting-config enable=on,target=native \
    -kernel "$image" -append lines >"$tmp/out" 2>/dev/null
rc=$?
if [ "$rc" -ne 0 ] || [ "$(wc -l <"$tmp/out")" -ne 3 ]; then
    echo "harness[$board]: 'lines' mode: status $rc, $(wc -l <"$tmp/out") lines (want 0, 3)"; exit 1
fi
cp tests/golden/check.sh "$tmp/check.sh"

# Same lines expected: passes.
cp "$tmp/out" "$tmp/harness.expected"
if ! GOLDEN_CHECK="$tmp/check.sh" $run "$board" 20 "$image" "$@" -append lines >"$tmp/log" 2>&1; then
    echo "harness[$board]: identical expected values did not pass:"; cat "$tmp/log"; bad=1
fi
# Frame 1 expected differently: the mismatch names board, vector and frame.
awk 'NR == 2 { $3 = "0123456789abcdef" } { print }' "$tmp/out" >"$tmp/harness.expected"
GOLDEN_CHECK="$tmp/check.sh" expect_fail mismatch "golden\[$board\]: MISMATCH harness/text frame 1" \
    $run "$board" 20 "$image" "$@" -append lines
expect_fail exit-status "golden\[$board\]: runner exited with status 3" $run "$board" 20 "$image" "$@" -append exit3
expect_fail fault "fault: HardFault" $run "$board" 20 "$image" "$@" -append fault
expect_fail hang "golden\[$board\]: QEMU timed out" $run "$board" 2 "$image" "$@" -append hang
[ "$bad" -eq 0 ] && echo "harness[$board]: all failure modes detected"
exit "$bad"
