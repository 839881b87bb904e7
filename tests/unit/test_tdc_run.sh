#!/bin/sh
# tdc-run end to end: happy paths agree bit for bit, every bad input gets a
# message and the right exit code.  Usage: tests/unit/test_tdc_run.sh PATH/TO/tdc-run
run=$1
. tests/unit/tool_expect.sh
expect 0 "--help" "usage: tdc-run" -- "$run" --help
expect 1 "no arguments" "no output folder" -- "$run"
expect 1 "unknown panel" "tdc-run: unknown panel 'nope': known panels" -- "$run" -o "$t/o" -p nope x.png
expect 1 "ratio below 1/4" "--ratio must be" -- "$run" -o "$t/o" -r 1/5 x.png
expect 1 "bad frames pattern" "--frames must be" -- "$run" -o "$t/o" -f RF x.png
expect 1 "unknown option" "unknown option" -- "$run" --bogus
expect 7 "missing file" "cannot open" -- "$run" -o "$t/o" "$t/nothere.png"
printf 'not a png' > "$t/junk.png"
expect 13 "not a PNG" "not a PNG" -- "$run" -o "$t/o" "$t/junk.png"
expect 14 "TRM below 90 Hz refused" "refused" -- "$run" -o "$t/o" --refresh 60 --builtin edge --count 2 --size 32x16
# Exit codes are the shared table (docs/tools.md); numbers that do not fit
# are refused, never wrapped (issue 19: 4294967297 Hz passed as 1 Hz,
# 4294967312x16 as 16x16)
expect 1 "--refresh 2^32+1 refused" "--refresh must be 1..1000 Hz, got '4294967297'" -- "$run" -o "$t/o" --refresh 4294967297 --builtin edge
expect 1 "--size 2^32+16 refused" "--size must be WxH" -- "$run" -o "$t/o" --size 4294967312x16 --builtin edge
expect 1 "--count 2^32+1 refused" "--count must be" -- "$run" -o "$t/o" --count 4294967297 --builtin edge
expect 1 "--ratio 2^32+1/2 refused" "--ratio must be" -- "$run" -o "$t/o" -r 4294967297/2 --builtin edge
expect 1 "--sigma nan refused" "--sigma must be" -- "$run" -o "$t/o" --sigma nan --builtin edge
expect 1 "--sensitivity inf refused" "--sensitivity must be" -- "$run" -o "$t/o" -s inf --builtin edge

# built-in run: N drive frames and a CSV row each
"$run" -q -o "$t/a" --builtin text --count 6 --size 40x30 --frames auto --perceived || bad "builtin run"
n=$(ls "$t/a"/drive_*.png 2>/dev/null | wc -l); rows=$(($(wc -l < "$t/a/stats.csv") - 1))
[ "$n" -eq 6 ] && [ "$rows" -eq 6 ] && ok "6 drive frames and 6 CSV rows" || bad "drive frames $n, rows $rows"
[ "$(ls "$t/a"/perceived_*.png | wc -l)" -eq 5 ] && ok "perceived frames" || bad "perceived frames"
grep -q '^1,0,reduced,' "$t/a/stats.csv" && ok "frame 1 is reduced" || bad "frame kinds in CSV"

# r = 1 passes frames through unchanged: use it to write the inputs as files,
# then files in --frames auto must give the same bytes as the built-in run
"$run" -q -o "$t/in" -r 1 --builtin text --count 6 --size 40x30 || bad "pass-through run"
grep -q ',pass,' "$t/in/stats.csv" && ok "r=1 runs no TRM (pass)" || bad "r=1 not pass-through"
"$run" -q -o "$t/b" --frames auto "$t/in"/drive_*.png || bad "file run"
same=1; for f in "$t/a"/drive_*.png; do cmp -s "$f" "$t/b/$(basename "$f")" || same=0; done
[ $same -eq 1 ] && ok "files and built-in content give identical drive frames" || bad "file vs built-in differ"

# alternate mode: a reduced frame of the wrong size is rejected with the sizes
expect 13 "reduced frame size mismatch" "reduced frame is 40x30, expected 20x15" -- "$run" -o "$t/c" "$t/in/drive_00000.png" "$t/in/drive_00001.png"
# a full frame of another size
"$run" -q -o "$t/small" -r 1 --builtin edge --count 1 --size 20x10 || bad "small run"
expect 13 "full frame size mismatch" "expected 40x30" -- "$run" -o "$t/d" -f FF "$t/in/drive_00000.png" "$t/small/drive_00000.png"
# stereo needs auto and works
expect 1 "stereo without auto" "--stereo needs --frames auto" -- "$run" -o "$t/e" --stereo x.png
"$run" -q -o "$t/s" --stereo --frames auto --builtin edge --count 4 --size 64x20 && \
    grep -q '^1,1,full,' "$t/s/stats.csv" && grep -q '^1,0,reduced,' "$t/s/stats.csv" && ok "stereo eyes alternate" || bad "stereo"
# the portable and the AVX2 row kernels give the same drive frames through
# the whole tool (on a CPU without AVX2 only the refusal is checked)
expect 1 "bad --kernels" "--kernels must be auto, c or avx2" -- "$run" -o "$t/k" --kernels neon --builtin edge
"$run" -q -o "$t/kc" --kernels c --builtin text --count 6 --size 97x67 --frames auto || bad "--kernels c run"
if "$run" -q -o "$t/kv" --kernels avx2 --builtin text --count 6 --size 97x67 --frames auto 2> "$t/kv.err"; then
    same=1; for f in "$t/kc"/drive_*.png; do cmp -s "$f" "$t/kv/$(basename "$f")" || same=0; done
    # every column but the last (firmware_us, a time)
    [ $same -eq 1 ] && [ "$(sed 's/,[^,]*$//' "$t/kc/stats.csv")" = "$(sed 's/,[^,]*$//' "$t/kv/stats.csv")" ] && \
        ok "C and AVX2 kernels give identical drive frames and stats" \
        || bad "C and AVX2 kernels differ"
else
    grep -q "no AVX2 kernels" "$t/kv.err" && ok "--kernels avx2 refused without AVX2" || bad "--kernels avx2"
fi
# gaze-aware TRM from files (--gaze, --mv; run_gaze.c): a 40x30 eye is 3x2
# tiles of 16 px.  Tracking (gaze = motion: no retinal motion, k = 1) gives
# plain TRM's bytes; fixating moving content (retinal 4 px/frame > 2: k = 0)
# shows each full frame unsharpened, i.e. the input's bytes, and differs
# from TRM.
printf 'frame,gx,gy\n' > "$t/g_track.csv"; printf '# fixation\n' > "$t/g_fix.csv"; printf 'frame,tx,ty,dx,dy\n' > "$t/mv.csv"
for f in 0 1 2 3 4 5; do
    echo "$f,4,0" >> "$t/g_track.csv"; echo "$f,0,0" >> "$t/g_fix.csv"
    for y in 0 1; do for x in 0 1 2; do echo "$f,$x,$y,4,0" >> "$t/mv.csv"; done; done
done
"$run" -q -o "$t/gp" --builtin text --count 6 --size 40x30 --frames auto || bad "plain TRM run"
"$run" -q -o "$t/gt" --builtin text --count 6 --size 40x30 --frames auto --gaze "$t/g_track.csv" --mv "$t/mv.csv" || bad "gaze run (track)"
"$run" -q -o "$t/gf" --builtin text --count 6 --size 40x30 --frames auto --gaze "$t/g_fix.csv" --mv "$t/mv.csv" --save-input || bad "gaze run (fixate)"
same=1; for f in "$t/gp"/drive_*.png; do cmp -s "$f" "$t/gt/$(basename "$f")" || same=0; done
[ $same -eq 1 ] && ok "--gaze tracking the motion: plain TRM's drive frames" || bad "--gaze tracking differs from TRM"
cmp -s "$t/gf/drive_00002.png" "$t/gf/input_00002.png" && cmp -s "$t/gf/drive_00004.png" "$t/gf/input_00004.png" \
    && ! cmp -s "$t/gf/drive_00002.png" "$t/gp/drive_00002.png" \
    && ok "--gaze fixating: full frames shown unsharpened (the input's bytes), unlike TRM" || bad "--gaze fixating"
expect 1 "--gaze without --mv" "--gaze and --mv go together" -- "$run" -o "$t/gx" --builtin text --gaze "$t/g_fix.csv"
expect 1 "--gaze with --stereo" "--gaze is for one eye" -- "$run" -o "$t/gx" --stereo --frames auto --builtin text --gaze "$t/g_fix.csv" --mv "$t/mv.csv"
expect 7 "--gaze file missing" "cannot open --gaze file" -- "$run" -o "$t/gx" --builtin text --count 6 --size 40x30 --frames auto --gaze "$t/none.csv" --mv "$t/mv.csv"
grep -v '^4,1,1,' "$t/mv.csv" > "$t/mv_short.csv"
expect 13 "a full frame's tile missing" "full frame 4 has 5 of its 3x2 tile motion vectors" -- "$run" -o "$t/gx" --builtin text --count 6 --size 40x30 --frames auto --gaze "$t/g_fix.csv" --mv "$t/mv_short.csv"
printf '0,0,0,4\n' > "$t/mv_bad.csv"
expect 13 "malformed --mv line" "line 1: expected frame,tx,ty,dx,dy" -- "$run" -o "$t/gx" --builtin text --count 6 --size 40x30 --frames auto --gaze "$t/g_fix.csv" --mv "$t/mv_bad.csv"
printf '0,3,0,1,1\n' > "$t/mv_out.csv"
expect 13 "tile outside the frame" "tile (3, 0) outside the 3x2 tiles" -- "$run" -o "$t/gx" --builtin text --count 6 --size 40x30 --frames auto --gaze "$t/g_fix.csv" --mv "$t/mv_out.csv"
echo "tdc-run: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
