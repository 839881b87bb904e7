#!/bin/sh
# run_par.sh JOBS FILE: runs each line of FILE as a shell command, at most
# JOBS at a time, then prints their outputs in line order; exits 1 if any
# command failed, 2 if FILE cannot be read.  QEMU's TCG runs a guest on one
# core, so a pair's fw-check modes (independent runs of one image) go two at
# a time: mps3-an547/htc-vive's seven modes took 264 s one after another.
jobs=$1; f=$2
[ -r "$f" ] || { echo "run_par.sh: $f: cannot read the command list" >&2; exit 2; }
d=$(mktemp -d) || exit 2
trap 'rm -rf "$d"' EXIT
trap 'exit 2' INT TERM
n=$(grep -c '' "$f")
[ "$n" -gt 0 ] || exit 0
seq 1 "$n" | xargs -P "$jobs" -I{} sh -c 'sed -n "$1p" "$2" | sh > "$3/$1.log" 2>&1 || : > "$3/$1.fail"' sh {} "$f" "$d"
rc=0
for i in $(seq 1 "$n"); do
    cat "$d/$i.log"
    if [ -e "$d/$i.fail" ]; then rc=1; fi
done
exit $rc
