#!/bin/sh
# Rows in flight (issue 17 item 2): the frame loop built with bands
# (TDC_CFG_BANDS: one band staged, front/back frame buffers swapped only on
# a complete frame) on the banded streams of tests/arm/fw_stream.c, against
# the loop without bands on the whole-picture streams:
#   trm-bands                    = trm (same frames, byte for byte: the
#                                  stages see the same pictures)
#   trm-bands-crc|order|missing|size  (frame 2, eye 0's FULL picture with a
#                                  bad band) = trm-drop (that picture lost
#                                  whole: the eye keeps its last good
#                                  image, the next reduced frame of the eye
#                                  is shown without residual, never with
#                                  stale state)
#   trm-bands-other              = trm (a band for another frame is refused
#                                  alone)
# and each refusal is counted (the loop's log).  On LCD panels the dropped
# picture's first rows already ran through the LCD inverse (it runs per
# band): that eye's LCD restarts without history, so there the drop cases
# must match trm-drop up to the drop and show the same frames after it.
# Usage: test_fw_bands.sh HOST_LOOP_BANDS HOST_LOOP_WHOLE FW_STREAM W H EYES
hb=$1; hw=$2; gen=$3; w=$4; h=$5; eyes=$6
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
frames=6
fail=0
run() { # host mode -> $tmp/mode.out, .err
    "$gen" "$2" "$w" "$h" "$eyes" "$frames" "$tmp/$2.tdcs" || { echo "fw-bands: fw_stream $2 failed"; exit 1; }
    "$1" "$tmp/$2.tdcs" >"$tmp/$2.out" 2>"$tmp/$2.err"
    rm -f "$tmp/$2.tdcs"
}
check() { # crafted reference counter-pattern
    n=$(grep -c . "$tmp/$1.out")
    if [ "$n" -eq 0 ] || ! cmp -s "$tmp/$1.out" "$tmp/$2.out"; then
        echo "fw-bands[$1]: FAIL: shows $n frames, not those of $2:"
        diff "$tmp/$1.out" "$tmp/$2.out" | head -10; grep -v ': 0$' "$tmp/$1.err" | head -20
        fail=1
    elif [ -n "$3" ] && ! grep -q "$3" "$tmp/$1.err"; then
        echo "fw-bands[$1]: FAIL: its log lacks '$3':"; grep -v ': 0$' "$tmp/$1.err" | head -20
        fail=1
    else
        echo "fw-bands[$1]: $n frames as $2 ($(grep -E 'rejected|dropped|copied|row bands|without their' "$tmp/$1.err" | sed 's/^\[host\] //' | tr '\n' ';'))"
    fi
}
run "$hw" trm; run "$hw" trm-drop
for m in trm-bands trm-bands-crc trm-bands-order trm-bands-missing trm-bands-size trm-bands-other; do run "$hb" $m; done
[ "$(grep -c . "$tmp/trm.out")" -eq "$frames" ] || { echo "fw-bands: FAIL: the clean TRM stream shows $(grep -c . "$tmp/trm.out") of $frames frames"; fail=1; }
cmp -s "$tmp/trm.out" "$tmp/trm-drop.out" && { echo "fw-bands: FAIL: losing a picture changes nothing: the test cannot fail"; fail=1; }
check trm-bands trm 'packets/bytes rejected: 0'
if grep -q '^\[host\] LCD unreached' "$tmp/trm.err"; then
    # LCD panels: the dropped picture's first rows already ran through the
    # LCD inverse, so that eye's LCD restarts without history (counted): the
    # frames before the drop are the reference's, the same frames are shown
    # after it, and the clean stream is byte-identical (above).
    for m in crc order missing size; do
        a=$(awk '$2 < 2' "$tmp/trm-bands-$m.out"); b=$(awk '$2 < 2' "$tmp/trm-drop.out")
        if [ -z "$a" ] || [ "$a" != "$b" ] || [ "$(awk '{print $2}' "$tmp/trm-bands-$m.out")" != "$(awk '{print $2}' "$tmp/trm-drop.out")" ] ||
           ! grep -q 'pictures dropped (bad or missing band): 1' "$tmp/trm-bands-$m.err" ||
           ! grep -q 'LCD history resets (picture dropped after its first LCD rows): 1' "$tmp/trm-bands-$m.err"; then
            echo "fw-bands[trm-bands-$m]: FAIL: not the frames of trm-drop before the drop, or not the same frames shown, or no drop/LCD reset counted:"
            diff "$tmp/trm-bands-$m.out" "$tmp/trm-drop.out" | head -10; grep -v ': 0$' "$tmp/trm-bands-$m.err" | head -20
            fail=1
        else
            echo "fw-bands[trm-bands-$m]: frames $(awk '{printf "%s ", $2}' "$tmp/trm-bands-$m.out")shown as trm-drop, identical before the drop; LCD restarted without history (1 reset)"
        fi
    done
else
    for m in crc order missing size; do check trm-bands-$m trm-drop 'pictures dropped (bad or missing band): 1'; done
fi
check trm-bands-other trm 'packets/bytes rejected: 1'
exit $fail
