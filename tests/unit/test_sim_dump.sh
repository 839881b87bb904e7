#!/bin/sh
# test_sim_dump.sh TDC_SIM - tdc-sim --dump DIR (docs/eye.md): the files a
# run writes for an external metric, their sizes and headers, and the named
# exit codes of a write that fails and of out-of-range display and gaze
# parameters.  A few seconds on 32x32.
set -u
SIM=${1:?usage: test_sim_dump.sh TDC_SIM}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fail() { echo "test_sim_dump: FAIL: $*"; exit 1; }

# 1. a mono OLED run: 4 refreshes at 90 Hz, persistence 0.2 -> 5 steps each
"$SIM" -q --mono -g 32x32 -n 4 -m full,bfi --dump "$T/d" > "$T/out.md" 2> "$T/err" || fail "dump run exit $? ($(cat "$T/err"))"
for s in ref full bfi; do
    n=$(ls "$T/d/$s" | grep -c '^codes_.*\.png$')
    [ "$n" = 4 ] || fail "$s: $n codes PNGs, expected 4 (one per refresh)"
    for k in emitted retina; do
        n=$(ls "$T/d/$s" | grep -c "^${k}_.*\\.png\$")
        [ "$n" = 20 ] || fail "$s: $n $k PNGs, expected 20 (5 steps x 4 refreshes)"
    done
    # Y4M: header line + 20 x ("FRAME\n" + 32 * 32 * 2 bytes)
    head -c 60 "$T/d/$s/retina.y4m" | head -1 | grep -q '^YUV4MPEG2 W32 H32 F450000000:1000000 Ip A1:1 Cmono16$' ||
        fail "$s: y4m header: $(head -1 "$T/d/$s/retina.y4m")"
    hl=$(head -1 "$T/d/$s/retina.y4m" | wc -c)
    sz=$(wc -c < "$T/d/$s/retina.y4m")
    [ "$sz" = $((hl + 20 * (6 + 2048))) ] || fail "$s: y4m is $sz bytes"
done
python3 - "$T/d" <<'EOF' || fail "dump.json / PNG check"
import json, struct, sys, zlib
d = sys.argv[1]
j = json.load(open(d + "/dump.json"))
assert j["steps"] == 20 and j["fps"] == 450.0 and j["steps_per_refresh"] == 5, j
disp = j["display"]
assert disp["panel"] == "htc-vive" and disp["peak_cdm2"] == 133.0 and disp["ppd"] == 11.4, disp
assert j["linear"]["full_scale_cdm2"] == 665.0 and j["streams"] == ["ref", "full", "bfi"], j
rows = open(d + "/steps.csv").read().splitlines()
assert len(rows) == 21 and rows[0].startswith("eye,step,refresh,t0,t1,gaze_x"), rows[:2]

def png(path):
    b = open(path, "rb").read()
    assert b[:8] == b"\x89PNG\r\n\x1a\n"
    w, h, depth, ctype = struct.unpack(">IIBB", b[16:26])
    data, i = b"", 8
    while i < len(b):
        n, t = struct.unpack(">I4s", b[i:i + 8])
        if t == b"IDAT":
            data += b[i + 8:i + 8 + n]
        i += 12 + n
    raw = zlib.decompress(data)
    return w, h, depth, ctype, raw

# 16-bit linear RGB; the BFI's second refresh (steps 5..9) is black, its lit
# step carries 5x the mean light of the reference's refresh
w, h, depth, ctype, _ = png(d + "/bfi/retina_000005.png")
assert (w, h, depth, ctype) == (32, 32, 16, 2), (w, h, depth, ctype)
y4m = open(d + "/bfi/retina.y4m", "rb").read()
hl = y4m.index(b"\n") + 1
fr = [y4m[hl + k * 2054 + 6: hl + (k + 1) * 2054] for k in range(20)]
lum = [sum(struct.unpack("<1024H", f)) / 1024 for f in fr]
assert max(lum[5:10]) < 0.01 * lum[0] and lum[0] > 100 and lum[10] > 100, lum
ref = open(d + "/ref/retina.y4m", "rb").read()
rl = [sum(struct.unpack("<1024H", ref[hl + k * 2054 + 6: hl + (k + 1) * 2054])) / 1024 for k in range(20)]
assert rl[5] > 100 and all(v == 0 for v in rl[1:5]), rl
EOF

# the same bytes with 1 and 2 threads
"$SIM" -q --threads 1 --mono -g 32x32 -n 4 -m full,bfi --dump "$T/t1" > /dev/null 2>&1 || fail "1-thread run"
for f in $(cd "$T/d" && find . -type f | sort); do
    cmp -s "$T/d/$f" "$T/t1/$f" || fail "$f differs between 1 and 2 threads"
done

# pursuit lag: the eye starts pursuing 100 px/s 50 ms late (shift 0 up to
# the middle of step 4 at 50 ms, then 100 px/s x (61.1 ms - 50 ms))
"$SIM" -q --mono -g 32x32 -n 7 -m full --retina-steps 1 --speed 100 --pursuit-lag 50 --dump "$T/lag" > /dev/null 2>&1 ||
    fail "lag run"
[ "$(awk -F, '$2 == 4 { print $10 } $2 == 5 { print $10 }' "$T/lag/steps.csv" | tr '\n' ' ')" = "0.0000 1.1111 " ] ||
    fail "pursuit lag: $(cut -d, -f2,10 "$T/lag/steps.csv" | tr '\n' ' ')"

# 2. a write that fails mid-run: a folder where the video goes -> FILE (7), no dump.json
mkdir -p "$T/e/full/retina.y4m"
"$SIM" -q --mono -g 32x32 -n 2 -m full --dump "$T/e" > /dev/null 2> "$T/err"
rc=$?
[ "$rc" = 7 ] || fail "write failure: exit $rc, expected 7 (FILE)"
[ "$(wc -l < "$T/err")" = 1 ] && grep -q '^tdc-sim: --dump: cannot write .*retina.y4m' "$T/err" || fail "message: $(cat "$T/err")"
[ ! -e "$T/e/dump.json" ] || fail "dump.json written after a failed write"
# a dump folder that cannot be created
: > "$T/file"
"$SIM" -q --mono -g 32x32 -n 2 -m full --dump "$T/file/x" > /dev/null 2>&1
[ $? = 7 ] || fail "uncreatable folder: not exit 7"

# 3. display and gaze parameters out of range -> ARGS (1), one line
for a in "--gaze fixed --gaze-at 40,5" "--retina-steps 0" "--retina-steps 2.5" "-r 1000 --retina-steps 8" \
         "--pursuit-lag -1" "--pursuit-lag 600" "--dump ''" "-r 0" "-g 4x4"; do
    eval "\"\$SIM\" -q --mono -g 32x32 -n 2 -m full --dump \"\$T/a\" $a" > /dev/null 2> "$T/err"
    rc=$?
    [ "$rc" = 1 ] || fail "'$a': exit $rc, expected 1 (ARGS)"
    [ "$(wc -l < "$T/err")" = 1 ] || fail "'$a': $(cat "$T/err")"
done
echo "test_sim_dump: OK"
