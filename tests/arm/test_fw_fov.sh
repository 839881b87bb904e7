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
#   trm-fov      foveated TRM (REDUCED | FOVEATED; both slots foveated, a
#                CRC error in a reduced slot, a refused foveation header in
#                a full slot, one frame of plain slots): this build (trm and
#                fov) plays it through tdc_fov_trm and must show the frames
#                fw_stream computes without the loop (PANEL: TRM's profile),
#                with foveated pictures composed in both slots and the two
#                refusals counted; the builds without the foveation stage,
#                without TRM, and with both but TDC_CFG_FOV_TRM=0 must
#                refuse it (nothing shown, exit 1, the refusal named)
# With BANDS_LOOP (the same build with row bands: front/back frame buffers,
# staging sized for a foveated payload) fov, fovlr and trm-fov must show the
# same expected frames through the swap, kept eyes copied from the front.
# Usage: test_fw_fov.sh HOST_LOOP FW_STREAM W H EYES BANDS_LOOP PANEL|- NOFOV_LOOP NOTRM_LOOP OPTOUT_LOOP
host=$1; gen=$2; w=$3; h=$4; eyes=$5; bands=$6; panel=$7; nofov=$8; notrm=$9; shift 9; optout=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
for m in fov fovlr fov-taa trm trm-fov; do
    n=9; p=; case $m in trm) n=4;; trm-fov) n=8; [ "$panel" = - ] || p=$panel;; esac
    "$gen" $m "$w" "$h" "$eyes" $n "$tmp/$m.tdcs" "$tmp/$m.exp" $p || { echo "fw-fov: fw_stream $m failed"; exit 1; }
    "$host" "$tmp/$m.tdcs" >"$tmp/$m.out" 2>"$tmp/$m.err"; echo $? > "$tmp/$m.rc"
done
for m in fov fovlr; do
    if ! cmp -s "$tmp/$m.exp" "$tmp/$m.out" || [ "$(grep -c . "$tmp/$m.out")" -lt 5 ]; then
        echo "fw-fov[$m]: FAIL: frames differ from the expected ones:"; diff "$tmp/$m.exp" "$tmp/$m.out" | head; fail=1
    else echo "fw-fov[$m]: $(grep -c . "$tmp/$m.out") frames as expected without TAA ($(grep -E 'composed|headers refused' "$tmp/$m.err" | sed 's/^\[host\] //' | tr '\n' ';'))"; fi
done
for m in fov fovlr trm-fov; do
    [ -n "$bands" ] && [ -f "$tmp/$m.exp" ] || continue
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
# foveated TRM on this build: played, both slots foveated, refusals counted
t=$tmp/trm-fov
full=$(sed -n 's/.*foveated TRM pictures composed, full slot: //p' "$t.err")
red=$(sed -n 's/.*foveated TRM pictures composed, reduced slot: //p' "$t.err")
if [ "$(cat "$t.rc")" -ne 0 ] || [ "$(grep -c . "$t.out")" -lt 6 ] || [ "${full:-0}" -lt 2 ] || [ "${red:-0}" -lt 2 ] ||
   ! grep -q 'foveation headers refused: 1$' "$t.err" || ! grep -q 'stage errors: 0$' "$t.err" ||
   { [ -f "$t.exp" ] && ! cmp -s "$t.exp" "$t.out"; } || { [ "$panel" != - ] && [ ! -f "$t.exp" ]; }; then
    echo "fw-fov[trm-fov]: FAIL: foveated TRM not played as expected (rc $(cat "$t.rc"), slots composed ${full:-?}/${red:-?}):"
    [ -f "$t.exp" ] && diff "$t.exp" "$t.out" | head; grep -v ': 0$' "$t.err" | head -20; fail=1
else echo "fw-fov[trm-fov]: played: $(grep -c . "$t.out") frames$([ -f "$t.exp" ] && echo ' as expected'), foveated pictures composed $full full slot / $red reduced slot, $(sed -n 's/.*\(packets\/bytes rejected: [0-9]*\).*/\1/p' "$t.err"), 1 foveation header refused"; fi
# ... and refused by the builds that cannot play it
for b in nofov:"$nofov":'stream header refused by the decoder' notrm:"$notrm":'stream header refused by the decoder' \
         optout:"$optout":'stream foveates TRM frames: not in this build'; do
    name=${b%%:*}; r=${b#*:}; loop=${r%%:*}; why=${r#*:}
    "$loop" "$t.tdcs" >"$t.$name.out" 2>"$t.$name.err"; rc=$?
    if [ -s "$t.$name.out" ] || [ "$rc" -ne 1 ] || ! grep -q "$why" "$t.$name.err" ||
       grep -q 'unsupported streams: 0$' "$t.$name.err"; then
        echo "fw-fov[trm-fov, $name build]: FAIL: foveated TRM not refused (rc $rc, $(grep -c . "$t.$name.out") frames shown)"
        cat "$t.$name.err"; fail=1
    else echo "fw-fov[trm-fov, $name build]: refused, nothing shown: $(grep "$why" "$t.$name.err" | head -1 | sed 's/^\[host\] //')"; fi
done
exit $fail
