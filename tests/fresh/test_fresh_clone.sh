#!/bin/sh
# test_fresh_clone.sh [PAIRS...] - the README's commands work as the first
# command in a fresh clone.  The working tree (tracked files and untracked,
# not ignored ones: what a commit of it would hold, without build/ or report/)
# is copied to a temporary folder, with make's own variables cleared so the
# copy is entered as a newcomer's shell would.  Checked there:
#   1. `make -n CMD` for every command the README names prints the `deps`
#      step before its first compiler line;
#   2. the board/panel images PAIRS (board:panel; default: the README's
#      example) build, each in a copy where nothing else was built (a missing
#      generated-header dependency fails there), and `make size` builds every
#      pair from a clean tree (a pair that does not fit is a verdict, not a
#      failure);
#   3. `make -j2 demo DEMO_SCALE=ci` (every demo run, tiny sizes) exits 0
#      and writes report/index.md; when FRESH_DEMO_MARK names a file, `make
#      test` already ran it in its own fresh tree (demo_in_tree.sh) and its
#      line is the verdict.
# Packages are already present here (make test installed them); that step of
# a fresh machine is what `make -n` shows in 1.
set -u
src=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d /tmp/tdc-fresh.XXXXXX)
trap 'rm -rf "$tmp"' EXIT INT TERM
unset MAKEFLAGS MFLAGS MAKELEVEL MAKEOVERRIDES TDC_DEPS
fail=0
say() { printf '%s\n' "$*"; }
bad() { say "FAIL: $*"; fail=1; }

copy_tree() { # copy_tree DEST
    mkdir -p "$1"
    (cd "$src" && git ls-files -z --cached --others --exclude-standard | \
        xargs -0 sh -c 'for f; do [ -e "$f" ] && printf "%s\0" "$f"; done' sh | \
        cpio -0 -pdm --quiet "$1") || { bad "copy of the working tree failed"; exit 1; }
}
copy_tree "$tmp/n"

# 1. deps before the first compiler line, for every command the README names
#    (and its -j2 form: the order must not depend on the job count)
for cmd in "" demo test bench bench-sim size report-lcd "experiments EXP_SCALE=demo" \
           "sweep SWEEP=sim/sweep/examples/small.sweep" "BOARD=stm32h747i-disco PANEL=disco-dsi" \
           "BOARD=mps2-an500 PANEL=htc-vive" "BOARD=mps3-an547 PANEL=htc-vive"; do
    # -j2 where the order once depended on it (demo, test) and for a board
    case $cmd in demo|test|BOARD=stm32h747i-disco*) jobs="1 2" ;; *) jobs=1 ;; esac
    for jn in $jobs; do
        j=; [ "$jn" = 2 ] && j=-j2
        # shellcheck disable=SC2086
        out=$(cd "$tmp/n" && make -n $j $cmd 2>&1); rc=$?
        [ $rc -eq 0 ] || { bad "make -n $j $cmd: exit $rc: $(printf '%s\n' "$out" | grep -E '\*\*\*' | head -1)"; continue; }
        d=$(printf '%s\n' "$out" | grep -n 'dpkg-query' | head -1 | cut -d: -f1)
        c=$(printf '%s\n' "$out" | grep -nE '^(gcc|clang|cc|arm-none-eabi-gcc|g\+\+) ' | head -1 | cut -d: -f1)
        if [ -z "$d" ]; then bad "make -n $j $cmd: no deps step"
        elif [ -n "$c" ] && [ "$c" -lt "$d" ]; then bad "make -n $j $cmd: compiler line $c before the deps step (line $d)"
        else say "ok: make -n $j $cmd: deps first (line $d; first compile ${c:-none})"; fi
    done
done

# 2. board images from a clean tree: the README's example pair first in its
#    own copy (nothing else built there), then `make size` in another copy,
#    which builds every board/panel pair and fails on any failure that is
#    not a memory-fit verdict
[ $# -gt 0 ] || set -- stm32h747i-disco:disco-dsi
for pair in "$@"; do
    b=${pair%%:*}; p=${pair#*:}
    copy_tree "$tmp/b-$b-$p"
    if (cd "$tmp/b-$b-$p" && make -j2 BOARD="$b" PANEL="$p" > "$tmp/log-$b-$p" 2>&1) && \
       [ -s "$tmp/b-$b-$p/build/$b-$p/tdc-firmware.elf" ]; then
        say "ok: make -j2 BOARD=$b PANEL=$p in a fresh tree"
    else
        bad "make -j2 BOARD=$b PANEL=$p in a fresh tree:"; tail -5 "$tmp/log-$b-$p" | sed 's/^/    /'
    fi
    rm -rf "$tmp/b-$b-$p"
done
copy_tree "$tmp/s"
if (cd "$tmp/s" && make size > "$tmp/size.log" 2>&1); then
    say "ok: make size in a fresh tree: $(grep -c '^== ' "$tmp/size.log") pairs, $(grep -c 'region' "$tmp/size.log") region lines, $(grep -c '^    memory fit' "$tmp/size.log") memory-fit verdicts"
else
    bad "make size in a fresh tree:"; grep -B1 -A5 'build failed' "$tmp/size.log" | head -20 | sed 's/^/    /'
fi
rm -rf "$tmp/s"

# 3. the demo, every run at the ci scale: the verdict of the run `make test`
#    made in place when its tree was fresh (FRESH_DEMO_MARK), else in the copy
mark=${FRESH_DEMO_MARK:-}
t0=$(date +%s)
if [ -n "$mark" ] && [ -s "$mark" ]; then
    cat "$mark"; grep -q '^ok: ' "$mark" || fail=1
elif (cd "$tmp/n" && make -j2 demo DEMO_SCALE=ci > "$tmp/demo.log" 2>&1) && [ -s "$tmp/n/report/index.md" ]; then
    say "ok: make -j2 demo DEMO_SCALE=ci in a fresh tree ($(( $(date +%s) - t0 )) s, report/index.md written)"
else
    bad "make -j2 demo DEMO_SCALE=ci in a fresh tree ($(( $(date +%s) - t0 )) s):"; grep -E 'FAILED|Error|error:' "$tmp/demo.log" | head -8 | sed 's/^/    /'
    tail -5 "$tmp/demo.log" | sed 's/^/    /'
fi
exit $fail
