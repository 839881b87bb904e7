#!/bin/sh
# Every LCD inverse through the simulator's whole path (issue 18): modes
# gamma, exact, od17, od33, state, state-pair on both LCD profiles at each of
# their rates (pg279q 120/144/165, lcd-240 144/240), with and without TRM
# (modes full and trm50), hold-type and strobed backlight.  Each run must be
# accepted by the firmware stage (no "refused" note), name its inverse, and
# give finite metrics; an unknown mode or bad backlight is a usage error.
# And on pg279q at 144 Hz the stateful inverse must beat plain gamma on TRM
# (FLIP lower), the property it exists for.
# Usage: tests/test_lcd_sim_modes.sh TDC_SIM
sim=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "lcd sim modes: FAIL: $*"; exit 1; }
runs=0
for pr in pg279q:120 pg279q:144 pg279q:165 lcd-240:144 lcd-240:240; do
    prof=${pr%%:*}; hz=${pr##*:}
    for mode in gamma exact od17 od33 state state-pair; do
        for bl in hold strobe; do
            out=$tmp/$prof-$hz-$mode-$bl.txt
            "$sim" -p lcd --profile "$prof" -r "$hz" -m full,trm50 -g 32x24 -n 6 -q --lcd-mode "$mode" \
                --backlight "$bl" > "$out" 2>&1 || fail "$prof $hz Hz $mode $bl: exit $? ($(tail -1 "$out"))"
            grep -q "refused" "$out" && fail "$prof $hz Hz $mode $bl: $(grep refused "$out" | head -1)"
            grep -q "LCD inverse $mode, 8-bit history" "$out" || fail "$prof $hz Hz $mode $bl: inverse not named"
            want=$([ "$bl" = hold ] && echo constant || echo strobed)
            grep -q "$want backlight" "$out" || fail "$prof $hz Hz $mode $bl: backlight not $want"
            grep -qi "nan\|inf " "$out" && fail "$prof $hz Hz $mode $bl: non-finite metric"
            runs=$((runs + 1))
        done
    done
done
echo "lcd sim modes: $runs runs (6 inverses x 5 profile rates x 2 backlights, each with and without TRM) accepted"
if "$sim" -p lcd --lcd-mode fastest -n 2 -q > "$tmp/e" 2>&1; then fail "unknown --lcd-mode accepted"; fi
grep -q "lcd-mode" "$tmp/e" || fail "no message naming --lcd-mode"
if "$sim" -p lcd --backlight strobe:0.8:0.5 -n 2 -q > "$tmp/e" 2>&1; then fail "strobe past the refresh accepted"; fi
# FLIP column of trm50 (6th field of the table row); lower is better.
flip() { awk -F'|' '$2 ~ /^ trm50 / { gsub(/ /, "", $6); print $6 }' "$1"; }
for m in gamma state-pair; do
    "$sim" -p lcd --profile pg279q -r 144 -m trm50 -g 64x48 -n 12 -q --lcd-mode $m > "$tmp/$m.txt" 2>&1 || fail "$m"
done
g=$(flip "$tmp/gamma.txt"); s=$(flip "$tmp/state-pair.txt")
echo "lcd sim modes: pg279q 144 Hz trm50 FLIP: gamma $g, state-pair $s"
awk -v g="$g" -v s="$s" 'BEGIN { exit !(s + 0 < g + 0) }' || fail "state-pair FLIP $s not below gamma $g"
echo "lcd sim modes: PASS"
