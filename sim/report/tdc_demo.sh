#!/bin/sh
# tdc_demo.sh TDC_SIM OUTDIR - the default comparison on built-in scenes
# (make demo).  Runs tdc-sim on each scene/family, two runs at a time (2
# cores), then draws plots and writes OUTDIR/index.md.  < 5 minutes on 2 cores.
set -eu
SIM=$1
OUT=${2:-report}
mkdir -p "$OUT"
start=$(date +%s)
LOG="$OUT/demo.log"
: > "$LOG"

# name | arguments
RUNS='trm-pan|-s pan -r 90 -m trm-family -n 48
trm-discs|-s discs -r 90 -m trm-family -n 48
trm-static|-s static -r 90 -m full,half,ncsfi,trm50,trm40,trm25 -n 48
trm-lcd|-s pan -r 120 -p lcd --profile pg279q -m full,half,trm50,trm40,trm25 -n 48
ncsfi-slow|-s pan -r 90 --speed 150 -m full,ncsfi,trm50 -n 36 -g 192x96
ncsfi-fast|-s pan -r 90 --speed 1800 -m full,ncsfi,trm50 -n 36 -g 192x96
asm-thin|-s thin -r 240 -m full,asm-hourglass,asm-bowtie,asm-adaptive -d 0.3
asm-fence|-s fence -r 240 -m asm-family -d 0.25
asm-pan|-s pan -r 240 -m asm-family -d 0.25
render-panorama|-R panorama -r 90 -m trm-family -n 36
render-fence|-R fence -r 240 -m full,full60,taa60,asm-adaptive,asm-adaptive-smv -d 0.2
stiff-long|-s pan -r 90 -g 16x16 -n 100000 --metric-every 1000 -m full,trm50 --gt-ss 2
stiff-cut|-s cut -r 90 -m trm-family -n 36
stiff-cut240|-s cut -r 240 -m full,asm-adaptive,taa60 -d 0.2
stiff-fast|-s pan -r 90 --speed 20000 -m trm-family -n 27
stiff-black|-s black -r 90 -m trm-family -n 18
stiff-white|-s white -r 90 -m trm-family -n 18
stiff-black240|-s black -r 240 -m asm-family -d 0.05
stiff-white240|-s white -r 240 -m asm-family -d 0.05'

run_one() {
    name=$1; shift
    t0=$(date +%s)
    # 128x96 mono unless the run gives its own -g / --stereo (the later option wins)
    if "$SIM" -q -l "$name" -o "$OUT/$name" -g 128x96 --mono "$@" > "$OUT/$name/stdout.txt" 2> "$OUT/$name/stderr.txt"; then
        echo "$name ok ($(( $(date +%s) - t0 )) s): tdc-sim $*" >> "$LOG"
    else
        echo "$name FAILED (exit $?): tdc-sim $*" >> "$LOG"
    fi
}

echo "$RUNS" | { i=0; while IFS='|' read -r name args; do
    mkdir -p "$OUT/$name"
    echo "tdc-sim $args  ->  $OUT/$name" >&2
    # shellcheck disable=SC2086
    run_one "$name" $args &
    i=$((i + 1))
    if [ $((i % 2)) -eq 0 ]; then wait; fi
done; wait; }
end=$(date +%s)
echo "simulation: $((end - start)) s" >> "$LOG"
/usr/bin/python3 sim/report/tdc_plots.py "$OUT" "$((end - start))"
cat "$LOG" >&2
echo "wrote $OUT/index.md" >&2
if grep -q FAILED "$LOG"; then exit 1; fi
