#!/bin/sh
# Every program the project builds keeps the convention of docs/tools.md:
# --help prints the usage on stdout and exits 0; a bad option, a folder
# given as an input file and an output that cannot be written each give ONE
# line "tool: ...: why" on stderr and their named exit code (ARGS, FILE),
# never success.  tdc-usb adds its closing "tdc-usb: exit N (NAME)" line.
#
# The programs come from the build (HOST_PROGS and the table generator, in
# mk/tools.mk); a program without cases here fails the test, so a new
# program cannot skip the convention.
# Usage: tests/unit/test_tool_conventions.sh PROGRAM...
. tests/unit/tool_expect.sh

mkdir "$t/dir"                   # a folder where a file is expected
printf 'a file' > "$t/file"      # a file where a folder is expected
nowhere="$t/file/sub"            # cannot be created: ENOTDIR, also as root

# one_line CODE WHAT PROG ARGS...: exit CODE and exactly one stderr line
# "prog: ..." (tdc-usb: that line and "tdc-usb: exit CODE (NAME)").
one_line() {
    code=$1; what=$2; prog=$3; shift 3
    name=$(basename "$prog")
    "$prog" "$@" >"$t/out" 2>"$t/err"; got=$?
    lines=$(wc -l < "$t/err")
    want=1; [ "$name" = tdc-usb ] && want=2
    if [ "$got" -ne "$code" ]; then
        bad "$name: $what (exit $got, want $code; stderr: $(head -c 300 "$t/err"))"
    elif [ "$lines" -ne "$want" ] || ! head -n 1 "$t/err" | grep -q "^$name: "; then
        bad "$name: $what (want $want stderr line(s) '$name: ...', got $lines: $(head -c 300 "$t/err"))"
    elif [ "$name" = tdc-usb ] && ! tail -n 1 "$t/err" | grep -q "^tdc-usb: exit $code ([A-Z_]*)\$"; then
        bad "$name: $what (no closing 'tdc-usb: exit $code (NAME)' line: $(tail -n 1 "$t/err"))"
    elif grep -q "Sanitizer" "$t/err"; then
        bad "$name: $what (sanitizer report)"
    else
        ok "$name: $what"
    fi
}

# --help: exit 0, the usage on stdout, nothing on stderr; the exit codes it
# lists ("N NAME" after "exit codes") are those of the one table.
python3 common/tdc_exit.py list > "$t/codes" || bad "tdc_exit.py list"
help_ok() {
    prog=$1; name=$(basename "$prog")
    "$prog" --help >"$t/out" 2>"$t/err"; got=$?
    if [ "$got" -eq 0 ] && [ -s "$t/out" ] && [ ! -s "$t/err" ]; then ok "$name: --help"
    else bad "$name: --help (exit $got, stdout $(wc -c < "$t/out") bytes, stderr: $(head -c 200 "$t/err"))"; fi
    wrong=$(sed -n '/[Ee]xit codes/,$p' "$t/out" | grep -oE '\b[0-9]{1,2} [A-Z][A-Z_]+\b' | sort -u | grep -vxF -f "$t/codes")
    if ! grep -qi "exit codes" "$t/out"; then bad "$name: --help names no exit codes"
    elif [ -n "$wrong" ]; then bad "$name: --help names codes not in tdc_exit.h: $wrong"
    else ok "$name: --help exit codes match tdc_exit.h"; fi
}

for prog in "$@"; do
    name=$(basename "$prog")
    help_ok "$prog"
    one_line 1 "unknown option" "$prog" --no-such-option
    case $name in
    tdc-run)
        one_line 7 "folder as input frame" "$prog" -q -o "$t/run" "$t/dir"
        one_line 7 "output folder not creatable" "$prog" -q -o "$nowhere" --builtin edge --count 2 --size 16x8
        one_line 7 "output folder is a file" "$prog" -q -o "$t/file" --builtin edge --count 2 --size 16x8
        ;;
    tdc-usb)
        one_line 1 "unknown command" "$prog" frobnicate
        one_line 1 "missing argument" "$prog" stream
        one_line 7 "stream: folder as input" "$prog" stream "$t/dir"
        one_line 7 "flash: folder as image" "$prog" flash "$t/dir"
        one_line 7 "mkimage: folder as input" "$prog" mkimage --board b "$t/dir" "$t/x.img"
        one_line 7 "mkimage: output not writable" "$prog" mkimage --board b "$t/file" "$nowhere.img"
        ;;
    tdc-gpio)
        # no file inputs or outputs: a folder named as the chip is no chip
        one_line 2 "folder as GPIO chip" "$prog" reset --chip "$t/dir" --line 0
        ;;
    tdc-lcd-measure)
        one_line 7 "folder as panel" "$prog" "$t/dir" 60
        one_line 7 "output not writable" "$prog" sim/lcd/panels/lcd-240.lcdsim 60 --grid 3 -o "$nowhere.csv"
        ;;
    tdc-calib)
        one_line 7 "folder as measurement" "$prog" "$t/dir" -o "$t/x.panel" --name x --width 8 --height 8
        meas=$(dirname "$prog")/tdc-lcd-measure
        if "$meas" sim/lcd/panels/lcd-240.lcdsim 60 --grid 5 -o "$t/meas.csv" 2>"$t/err"; then
            one_line 7 "output not writable" "$prog" "$t/meas.csv" -o "$nowhere.panel" --name x --width 8 --height 8
        else bad "tdc-calib: no measurement from $meas: $(cat "$t/err")"; fi
        ;;
    tdc-sim)
        sim="$prog -q -m full -n 2 -g 16x8 --eyes 1"
        one_line 7 "folder as --image" $sim --image "$t/dir"
        one_line 7 "--out is a file" $sim -o "$t/file"
        [ -e "$t/file/summary.csv" ] && bad "tdc-sim: wrote into a file" || true
        one_line 7 "--out not creatable" $sim -o "$nowhere"
        # the folder exists, but the outputs in it cannot be written
        for out in summary.csv series.csv summary.md foveation.csv strip_full.png; do
            rm -rf "$t/simout"; mkdir -p "$t/simout/$out"
            one_line 7 "$out not writable" $sim -o "$t/simout"
        done
        for out in jod.csv jod_series.csv; do
            rm -rf "$t/simout"; mkdir -p "$t/simout/$out"
            one_line 7 "--jod: $out not writable" $sim --jod -o "$t/simout"
        done
        # a judged run (30 refreshes: past the 250 ms warm-up): the heat map, series.csv's jod column
        for out in heatmap_full.png series.csv.tmp; do
            rm -rf "$t/simout"; mkdir -p "$t/simout/$out"
            one_line 7 "judged: $out not writable" $sim -n 30 -o "$t/simout"
        done
        ;;
    tdc-render)
        one_line 7 "folder as --scene" "$prog" --scene "$t/dir"
        one_line 7 "--png not creatable" "$prog" --builtin fence --size 16x8 --quiet --png "$nowhere"
        one_line 7 "--stream is a folder" "$prog" --builtin fence --size 16x8 --quiet --stream "$t/dir"
        one_line 7 "--stream not creatable" "$prog" --builtin fence --size 16x8 --quiet --stream "$nowhere.tdcs"
        ;;
    tdc-linkdump)
        one_line 7 "folder as stream" "$prog" "$t/dir"
        : > "$t/empty.tdcs"
        one_line 13 "empty stream" "$prog" "$t/empty.tdcs"
        printf 'not a stream, not at all, no' > "$t/junk.tdcs"
        one_line 13 "garbage stream" "$prog" "$t/junk.tdcs"
        ;;
    tdc-tablegen)
        mkdir -p "$t/gen"
        one_line 7 "folder as profile" "$prog" "$t/dir" "$t/gen"
        one_line 7 "output folder not writable" "$prog" boards/panels/htc-vive.panel "$nowhere"
        one_line 7 "--fov output not writable" "$prog" --fov "$nowhere.h"
        one_line 7 "--trm output is a folder" "$prog" --trm "$t/dir"
        ;;
    tdc-fvvdp-validate)
        one_line 7 "table: folder as the reference table" "$prog" table "$t/dir"
        one_line 7 "table: no such table" "$prog" table "$t/none.csv"
        printf 'condition,reference_jod,seconds\n' > "$t/short.csv"
        one_line 13 "table: a condition missing" "$prog" table "$t/short.csv"
        one_line 7 "dump: folder not creatable" "$prog" dump "$nowhere"
        ;;
    tdc-zeng)
        one_line 7 "--csv is a folder" "$prog" --scene fence --size 16x16 --frames 2 --eval-from 1 --seeds 1 \
            --gt-spp 1 --csv "$t/dir"
        one_line 7 "--csv not creatable" "$prog" --scene fence --size 16x16 --frames 2 --eval-from 1 --seeds 1 \
            --gt-spp 1 --csv "$nowhere.csv"
        ;;
    *)
        bad "$name: no cases in $0 (every program keeps docs/tools.md)"
        ;;
    esac
done

echo "tool conventions: $pass passed, $fail failed"
[ "$fail" -eq 0 ] && [ "$pass" -gt 0 ]
