#!/bin/sh
# test_sim_image.sh TDC_SIM PHOTO_DIR - tdc-sim --image end to end: a run on
# a Debian photograph (mate-backgrounds) at small size gives finite metrics,
# the full mode beats half rate under a pan; every bad input is one line on
# stderr naming the file, exit FILE (7) or INPUT (13), and no summary passed off as a result.
set -u
SIM=$1; PHOTOS=$2
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
fail=0
ok() { echo "ok: $*"; }
bad() { echo "FAIL: $*"; fail=1; }
photo=$PHOTOS/Storm.jpg
[ -r "$photo" ] || { echo "FAIL: $photo missing (make deps installs mate-backgrounds)"; exit 1; }
if "$SIM" -q --image "$photo" -g 96x64 -r 90 -m full,half -n 10 --speed 400 --zoom 0.5 --rotate 10 \
        -o "$T/run" > "$T/out.txt" 2> "$T/err.txt"; then
    # columns by header name: mode, psnr_db
    mc=$(head -1 "$T/run/summary.csv" | tr , '\n' | grep -nx 'mode' | cut -d: -f1)
    col=$(head -1 "$T/run/summary.csv" | tr , '\n' | grep -nx 'psnr_db' | cut -d: -f1)
    pf=$(awk -F, -v m="$mc" -v c="$col" '$m=="full"{print $c}' "$T/run/summary.csv")
    ph=$(awk -F, -v m="$mc" -v c="$col" '$m=="half"{print $c}' "$T/run/summary.csv")
    if awk -v a="$pf" -v b="$ph" 'BEGIN{exit !(a > b && a > 20 && a < 200)}'; then
        ok "full PSNR $pf dB > half $ph dB on a moving photograph"
    else bad "PSNR full '$pf' half '$ph'"; fi
else bad "photo run failed: $(cat "$T/err.txt")"; fi
: > "$T/empty.png"
head -c 3000 "$photo" > "$T/cut.jpg"
printf 'not an image' > "$T/junk.jpg"
for f in "$T/missing.jpg" "$T/empty.png" "$T/cut.jpg" "$T/junk.jpg"; do
    "$SIM" -q --image "$f" -g 32x32 -n 4 -o "$T/bad" > "$T/o.txt" 2> "$T/e.txt"; rc=$?
    lines=$(wc -l < "$T/e.txt")
    want=13; [ "$f" = "$T/missing.jpg" ] && want=7   # FILE for an unreadable file, INPUT for bad contents
    if [ "$rc" -eq "$want" ] && [ "$lines" -eq 1 ] && grep -q "$f" "$T/e.txt" && [ ! -s "$T/o.txt" ] \
            && [ ! -e "$T/bad/summary.csv" ]; then
        ok "$(cat "$T/e.txt")"
    else bad "bad input $f: exit $rc, stderr: $(cat "$T/e.txt")"; fi
done
for a in "--zoom 0" "--zoom-rate 99" "--rotate x"; do
    # shellcheck disable=SC2086
    "$SIM" -q --image "$photo" $a -g 32x32 -n 4 > /dev/null 2> "$T/e.txt"; rc=$?
    [ "$rc" -eq 1 ] && [ "$(wc -l < "$T/e.txt")" -eq 1 ] && ok "$a: $(cat "$T/e.txt")" || bad "$a: exit $rc"
done
exit $fail
