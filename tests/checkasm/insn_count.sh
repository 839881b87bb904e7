#!/bin/sh
# Instructions per unit (pixel unless the input says otherwise) of every
# registered kernel pair's benchmark input, reference and optimised side,
# counted by an emulator: checkasm --marks calls each side once between
# checkasm_mark() calls, and QEMU with the counting plugin
# (tests/arm/tdc_insn_plugin.c) records its instruction count at each.
# Executed instructions, exact for the code as compiled; not cycles.
# The bracket's own cost (the loop around the call, ~20 instructions) is
# in both sides: below 0.05 per unit on these inputs.
# Usage: tests/checkasm/insn_count.sh NM PLUGIN QEMU CHECKASM [PATTERN...]
set -eu
nm=$1; plugin=$2; qemu=$3; bin=$4; shift 4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mark=$("$nm" "$bin" | awk '$3 == "checkasm_mark" { print "0x" $1 }')
[ -n "$mark" ] || { echo "insn_count: no checkasm_mark in $bin" >&2; exit 1; }
"$qemu" -plugin "$plugin,mark=$mark,out=$tmp/marks" "$bin" --marks "$@" > "$tmp/out" \
    || { cat "$tmp/out" >&2; echo "insn_count: checkasm failed under $qemu" >&2; exit 1; }
grep -q '^mark ' "$tmp/out" || { echo "insn_count: no benchmark selected" >&2; exit 1; }
printf '  %-24s %-38s %9s %9s %8s\n' kernel input C optimised ratio
awk -v marks="$tmp/marks" '
    BEGIN { while ((getline l < marks) > 0) { split(l, a, " "); if (a[1] != "total") m[a[1]] = a[2] } }
    /^mark / { sub(/^mark /, ""); split($0, f, "|")
               ref = m[4 * k + 1] - m[4 * k]; opt = m[4 * k + 3] - m[4 * k + 2]; k++
               printf "  %-24s %-38s %9.1f %9.1f %7.2fx\n", f[1], f[2], ref / f[3], opt / f[3], opt ? ref / opt : 0 }' "$tmp/out"
