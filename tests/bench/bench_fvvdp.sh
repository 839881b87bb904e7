#!/bin/sh
# bench_fvvdp.sh TOOL [REF_CHECKOUT] - part of make bench-sim: the C
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
REF=${2:-}
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "bench-fvvdp: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), 1 thread each, $(date -u +%H:%M) UTC"
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
