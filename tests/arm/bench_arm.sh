#!/bin/sh
# Runs the ARM bench image in QEMU with the instruction-counting plugin and
# prints "label<TAB>instructions per pixel" for every stage (repeated
# labels are summed: instructions / pixels over all their measurements).
# The cost of the two marker calls (measured first, label "(mark
# overhead)") is subtracted from every measurement.
# Usage: tests/arm/bench_arm.sh NM PLUGIN IMAGE QEMU_ARGS...
nm=$1; plugin=$2; image=$3; shift 3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mark=$("$nm" "$image" | awk '$3 == "tdc_bench_mark" { print "0x" $1 }')
[ -n "$mark" ] || { echo "bench-arm: no tdc_bench_mark in $image" >&2; exit 1; }
if ! timeout 600 qemu-system-arm "$@" -display none -nodefaults -semihosting-config enable=on,target=native \
        -plugin "$plugin,mark=$mark,out=$tmp/marks" -kernel "$image" >"$tmp/labels" 2>"$tmp/err"; then
    grep -v 'has no peer' "$tmp/err" >&2; echo "bench-arm: QEMU run failed ($image)" >&2; exit 1
fi
awk -v marks="$tmp/marks" '
    BEGIN { while ((getline l < marks) > 0) { split(l, a, " "); if (a[1] != "total") m[a[1]] = a[2] } }
    { px = $NF; label = $0; sub(/ [0-9]+$/, "", label)
      ins = m[2 * (NR - 1) + 1] - m[2 * (NR - 1)]
      if (NR == 1) { over = ins; next }
      if (!(label in sum)) order[++n] = label
      sum[label] += ins - over; pix[label] += px }
    END { for (i = 1; i <= n; i++) printf "%s\t%.1f\n", order[i], sum[order[i]] / pix[order[i]] }' "$tmp/labels"
