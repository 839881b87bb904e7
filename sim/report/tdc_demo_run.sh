#!/bin/sh
# tdc_demo_run.sh SIM OUT NAME ARGS - one run of `make demo` (called by GNU
# parallel from tdc_demo.sh): tdc-sim with its progress bar into
# OUT/NAME/stderr.txt, one ok/FAILED line into OUT/demo.log, and for large
# runs (hs-*) the 1:1 crops + downscaled frames instead of full-size strips.
SIM=$1; OUT=$2; name=$3; args=$4
mkdir -p "$OUT/$name"
rm -f "$OUT/$name/done"
t0=$(date +%s)
# 128x96 mono unless the run gives its own -g / --stereo (the later option wins)
# shellcheck disable=SC2086
if /usr/bin/time -o "$OUT/$name/time.txt" -f '%U %S %M' \
        "$SIM" -l "$name" -o "$OUT/$name" -g 128x96 --mono $args > "$OUT/$name/stdout.txt" 2> "$OUT/$name/stderr.txt"; then
    case $name in
    hs-*|fov-render) /usr/bin/python3 sim/report/tdc_crops.py "$OUT/$name" >> "$OUT/$name/stderr.txt" 2>&1 ;;
    # the layered runs: the window where ordinary and Zeng vectors part (shadow, reflection)
    lasm-render-*) /usr/bin/python3 sim/report/tdc_crops.py "$OUT/$name" --crop 160 --pick-diff lasm-ordinary,lasm-zeng \
                   >> "$OUT/$name/stderr.txt" 2>&1 ;;
    esac
    cpu=$(awk '{printf "%.0f s CPU, %.2f GB peak", $1 + $2, $3 / 1048576}' "$OUT/$name/time.txt")
    echo "$name ok ($(( $(date +%s) - t0 )) s wall, $cpu): tdc-sim $args" >> "$OUT/demo.log"
else
    echo "$name FAILED (exit $?): tdc-sim $args: $(tr '\r' '\n' < "$OUT/$name/stderr.txt" | grep -v '^ *$' | tail -1)" >> "$OUT/demo.log"
fi
: > "$OUT/$name/done"
