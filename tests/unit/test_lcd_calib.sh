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
"$measure" sim/lcd/panels/pg279q.lcdsim 120,144,165 $flags -o "$tmp/pg.csv" || fail measure
"$calib" "$tmp/pg.csv" -o "$tmp/pg279q.panel" --name pg279q --width 2560 --height 1440 --refresh 144 --table 33 \
    --note "x" > /dev/null || fail calib
"$measure" sim/lcd/panels/lcd-240.lcdsim 144,240 $flags -o "$tmp/l.csv" || fail measure
"$calib" "$tmp/l.csv" -o "$tmp/lcd-240.panel" --name lcd-240 --width 1920 --height 1080 --refresh 240 --table 33 \
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
echo "calib loop: PASS"
