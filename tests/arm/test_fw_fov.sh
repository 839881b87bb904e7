#!/bin/sh
# Foveated streams on a build WITHOUT peripheral TAA (STAGES=fov; issue 14):
#   fov, fovlr   the frames the panel must show (fw_stream's EXPECTED,
#                computed through its own stage) exactly as a TAA build
#                shows them: packets without vectors are composed without
#                TAA in every build
#   fov-taa      its packets carry vectors, which this build has no buffer
#                for: every FOVEATED packet is refused by the decoder
#                (UNEXPECTED, counted), nothing foveated is shown, the FULL
#                picture of frame 6 is (the one packet it can play)
#   trm          a stream without foveated packets never starts the stage
#                (stage elision: "foveated frames composed: 0")
#   trm-fov      foveated TRM (REDUCED | FOVEATED, which the decoder
#                accepts): the loop refuses the stream by name (its
#                foveation block shares the mode arena with TRM's), shows
#                nothing and exits 1 (an unsupported stream)
# With BANDS_LOOP (the same build with row bands: front/back frame buffers,
# staging sized for a foveated payload) fov and fovlr must show the same
# expected frames through the swap, kept eyes copied from the front.
# Usage: test_fw_fov.sh HOST_LOOP FW_STREAM W H EYES [BANDS_LOOP]
host=$1; gen=$2; w=$3; h=$4; eyes=$5; bands=$6
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
for m in fov fovlr fov-taa trm trm-fov; do
    n=9; case $m in trm*) n=4;; esac
    "$gen" $m "$w" "$h" "$eyes" $n "$tmp/$m.tdcs" "$tmp/$m.exp" || { echo "fw-fov: fw_stream $m failed"; exit 1; }
    "$host" "$tmp/$m.tdcs" >"$tmp/$m.out" 2>"$tmp/$m.err"; echo $? > "$tmp/$m.rc"
done
for m in fov fovlr; do
    if ! cmp -s "$tmp/$m.exp" "$tmp/$m.out" || [ "$(grep -c . "$tmp/$m.out")" -lt 5 ]; then
        echo "fw-fov[$m]: FAIL: frames differ from the expected ones:"; diff "$tmp/$m.exp" "$tmp/$m.out" | head; fail=1
    else echo "fw-fov[$m]: $(grep -c . "$tmp/$m.out") frames as expected without TAA ($(grep -E 'composed|headers refused' "$tmp/$m.err" | sed 's/^\[host\] //' | tr '\n' ';'))"; fi
done
for m in fov fovlr; do
    [ -n "$bands" ] || continue
    "$bands" "$tmp/$m.tdcs" >"$tmp/$m.bout" 2>"$tmp/$m.berr"
    if ! cmp -s "$tmp/$m.exp" "$tmp/$m.bout"; then
        echo "fw-fov[$m, bands]: FAIL: the banded loop's frames differ from the expected ones:"
        diff "$tmp/$m.exp" "$tmp/$m.bout" | head; grep -v ': 0$' "$tmp/$m.berr" | head; fail=1
    else echo "fw-fov[$m, bands]: $(grep -c . "$tmp/$m.bout") frames as expected through the front/back swap ($(grep 'copied' "$tmp/$m.berr" | sed 's/^\[host\] //'))"; fi
done
rej=$(sed -n 's/.*packets\/bytes rejected: //p' "$tmp/fov-taa.err")
if [ "$(cat "$tmp/fov-taa.out" | awk '{print $2}' | tr '\n' ' ')" != "6 " ] || [ "${rej:-0}" -lt 16 ] ||
   ! grep -q 'foveated frames composed: 0' "$tmp/fov-taa.err"; then
    echo "fw-fov[fov-taa]: FAIL: vectors on a build without TAA: shown frames $(awk '{print $2}' "$tmp/fov-taa.out" | tr '\n' ' '), rejected ${rej:-?}"
    cat "$tmp/fov-taa.err"; fail=1
else echo "fw-fov[fov-taa]: every FOVEATED packet refused ($rej rejected), only the FULL picture of frame 6 shown"; fi
if [ "$(grep -c . "$tmp/trm.out")" -ne 4 ] || ! grep -q 'foveated frames composed: 0' "$tmp/trm.err"; then
    echo "fw-fov[trm]: FAIL: the TRM stream in a foveating build"; cat "$tmp/trm.err"; fail=1
else echo "fw-fov[trm]: 4 frames, stage not started"; fi
if [ -s "$tmp/trm-fov.out" ] || [ "$(cat "$tmp/trm-fov.rc")" -ne 1 ] || ! grep -q 'stream foveates TRM' "$tmp/trm-fov.err" ||
   ! grep -q 'unsupported streams: 1' "$tmp/trm-fov.err"; then
    echo "fw-fov[trm-fov]: FAIL: foveated TRM not refused by name"; cat "$tmp/trm-fov.err"; fail=1
else echo "fw-fov[trm-fov]: refused: $(grep 'stream foveates' "$tmp/trm-fov.err" | sed 's/^\[host\] //')"; fi
exit $fail
