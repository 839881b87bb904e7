#!/bin/sh
# make bench: the Linux board's frame loop (tdc-board --bench: the stream
# read from a file, the scan-out conversion RGB888 -> XRGB8888 into RAM as
# the KMS path does, no display) on this machine's x86-64, htc-vive stereo
# 2x1080x1200 at 90 Hz: frames per second and the share of the 11.1 ms
# budget per part (transport read, loop = link decode + the stream's stage,
# panel out), and per stage of the loop (its timing line: decode, family,
# LCD inverse, show).  One core (the loop is single-threaded today): the baseline;
# the goal is 90 fps with the TRM stream on <= 2 cores.
# Usage: bench_board_rt.sh TDC_BOARD FW_STREAM W H EYES HZ
set -eu
board=$1; gen=$2; w=$3; h=$4; eyes=$5; hz=$6
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
budget_us=$((1000000 / hz))
printf 'Linux board frame loop, %dx%dx%d @ %d Hz: budget %d us per frame (1 core, x86-64 gcc -O2, AVX2 row kernels)\n' \
    "$eyes" "$w" "$h" "$hz" "$budget_us"
printf '%-10s %6s %10s %8s | %9s %9s %9s | %8s %8s %8s %8s  (%% of the budget per frame)\n' stream frames "us/frame" fps \
    transport loop panel decode family lcd show
# 64 frames: the loop's per-stage line (decode, family = the stream's stage,
# LCD inverse, show = the scan-out conversion) comes every 64 frames shown
# (the foveated stream's gaze path is refused beyond ~32 frames: no line, -)
for spec in trm:64 fov-clean:32 plain:64; do
    m=${spec%%:*}; n=${spec#*:}
    "$gen" "$m" "$w" "$h" "$eyes" "$n" "$tmp/$m.tdcs" > /dev/null
    cat "$tmp/$m.tdcs" > /dev/null # page cache: the transport is memory, as a USB buffer is
    "$board" --stream "$tmp/$m.tdcs" --bench 2> "$tmp/log" > "$tmp/out" || { cat "$tmp/log"; exit 1; }
    stages=$(sed -n 's/.*cycles\/frame: decode \([0-9]*\) family \([0-9]*\) lcd \([0-9]*\) show \([0-9]*\).*/\1 \2 \3 \4/p' "$tmp/log" | tail -n 1)
    [ -n "$stages" ] || stages="- - - -"
    awk -v m="$m" -v b="$budget_us" -v st="$stages" '/^bench:/ {
        f = $3; t = $5; tr = $7; p = $9; l = $11
        split(st, s, " ")
        printf "%-10s %6d %10.0f %8.1f | %8.1f%% %8.1f%% %8.1f%% |", m, f, t / f, 1e6 * f / t, 100 * tr / f / b, 100 * l / f / b, 100 * p / f / b
        for (i = 1; i <= 4; i++) { if (s[i] == "-") printf " %8s", "-"; else printf " %7.1f%%", s[i] / 10 / b }
        printf "\n"
        if (m == "trm") { printf "goal: %d fps with the TRM stream on <= 2 cores; today, 1 core: %.1f fps (%.1fx short; 2 cores by row bands would need %.1fx)\n", 1e6 / b, 1e6 * f / t, (t / f) / b, (t / f) / b / 2 > "/dev/stderr" } }' "$tmp/out"
    rm -f "$tmp/$m.tdcs"
done 2> "$tmp/goal"
cat "$tmp/goal"
