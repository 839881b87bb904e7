#!/bin/sh
# The layered family of the frame loop (firmware/board/tdc_fw_layers.c,
# STAGES=layers), host build: the layered streams of tests/arm/fw_stream.c
# (every layer, falloff, a hash ordering per cycle) must show every frame
# exactly as tdc_layers itself assembles the packets (fw_stream's expected
# frames: the stage with the family's configuration), without history
# (stream flags SUBFRAMES | LAYERS) and with it (+ LAYER_HIST); the two
# agree on frame 0 (no history yet) and differ on every later frame (the
# flag reaches the stage); a build without the layered stage refuses the
# stream by name and shows nothing.
# Usage: test_fw_layers.sh HOST_LAYERS HOST_WITHOUT FW_STREAM W H EYES PANEL
host=$1; other=$2; gen=$3; w=$4; h=$5; eyes=$6; panel=$7
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
for m in layers layers-hist; do
    "$gen" $m "$w" "$h" "$eyes" 4 "$tmp/$m.tdcs" "$tmp/$m.expected" "$panel" || { echo "fw-layers: fw_stream $m failed"; exit 1; }
    if ! "$host" "$tmp/$m.tdcs" >"$tmp/$m.out" 2>"$tmp/$m.err"; then
        echo "fw-layers[$m]: FAIL: the loop exited non-zero"; cat "$tmp/$m.err"; fail=1; continue
    fi
    if [ "$(grep -c . "$tmp/$m.out")" -ne 4 ] || ! cmp -s "$tmp/$m.out" "$tmp/$m.expected"; then
        echo "fw-layers[$m]: FAIL: the loop does not show what tdc_layers assembles:"; diff "$tmp/$m.expected" "$tmp/$m.out" | head; fail=1
    else echo "fw-layers[$m]: 4 frames as tdc_layers assembles them ($(grep 'with history' "$tmp/$m.err" | sed 's/^\[host\] //'))"; fi
done
same=$(paste -d' ' "$tmp/layers.out" "$tmp/layers-hist.out" | awk '$3 == $6 { n++ } END { print n + 0 }')
first=$(paste -d' ' "$tmp/layers.out" "$tmp/layers-hist.out" | awk 'NR == 1 { print ($3 == $6) }')
if [ "$first" != 1 ] || [ "$same" -ne 1 ]; then
    echo "fw-layers[history]: FAIL: with and without history, $same equal frames (want frame 0 only)"; fail=1
else echo "fw-layers[history]: frame 0 equal, frames 1-3 differ with LAYER_HIST"; fi
"$other" "$tmp/layers-hist.tdcs" >"$tmp/other.out" 2>"$tmp/other.err"
if [ "$(grep -c . "$tmp/other.out")" -ne 0 ] || ! grep -q 'refused' "$tmp/other.err"; then
    echo "fw-layers[refuse]: FAIL: a build without the layered stage showed $(grep -c . "$tmp/other.out") frames"; fail=1
else echo "fw-layers[refuse]: without STAGES=layers: $(grep refused "$tmp/other.err" | head -1 | sed 's/^\[host\] //')"; fi
exit $fail
