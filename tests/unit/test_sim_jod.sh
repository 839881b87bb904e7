#!/bin/sh
# tdc-sim --jod (sim/simulator/tdc_sim_jod.c): FovVideoVDP on the retinal
# signal.  A 64x64 pan at 90 Hz over 45 refreshes with modes full and trm50:
# jod.csv has one row per mode, JODs in (0, 10], the 23-refresh warm-up not
# pooled (22 pooled), TRM's JOD below full's (it shows half-resolution
# frames), jod_series.csv one row per mode and refresh with the warm-up
# marked; trm50 alone as with full (the reference shared); summary.csv's jod column and summary.md's leading JOD column; and
# the same JOD with 1 and 2 threads.
# Usage: tests/unit/test_sim_jod.sh TDC_SIM
sim=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "sim jod: FAIL: $*"; exit 1; }
for t in 1 2; do
    mkdir -p "$tmp/t$t"
    "$sim" -q -s pan -r 90 -g 64x64 --mono -m full,trm50 -n 45 --threads $t --jod -o "$tmp/t$t" > "$tmp/t$t/out" 2>&1 ||
        fail "tdc-sim --jod exited $?: $(tail -1 "$tmp/t$t/out")"
done
j=$tmp/t1/jod.csv
[ "$(head -1 "$j")" = "mode,eye,jod,jod_fovea,jod_periphery,frames_pooled" ] || fail "jod.csv header: $(head -1 "$j")"
[ "$(wc -l < "$j")" -eq 3 ] || fail "jod.csv has $(wc -l < "$j") lines, want 3"
awk -F, 'NR > 1 && !($3 > 0 && $3 <= 10 && $6 == 22) { bad = 1; print "bad row: " $0 } END { exit bad }' "$j" || fail "jod.csv rows"
full=$(awk -F, '$1 == "full" { print $3 }' "$j")
trm=$(awk -F, '$1 == "trm50" { print $3 }' "$j")
awk -v f="$full" -v t="$trm" 'BEGIN { exit !(t < f - 0.1) }' || fail "trm50 JOD $trm not below full $full"
cmp -s "$j" "$tmp/t2/jod.csv" || fail "1 and 2 threads differ: $(tr '\n' ' ' < "$tmp/t2/jod.csv")"
s=$tmp/t1/jod_series.csv
[ "$(wc -l < "$s")" -eq 91 ] || fail "jod_series.csv has $(wc -l < "$s") lines, want 1 + 2 x 45"
[ "$(awk -F, '$5 == 0' "$s" | wc -l)" -eq 46 ] || fail "warm-up rows: $(awk -F, '$5 == 0' "$s" | wc -l), want 2 x 23"
# trm50 judged alone (holding its own reference) = trm50 sharing full's.
mkdir -p "$tmp/alone"
"$sim" -q -s pan -r 90 -g 64x64 --mono -m trm50 -n 45 --jod -o "$tmp/alone" > /dev/null 2>&1 || fail "tdc-sim -m trm50 --jod exited $?"
alone=$(awk -F, '$1 == "trm50" { print $3 }' "$tmp/alone/jod.csv")
[ "$alone" = "$trm" ] || fail "trm50 alone $alone, sharing full's reference $trm"
# summary.csv carries the same JOD (mono: the one eye) and the report leads with it.
sc=$(head -1 "$tmp/t1/summary.csv" | tr , '\n' | grep -nx 'jod' | cut -d: -f1)
mc=$(head -1 "$tmp/t1/summary.csv" | tr , '\n' | grep -nx 'mode' | cut -d: -f1)
[ -n "$sc" ] || fail "summary.csv has no jod column"
sj=$(awk -F, -v m="$mc" -v c="$sc" '$m == "trm50" { print $c }' "$tmp/t1/summary.csv")
[ "$sj" = "$trm" ] || fail "summary.csv jod $sj, jod.csv $trm"
grep -q '^| mode | JOD | JOD fovea | JOD periphery | Hz |' "$tmp/t1/summary.md" || fail "summary.md does not lead with JOD"
echo "sim jod: ok (full $full, trm50 $trm)"
