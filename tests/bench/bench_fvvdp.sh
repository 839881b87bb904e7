#!/bin/sh
# bench_fvvdp.sh TOOL TDC_SIM [REF_CHECKOUT] - part of make bench-sim: the C
# FovVideoVDP's throughput against the reference implementation's CPU
# throughput on the same frames (the 40-condition validation set, 871 frames
# of 64 x 64), both on one thread, measured in the same run.  Goal: >= 3x.
#
# The reference runs only if REF_CHECKOUT (FVVDP_REF) names a checkout of
# github.com/gfxdisp/FovVideoVDP and Debian's python3-torch imports; else the
# stored seconds of sim/metrics/validation/fvvdp_reference.csv are used and
# the line says so (another run, so a ratio of two runs).
set -u
TOOL=$1
SIM=$2
REF=${3:-}
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "bench-fvvdp: $(getconf _NPROCESSORS_ONLN) cores, load $(cut -d' ' -f1-3 /proc/loadavg), 1 thread each, $(date -u +%H:%M) UTC"
if ! "$TOOL" bench > "$tmp/tdc"; then
    echo "bench-fvvdp: tdc-fvvdp-validate bench: FAILED"
    exit 1
fi
tdc_s=$(awk '{ print $6 }' "$tmp/tdc")
src="stored in sim/metrics/validation/fvvdp_reference.csv (not this run)"
ref_s=$(awk -F, '!/^#/ && $1 != "condition" { s += $3 } END { print s }' sim/metrics/validation/fvvdp_reference.csv)
if [ -n "$REF" ] && /usr/bin/python3 -c 'import torch' 2>/dev/null; then
    if "$TOOL" dump "$tmp/frames" > /dev/null &&
        FVVDP_THREADS=1 /usr/bin/python3 sim/metrics/validation/fvvdp_reference.py "$REF" "$tmp/frames" > "$tmp/ref.csv" 2> "$tmp/ref.err"; then
        ref_s=$(awk -F, '!/^#/ && $1 != "condition" { s += $3 } END { print s }' "$tmp/ref.csv")
        src="this run"
    else
        echo "bench-fvvdp: the reference failed: $(tail -1 "$tmp/ref.err"); using the stored seconds"
    fi
fi
awk -v t="$tdc_s" -v r="$ref_s" -v src="$src" 'BEGIN {
    printf "goal: C FovVideoVDP >= 3x the reference'"'"'s CPU throughput on the same frames: tdc %.2f s, reference %.2f s (%s): %.1fx (%s)\n",
        t, r, src, r / t, (r / t >= 3 ? "met" : "NOT met") }'

# The judge at headset scale, at steady state: tdc-sim's TRM stereo
# configuration (2 x 1440 x 1600, 90 Hz, full and trm50, 2 threads) without
# and with --jod over 32 refreshes: the judge's 250 ms warm-up (23 refreshes,
# which fill the temporal history: 23 frames per stream) and 9 pooled past
# it, so the peak holds the full history.  Goals: >= 2 M pixel-refreshes/s
# with the judge, peak <= 2 GB (RSS, /usr/bin/time).  Figures and where the
# time and memory go: docs/visual-model.md.
N=${BENCH_JOD_REFRESHES:-32}
conf="-q --threads 2 -s pan -r 90 -g 1440x1600 --stereo --ppd 15.2 -m full,trm50 -n $N"
# (a run longer than the warm-up is judged by default: --judge legacy
# leaves the judge out).  Three runs: the legacy judge alone; the default
# run (the judge and the legacy columns at every refresh: the goal's
# figure); the judge with the legacy columns at every 9th refresh
# (--metric-every 9: the same JODs, for runs that want JOD alone).
for j in legacy jod jod9; do
    case $j in
    jod9) opt="--judge jod --metric-every 9" ;;
    *) opt="--judge $j" ;;
    esac
    # shellcheck disable=SC2086
    if ! OMP_NUM_THREADS=2 /usr/bin/time -f "%e %U %S %M" -o "$tmp/time.$j" "$SIM" $conf $opt > /dev/null 2> "$tmp/err.$j"; then
        echo "bench-fvvdp: tdc-sim $conf $opt: FAILED: $(tail -1 "$tmp/err.$j")"
        exit 1
    fi
done
read -r w0 u0 s0 m0 < "$tmp/time.legacy"
read -r w1 u1 s1 m1 < "$tmp/time.jod"
read -r w2 u2 s2 m2 < "$tmp/time.jod9"
awk -v n="$N" -v w0="$w0" -v u0="$u0" -v s0="$s0" -v m0="$m0" -v w1="$w1" -v u1="$u1" -v s1="$s1" -v m1="$m1" 'BEGIN {
    c0 = u0 + s0; c1 = u1 + s1
    px = 1440 * 1600 * 2 * n * 2
    printf "TRM stereo 2x1440x1600 full,trm50, %d refreshes (23 of warm-up, %d past it: history full): --judge legacy %.2f M px-refreshes/s (%.1f s wall, %.1f CPU s, %.0f MB); --judge jod %.2f M/s (%.1f s wall, %.1f CPU s, %.0f MB)\n", n, n - 23, px / w0 / 1e6, w0, c0, m0 / 1024, px / w1 / 1e6, w1, c1, m1 / 1024
    printf "goal: with the judge at steady state >= 2 M px-refreshes/s: %.2f M wall, %.2f M per CPU-second x 2 cores (%s); peak RSS <= 2 GB: %.2f GB (%s)\n", px / w1 / 1e6, 2 * px / c1 / 1e6, (px / w1 / 1e6 >= 2 ? "met" : "NOT met"), m1 / 1048576, (m1 <= 2097152 ? "met" : "NOT met") }'
awk -v n="$N" -v w2="$w2" -v u2="$u2" -v s2="$s2" -v m2="$m2" 'BEGIN {
    c2 = u2 + s2; px = 1440 * 1600 * 2 * n * 2
    printf "the judge with the legacy columns at every 9th refresh (--metric-every 9, the same JODs): %.2f M px-refreshes/s wall (%.1f s wall, %.1f CPU s: %.2f M per CPU-second x 2 cores, %.0f MB)\n", px / w2 / 1e6, w2, c2, 2 * px / c2 / 1e6, m2 / 1024 }'
