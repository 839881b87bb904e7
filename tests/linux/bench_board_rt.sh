#!/bin/sh
# make bench: the Linux board's frame loop (tdc-board --bench: the stream
# read from a file, the scan-out conversion RGB888 -> XRGB8888 into RAM as
# the KMS path does, no display) on this machine's x86-64, htc-vive stereo
# 2x1080x1200 at 90 Hz: frames per second and the share of the 11.1 ms
# budget per part (transport read, loop = link decode + the stream's stage,
# panel out), and per stage of the loop (its timing line: decode, family,
# LCD inverse, show).  Times are the loop thread's CPU time (tdc-board
# --bench: on a shared machine the wall clock counts other jobs; with row
# workers it is the critical path when each worker has a core), wall and
# all threads' CPU beside.  The TRM stream runs on 1 thread (the baseline)
# and 2 (row bands, --threads 2) in this one run; the goal is 90 fps with
# it on <= 2 cores.
# Usage: bench_board_rt.sh TDC_BOARD FW_STREAM W H EYES HZ
set -eu
board=$1; gen=$2; w=$3; h=$4; eyes=$5; hz=$6
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
budget_us=$((1000000 / hz))
printf 'Linux board frame loop, %dx%dx%d @ %d Hz: budget %d us per frame (x86-64 gcc -O2, AVX2 row kernels; load average %s)\n' \
    "$eyes" "$w" "$h" "$hz" "$budget_us" "$(cut -d' ' -f1 /proc/loadavg)"
printf '%-10s %3s %6s %9s %7s %8s %9s | %8s %8s %8s | %8s %8s %8s %8s  (%% of the budget per frame)\n' stream thr frames \
    "us/frame" fps "wall fps" "all cpu" transport loop panel decode family lcd show
# 64 frames: the loop's per-stage line (decode, family = the stream's stage,
# LCD inverse, show = the scan-out conversion) comes every 64 frames shown
# (the foveated stream's gaze path is refused beyond ~32 frames: no line, -)
for spec in trm:64:1 trm:64:2 fov-clean:32:1 plain:64:1; do
    m=${spec%%:*}; rest=${spec#*:}; n=${rest%%:*}; thr=${rest#*:}
    [ -f "$tmp/$m.tdcs" ] || "$gen" "$m" "$w" "$h" "$eyes" "$n" "$tmp/$m.tdcs" > /dev/null
    cat "$tmp/$m.tdcs" > /dev/null # page cache: the transport is memory, as a USB buffer is
    "$board" --stream "$tmp/$m.tdcs" --bench --threads "$thr" 2> "$tmp/log" > "$tmp/out" || { cat "$tmp/log"; exit 1; }
    stages=$(sed -n 's/.*cycles\/frame: decode \([0-9]*\) family \([0-9]*\) lcd \([0-9]*\) show \([0-9]*\).*/\1 \2 \3 \4/p' "$tmp/log" | tail -n 1)
    [ -n "$stages" ] || stages="- - - -"
    awk -v m="$m" -v b="$budget_us" -v st="$stages" -v thr="$thr" '/^bench:/ {
        f = $3; c = $5; tr = $7; p = $9; l = $11; wall = $13; all = $15
        if ($17 != thr) { print "bench: asked for " thr " threads, the board runs " $17 > "/dev/stderr"; exit 1 }
        split(st, s, " ")
        printf "%-10s %3d %6d %9.0f %7.1f %8.1f %9.0f | %7.1f%% %7.1f%% %7.1f%% |", m, thr, f, c / f, 1e6 * f / c, 1e6 * f / wall,
            all / f, 100 * tr / f / b, 100 * l / f / b, 100 * p / f / b
        for (i = 1; i <= 4; i++) { if (s[i] == "-") printf " %8s", "-"; else printf " %7.1f%%", s[i] / 10 / b }
        printf "\n"
        if (m == "trm") printf "%d %.3f\n", thr, c / f >> "'"$tmp/trm"'" }' "$tmp/out"
    [ "$m" = plain ] || [ "$m" = fov-clean ] && rm -f "$tmp/$m.tdcs"
done
awk -v b="$budget_us" '{ t[$1] = $2 } END {
    printf "goal: %d fps with the TRM stream on <= 2 cores; baseline, 1 core: %.1f fps (%.2fx short); 2 threads: %.1f fps (%.2fx short); 2 threads vs 1: %.2fx\n",
        1e6 / b, 1e6 / t[1], t[1] / b, 1e6 / t[2], t[2] / b, t[1] / t[2] }' "$tmp/trm"
