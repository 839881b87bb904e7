#!/bin/sh
# The calibration loop end to end (issue 3): measure the simulated panel as
# paper Fig. 7 does (tdc-lcd-measure), fit (tdc-calib), generate the
# firmware tables (tdc-tablegen) and compile them with the firmware flags.
# Also: the fitted gamma recovers the simulated panel's static gamma; the
# shipped profiles are exactly what the loop produces (make lcd-profiles);
# bad measurement files are rejected with a message and a non-zero exit.
# Usage: tests/unit/test_lcd_calib.sh MEASURE CALIB TABLEGEN "CC FW_CFLAGS..."
measure=$1; calib=$2; tablegen=$3; cc=$4
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail() { echo "calib loop: FAIL: $*"; exit 1; }

# 1. measure -> fit -> profile -> tables -> firmware compile
"$measure" sim/lcd/panels/pg279q.lcdsim 120,165 --grid 9 --integration 0.5 --noise 0.002 --seed 3 \
    -o "$tmp/m.csv" || fail "tdc-lcd-measure"
"$calib" "$tmp/m.csv" -o "$tmp/t.panel" --name calib-test --width 64 --height 32 --table 17 > "$tmp/fit.txt" \
    || fail "tdc-calib"
cat "$tmp/fit.txt"
grep -q "fit RMSE" "$tmp/fit.txt" || fail "no RMSE printed"
grep -q "^type        lcd" "$tmp/t.panel" || fail "profile is not an LCD profile"
# fitted gamma within 0.02 of the simulated panel's (2.25 2.20 2.15)
awk '/^gamma R G B:/ { if ($5 < 2.23 || $5 > 2.27 || $6 < 2.18 || $6 > 2.22 || $7 < 2.13 || $7 > 2.17) exit 1 }' \
    "$tmp/fit.txt" || fail "gamma not recovered: $(grep '^gamma' "$tmp/fit.txt")"
"$tablegen" "$tmp/t.panel" "$tmp" || fail "tdc-tablegen rejected the profile"
$cc -I"$tmp" -c "$tmp/tdc_panel_calib-test.c" -o "$tmp/p.o" || fail "generated tables do not compile"
echo "calib loop: profile -> tables -> firmware compile OK"

# 2. the shipped profiles are the loop's output (same flags as make lcd-profiles)
flags="--grid 17 --integration 1 --noise 0.002 --seed 1"
tflags="--transitions --grid 33 --runs 2 --noise 0.002 --seed 2"
"$measure" sim/lcd/panels/pg279q.lcdsim 120,144,165 $flags -o "$tmp/pg.csv" || fail measure
"$measure" sim/lcd/panels/pg279q.lcdsim 120,144,165 $tflags -o "$tmp/pgt.csv" || fail measure
"$calib" "$tmp/pg.csv" -o "$tmp/pg279q.panel" --name pg279q --width 2560 --height 1440 --refresh 144 --table 33 \
    --transitions "$tmp/pgt.csv" --peak-cdm2 350 --black-cdm2 0.35 --distance-m 0.6 \
    --photometry-note "ASUS PG279Q data sheet: 350 cd/m^2, 1000:1; desk distance" --note "x" > /dev/null || fail calib
"$measure" sim/lcd/panels/lcd-240.lcdsim 144,240 $flags -o "$tmp/l.csv" || fail measure
"$measure" sim/lcd/panels/lcd-240.lcdsim 144,240 --transitions --grid 33 --runs 8 --noise 0.002 --seed 2 \
    -o "$tmp/lt.csv" || fail measure
"$calib" "$tmp/l.csv" -o "$tmp/lcd-240.panel" --name lcd-240 --width 1920 --height 1080 --refresh 240 --table 33 \
    --transitions "$tmp/lt.csv" --state-table 65 --smooth --peak-cdm2 400 --black-cdm2 0.4 --distance-m 0.6 \
    --photometry-note "assumed, not measured: a typical 240 Hz gaming LCD data sheet value, 1000:1; desk distance" \
    --note "x" > /dev/null || fail calib
for p in pg279q lcd-240; do
    grep -v '^#' "boards/panels/$p.panel" > "$tmp/a"; grep -v '^#' "$tmp/$p.panel" > "$tmp/b"
    cmp -s "$tmp/a" "$tmp/b" || { diff "$tmp/a" "$tmp/b"; fail "boards/panels/$p.panel is not what make lcd-profiles makes"; }
done
echo "calib loop: shipped profiles pg279q and lcd-240 reproduce from the simulated panels"

# 3. bad input: clear message, non-zero exit, no profile written
printf 'not,a,header\n' > "$tmp/bad1.csv"
head -3 "$tmp/m.csv" > "$tmp/bad2.csv"; echo "120,R,0,0,0.07" >> "$tmp/bad2.csv"      # no white rows
head -3 "$tmp/m.csv" > "$tmp/bad3.csv"; echo "120,Q,0,0,0.07" >> "$tmp/bad3.csv"      # bad channel
head -3 "$tmp/m.csv" > "$tmp/bad4.csv"; echo "120,R,0,0,abc" >> "$tmp/bad4.csv"       # not a number
for b in bad1 bad2 bad3 bad4 missing; do
    rm -f "$tmp/out.panel"
    if "$calib" "$tmp/$b.csv" -o "$tmp/out.panel" --name x --width 1 --height 1 > "$tmp/err.txt" 2>&1; then
        fail "$b accepted"
    fi
    [ -s "$tmp/err.txt" ] || fail "$b: no message"
    [ -e "$tmp/out.panel" ] && fail "$b: a profile was written"
    echo "calib loop: $b rejected: $(head -1 "$tmp/err.txt")"
done
# 4. issue 19: an error never truncates an existing profile (written to .tmp,
#    renamed on success); a 4th rate is refused (a profile holds 3, the table
#    generator's limit); options and fields do not wrap around.
cp "$tmp/t.panel" "$tmp/keep.panel"
if "$calib" "$tmp/m.csv" -o "$tmp/keep.panel" --name x --width 8 --height 8 --refresh 60 > "$tmp/err.txt" 2>&1; then
    fail "--refresh 60 (not measured) accepted"
fi
cmp -s "$tmp/t.panel" "$tmp/keep.panel" || fail "a failed run changed the existing profile ($(wc -c < "$tmp/keep.panel") bytes)"
[ -e "$tmp/keep.panel.tmp" ] && fail "temporary file left behind"
grep -q "not measured" "$tmp/err.txt" || fail "no message for --refresh 60: $(cat "$tmp/err.txt")"
"$measure" sim/lcd/panels/pg279q.lcdsim 120,144,165,200 --grid 5 --integration 0.2 -o "$tmp/4r.csv" || fail measure
if "$calib" "$tmp/4r.csv" -o "$tmp/4r.panel" --name x --width 8 --height 8 > "$tmp/err.txt" 2>&1; then
    fail "4 refresh rates accepted (tdc-tablegen takes 3)"
fi
grep -q "4r.csv:[0-9]*: field rate_hz" "$tmp/err.txt" || fail "4 rates: message does not name file, line, field"
for opt in "--width 4294967306" "--height -1" "--refresh 4294967297" "--eyes 3" "--width 12abc"; do
    # shellcheck disable=SC2086
    if "$calib" "$tmp/m.csv" -o "$tmp/w.panel" --name x --width 8 --height 8 $opt > "$tmp/err.txt" 2>&1; then
        fail "$opt accepted"
    fi
    [ -e "$tmp/w.panel" ] && fail "$opt: a profile was written"
    grep -q -- "${opt%% *}" "$tmp/err.txt" || fail "$opt: message does not name the option"
done
head -3 "$tmp/m.csv" > "$tmp/wrap.csv"; echo "120,R,4294967299,0,0.07" >> "$tmp/wrap.csv"
"$calib" "$tmp/wrap.csv" -o "$tmp/w.panel" --name x --width 8 --height 8 > "$tmp/err.txt" 2>&1 && fail "code 4294967299 accepted"
grep -q "wrap.csv:4: field code_a" "$tmp/err.txt" || fail "wrapped code: $(cat "$tmp/err.txt")"
# named exit codes (common/tdc_tool.h): ARGS 1, FILE 7, INPUT 13
code() { "$@" > /dev/null 2>&1; echo $?; }
[ "$(code "$calib" "$tmp/m.csv" -o "$tmp/w.panel" --name x --width 8 --height 8 --width 0)" = 1 ] || fail "bad option: not ARGS"
[ "$(code "$calib" "$tmp/none.csv" -o "$tmp/w.panel" --name x --width 8 --height 8)" = 7 ] || fail "missing file: not FILE"
[ "$(code "$calib" "$tmp/bad1.csv" -o "$tmp/w.panel" --name x --width 8 --height 8)" = 13 ] || fail "bad header: not INPUT"
[ "$(code "$measure" sim/lcd/panels/pg279q.lcdsim 120 --grid 4294967313 -o "$tmp/x.csv")" = 1 ] || fail "measure --grid wrap: not ARGS"
[ "$(code "$measure" sim/lcd/panels/pg279q.lcdsim 120 -o "$tmp/no/such/dir.csv")" = 7 ] || fail "measure unwritable: not FILE"
echo "calib loop: no truncation on error, 4 rates refused, wrapping numbers refused, named exit codes"

# 5. transitions: the stateful tables are fitted with per-class errors; every
#    kind of bad transition file is refused naming file, line and field.
"$measure" sim/lcd/panels/pg279q.lcdsim 120,165 --transitions --grid 17 --runs 2 --noise 0.002 --seed 4 \
    -o "$tmp/tr.csv" || fail "tdc-lcd-measure --transitions"
"$calib" "$tmp/m.csv" -o "$tmp/s.panel" --name calib-test --width 64 --height 32 --transitions "$tmp/tr.csv" \
    --state-table 17 > "$tmp/fit.txt" || fail "tdc-calib --transitions: $(tail -2 "$tmp/fit.txt")"
for cls in rise fall "small step" "full swing"; do
    grep -q "  $cls .*light RMS" "$tmp/fit.txt" || fail "no fit error for class $cls"
done
grep -q "^lcd_state_n 17" "$tmp/s.panel" || fail "no stateful tables in the profile"
"$tablegen" "$tmp/s.panel" "$tmp" || fail "tdc-tablegen rejected the stateful profile"
$cc -I"$tmp" -c "$tmp/tdc_panel_calib-test.c" -o "$tmp/p2.o" || fail "generated stateful tables do not compile"
hdr=$(grep -n '^rate_hz' "$tmp/tr.csv" | cut -d: -f1)
bad() { # name, awk program over the data rows (NR > hdr); expect the message to match $3
    awk -F, -v OFS=, -v h="$hdr" "NR <= h { print; next } $2" "$tmp/tr.csv" > "$tmp/$1.csv"
    rm -f "$tmp/o.panel"
    if "$calib" "$tmp/m.csv" -o "$tmp/o.panel" --name x --width 8 --height 8 --transitions "$tmp/$1.csv" \
        > "$tmp/err.txt" 2>&1; then fail "transitions $1 accepted"; fi
    [ -e "$tmp/o.panel" ] && fail "transitions $1: a profile was written"
    grep -q "$3" "$tmp/err.txt" || fail "transitions $1: message '$(cat "$tmp/err.txt")' lacks '$3'"
    echo "calib loop: transitions $1 rejected: $(cat "$tmp/err.txt")"
}
bad missing '!($3 == 64 && $4 == 128 && $2 == "G") { print }' "transition prev_code 64 -> code 128 missing"
bad grid '{ if ($4 == 64) $4 = 65; print }' "not the regular"
bad nan '{ if (NR == h + 40) $6 = "nan"; print }' "tr.csv\|nan.csv:[0-9]*: field light_cd_m2"
bad nonmono '{ if ($1 == 120 && $2 == "R" && $3 == 128 && $4 == 191) $6 = $6 / 3; print }' "nonmono.csv:[0-9]*: .*field light_cd_m2: falls"
bad noisy '{ if ($5 == 1) { $6 = $6 * (1 + 0.5 * sin(NR)); $7 = $7 * (1 + 0.5 * cos(NR)) } print }' "too noisy"
bad unreach '{ if ($2 == "B" && $3 == 128 && $1 == 165) { $6 = $6 * 0.3; $7 = $7 * 0.3 } print }' "own static light is out of reach"
bad toomany '{ print; if ($1 == 165) { $1 = 200; print; $1 = 240; print } }' "field rate_hz"
echo "calib loop: PASS"
