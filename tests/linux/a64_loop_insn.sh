#!/bin/sh
# Instructions per shown pixel of the arm64 board program's whole frame
# loop (link decode, stages, the panel checksum) under qemu-aarch64, two
# builds on the same stream: A (NEON) and B (the same program with the
# NEON D passes bound to C, tests/linux/trm_dpass_c.c).  The counting
# plugin (tests/arm/tdc_insn_plugin.c) records its count at every
# tdc_board_panel_show; frame k's cost is the count between shows k-1 and
# k (frame 0, with start-up, is left out).  The two programs must show the
# same frames (checksums), else exit 1.
# Usage: tests/linux/a64_loop_insn.sh PLUGIN PROGRAM_A PROGRAM_B STREAM PIXELS
set -eu
plugin=$1; a=$2; b=$3; stream=$4; px=$5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for p in a b; do
    eval prog=\$$p
    mark=$(aarch64-linux-gnu-nm "$prog" | awk '$3 == "tdc_board_panel_show" { print "0x" $1 }')
    [ -n "$mark" ] || { echo "a64_loop_insn: no tdc_board_panel_show in $prog" >&2; exit 1; }
    qemu-aarch64 -plugin "$plugin,mark=$mark,out=$tmp/marks-$p" "$prog" --stream "$stream" --no-display > "$tmp/frames-$p" \
        2> "$tmp/log-$p" || { cat "$tmp/log-$p" >&2; echo "a64_loop_insn: $prog failed" >&2; exit 1; }
done
cmp -s "$tmp/frames-a" "$tmp/frames-b" || { echo "a64_loop_insn: the two programs show different frames" >&2; exit 1; }
echo "frames identical: $(grep -c '^frame' "$tmp/frames-a") ($(basename "$stream"))"
awk -v px="$px" -v fa="$tmp/marks-a" -v fb="$tmp/marks-b" '
    function load(f, m,   l, x) { while ((getline l < f) > 0) { split(l, x, " "); if (x[1] != "total") m[x[1]] = x[2] } }
    BEGIN { load(fa, A); load(fb, B)
            printf "  frame   %-22s %-22s ratio\n", "A (NEON) instr/px", "B (C) instr/px"
            for (k = 1; (k in A) && (k in B); k++) {
                da = A[k] - A[k - 1]; db = B[k] - B[k - 1]; sa += da; sb += db; n++
                printf "  %5d   %-22.1f %-22.1f %.3f\n", k, da / px, db / px, db / da }
            if (n) printf "  mean    %-22.1f %-22.1f %.3f (B - A: %.1f instr/px, %.1f %% of B)\n", sa / n / px, sb / n / px, sb / sa, (sb - sa) / n / px, 100 * (sb - sa) / sb }'
