#!/bin/sh
# tdc-sim's judge (sim/simulator/tdc_sim_jod.c): FovVideoVDP on the retinal
# signal, on by default.  A 64x64 pan at 90 Hz over 45 refreshes with modes full and trm50:
# jod.csv has one row per mode, JODs in (0, 10], the 23-refresh warm-up not
# pooled (22 pooled), TRM's JOD below full's (it shows half-resolution
# frames), jod_series.csv one row per mode and refresh with the warm-up
# marked; trm50 alone as with full (the reference shared); summary.csv's jod column and summary.md's leading JOD column; and
# the same JOD with 1 and 2 threads; series.csv's jod column (the
# refresh's JOD from jod_series.csv, empty in the warm-up); the heat maps
# (trm50's visible difference above full's); --judge legacy (no JOD, said
# so), --metric-every 9 (JODs unchanged, the legacy cadence said), a run
# within the warm-up (not judged, said so), a bad --judge.
# Usage: tests/unit/test_sim_jod.sh TDC_SIM
sim=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "sim jod: FAIL: $*"; exit 1; }
for t in 1 2; do
    mkdir -p "$tmp/t$t"
    "$sim" -q -s pan -r 90 -g 64x64 --mono -m full,trm50 -n 45 --threads $t -o "$tmp/t$t" > "$tmp/t$t/out" 2>&1 ||
        fail "tdc-sim (default judge) exited $?: $(tail -1 "$tmp/t$t/out")"
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
"$sim" -q -s pan -r 90 -g 64x64 --mono -m trm50 -n 45 --judge jod -o "$tmp/alone" > /dev/null 2>&1 || fail "tdc-sim -m trm50 --judge jod exited $?"
alone=$(awk -F, '$1 == "trm50" { print $3 }' "$tmp/alone/jod.csv")
[ "$alone" = "$trm" ] || fail "trm50 alone $alone, sharing full's reference $trm"
# summary.csv carries the same JOD (mono: the one eye) and the report leads with it.
sc=$(head -1 "$tmp/t1/summary.csv" | tr , '\n' | grep -nx 'jod' | cut -d: -f1)
mc=$(head -1 "$tmp/t1/summary.csv" | tr , '\n' | grep -nx 'mode' | cut -d: -f1)
[ -n "$sc" ] || fail "summary.csv has no jod column"
sj=$(awk -F, -v m="$mc" -v c="$sc" '$m == "trm50" { print $c }' "$tmp/t1/summary.csv")
[ "$sj" = "$trm" ] || fail "summary.csv jod $sj, jod.csv $trm"
grep -q '^| mode | JOD | JOD fovea | JOD periphery | Hz |' "$tmp/t1/summary.md" || fail "summary.md does not lead with JOD"
# series.csv: jod last; a pooled row's value is jod_series.csv's for the
# refresh ending at its t (t = (refresh + 1) / 90); warm-up rows empty.
se=$tmp/t1/series.csv
[ "$(head -1 "$se")" = "mode,eval,t,psnr,ssim,flip,legacy_flicker,jod" ] || fail "series.csv header: $(head -1 "$se")"
sv=$(awk -F, '$1 == "trm50" && $2 == 40 { print $8 }' "$se")
st=$(awk -F, '$1 == "trm50" && $2 == 40 { printf "%d", $3 * 90 + 0.5 }' "$se")
jv=$(awk -F, -v r=$((st - 1)) '$1 == "trm50" && $3 == r { print $6 }' "$s")
[ -n "$sv" ] && [ "$sv" = "$jv" ] || fail "series.csv trm50 eval 40 jod '$sv', jod_series.csv refresh $((st - 1)): '$jv'"
[ -z "$(awk -F, '$1 == "trm50" && $2 == 0 { print $8 }' "$se")" ] || fail "series.csv: a warm-up row has a jod"
# heat maps: eye 0 of each mode; trm50's (half-resolution frames) carries
# more visible difference than full's: mean tint (red + green - 2 blue) larger.
for m in full trm50; do [ -s "$tmp/t1/heatmap_$m.png" ] || fail "no heatmap_$m.png"; done
tint() { /usr/bin/python3 -c 'import sys, matplotlib.image as mi; a = mi.imread(sys.argv[1]) * 255
print((a[..., 0] + a[..., 1] - 2 * a[..., 2]).mean())' "$1"; }
hf=$(tint "$tmp/t1/heatmap_full.png") && ht=$(tint "$tmp/t1/heatmap_trm50.png") || fail "heat maps unreadable"
awk -v f="$hf" -v t="$ht" 'BEGIN { exit !(t > f + 20) }' || fail "heat map tint: trm50 $ht not above full $hf"
# --judge legacy: no JOD anywhere, and the report says which judge it used.
mkdir -p "$tmp/leg"
"$sim" -q -s pan -r 90 -g 64x64 --mono -m full,trm50 -n 45 --judge legacy -o "$tmp/leg" > /dev/null 2>&1 || fail "--judge legacy exited $?"
[ ! -e "$tmp/leg/jod.csv" ] && [ ! -e "$tmp/leg/heatmap_full.png" ] || fail "--judge legacy wrote jod.csv or a heat map"
grep -q '^Judge: legacy' "$tmp/leg/summary.md" || fail "--judge legacy: summary.md does not say so"
grep -q '| JOD' "$tmp/leg/summary.md" && fail "--judge legacy: summary.md has a JOD column"
# --metric-every 9 (the legacy columns at a sparse cadence): the same JODs
# and JOD series bit for bit, fewer legacy rows, and the reports say so
mkdir -p "$tmp/k9"
"$sim" -q -s pan -r 90 -g 64x64 --mono -m full,trm50 -n 45 --metric-every 9 -o "$tmp/k9" > /dev/null 2>&1 ||
    fail "--metric-every 9 exited $?"
cmp -s "$j" "$tmp/k9/jod.csv" && cmp -s "$s" "$tmp/k9/jod_series.csv" || fail "--metric-every 9 changed the JODs"
[ "$(wc -l < "$tmp/k9/series.csv")" -lt "$(wc -l < "$se")" ] || fail "--metric-every 9: as many legacy rows as every refresh"
grep -q '^Legacy columns .* every 9th refresh only .*; JOD at every refresh' "$tmp/k9/summary.md" ||
    fail "--metric-every 9: summary.md does not say the legacy cadence"
grep -q '^Legacy columns' "$tmp/t1/summary.md" && fail "every refresh: summary.md has a cadence note"
# a run no longer than the warm-up (23 refreshes at 90 Hz): not judged, said so
mkdir -p "$tmp/short"
"$sim" -q -s pan -r 90 -g 64x64 --mono -m full -n 23 -o "$tmp/short" > /dev/null 2>&1 || fail "-n 23 exited $?"
[ ! -e "$tmp/short/jod.csv" ] && grep -q '^JOD: n/a' "$tmp/short/summary.md" || fail "-n 23: judged, or not said so"
"$sim" -q -s pan -r 90 -g 64x64 --mono -m full -n 4 --judge bogus > /dev/null 2>&1
[ $? -eq 1 ] || fail "--judge bogus: exit $?, want 1 (ARGS)"
echo "sim jod: ok (full $full, trm50 $trm; heat-map tint full $hf, trm50 $ht)"
