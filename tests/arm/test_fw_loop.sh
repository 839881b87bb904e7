#!/bin/sh
# The frame loop after loss and on every stream our renderer writes
# (issue 17 item 3): each crafted stream of tests/arm/fw_stream.c is run
# through the host build of the loop (tests/arm/tdc_board_host.c) and the
# frames it shows are compared with those of its clean reference stream.
#   trm-motion     per-pixel MOTION packets (the renderer sends them for any
#                  moving scene): every frame shown, as without them
#   trm-future     a rejected packet with a far-future frame index: it must
#                  not move the loop's notion of time (all frames shown)
#   trm-rehdr      the identical stream header after every frame: a no-op
#   subframes-late a subframe stream joined at frame 1000: assembly syncs to
#                  the stream's index and shows what a stream from 0 shows
#   trm-resend     a rejected FULL resent intact after its frame was shown,
#                  then that eye's next REDUCED rejected: from frame 3 on the
#                  frames of the reference (FULL intact, REDUCED rejected),
#                  i.e. the kept eye shows a processed image, never a raw one
# Usage: test_fw_loop.sh HOST_LOOP FW_STREAM W H EYES
host=$1; gen=$2; w=$3; h=$4; eyes=$5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
frames=6
fail=0
run() { # mode -> $tmp/mode.out
    "$gen" "$1" "$w" "$h" "$eyes" "$frames" "$tmp/$1.tdcs" || { echo "fw-loop: fw_stream $1 failed"; exit 1; }
    "$host" "$tmp/$1.tdcs" >"$tmp/$1.out" 2>"$tmp/$1.err"
    rm -f "$tmp/$1.tdcs"
}
check() { # label crafted reference [awk filter applied to both]
    a=$(awk "$4" "$tmp/$2.out"); b=$(awk "$4" "$tmp/$3.out")
    n=$(printf '%s\n' "$a" | grep -c .)
    if [ "$n" -eq 0 ] || [ "$a" != "$b" ]; then
        echo "fw-loop[$1]: FAIL: $2 shows $(grep -c . "$tmp/$2.out") frames, not those of $3:"
        diff "$tmp/$2.out" "$tmp/$3.out" | head -10; grep -v ': 0$' "$tmp/$2.err" | head -20
        fail=1
    else
        echo "fw-loop[$1]: $n frames as the reference ($(grep -E 'skipped|repeated|late full|restarts|rejected' "$tmp/$2.err" | grep -v ': 0$' | sed 's/^\[host\] //' | tr '\n' ';'))"
    fi
}
for m in trm trm-motion trm-future trm-rehdr trm-resend trm-resend-ref subframes subframes-late; do run $m; done
[ "$(grep -c . "$tmp/trm.out")" -eq "$frames" ] || { echo "fw-loop: FAIL: the clean TRM stream shows $(grep -c . "$tmp/trm.out") of $frames frames"; fail=1; }
check motion trm-motion trm '{print}'
check future trm-future trm '{print}'
check rehdr trm-rehdr trm '{print}'
check late subframes-late subframes '{print $3}'
check resend trm-resend trm-resend-ref '$2 >= 3 || $2 < 2 {print}'
grep -q 'late full packets processed: 1' "$tmp/trm-resend.err" || { echo "fw-loop[resend]: FAIL: the resent FULL was not processed"; fail=1; }
exit $fail
