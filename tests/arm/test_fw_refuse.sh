#!/bin/sh
# A 60 Hz panel (boards/panels/disco-dsi.panel, the STM32H747I-DISCO's own
# display) runs the link, tile assembly and the LCD inverse, and refuses
# TRM (below its 90 Hz minimum, paper section 9) whatever refresh the stream
# claims: the TRM stream shows no frame, names the refusal and exits 1; the
# plain and subframe streams show every frame (host build of the loop).
# Usage: test_fw_refuse.sh HOST_LOOP FW_STREAM W H EYES
host=$1; gen=$2; w=$3; h=$4; eyes=$5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
for m in plain trm subframes; do
    "$gen" $m "$w" "$h" "$eyes" 6 "$tmp/$m.tdcs" || { echo "fw-refuse: fw_stream $m failed"; exit 1; }
    "$host" "$tmp/$m.tdcs" >"$tmp/$m.out" 2>"$tmp/$m.err"; echo $? > "$tmp/$m.rc"
done
n=$(grep -c . "$tmp/trm.out")
if [ "$n" -ne 0 ] || [ "$(cat "$tmp/trm.rc")" -ne 1 ] || ! grep -q 'TRM refused' "$tmp/trm.err"; then
    echo "fw-refuse[trm]: FAIL: TRM stream on the 60 Hz panel: $n frames, exit $(cat "$tmp/trm.rc")"; cat "$tmp/trm.err"; fail=1
else echo "fw-refuse[trm]: refused at 60 Hz: $(grep 'TRM refused' "$tmp/trm.err" | head -1 | sed 's/^\[host\] //')"; fi
# plain (mono): frame 1 is rejected (its only eye) and frame 3 lost on the
# way (fw_stream), so 4 of 6 are shown
for m in plain:4 subframes:6; do
    s=${m%%:*}; want=${m#*:}; n=$(grep -c . "$tmp/$s.out")
    if [ "$n" -ne "$want" ] || [ "$(cat "$tmp/$s.rc")" -ne 0 ]; then
        echo "fw-refuse[$s]: FAIL: $n of $want frames, exit $(cat "$tmp/$s.rc")"; cat "$tmp/$s.err"; fail=1
    else echo "fw-refuse[$s]: $n frames shown (link, $( [ $s = subframes ] && echo 'tile assembly, ')LCD inverse)"; fi
done
exit $fail
