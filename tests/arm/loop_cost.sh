#!/bin/sh
# Instructions the firmware frame loop spends per shown frame on a stream:
# runs a firmware image in QEMU under the counting plugin with marks on
# tdc_board_panel_show (0) and tdc_board_vsync_wait (1).  Frame k costs
# show_k - vsync_(k-1): transport reads, link decode and every stage up to
# the panel, without the emulated panel's own checksum.  Frame 0 (start-up)
# is left out.  Prints "label<TAB>instructions/frame<TAB>instructions/pixel".
# Usage: tests/arm/loop_cost.sh NM PLUGIN IMAGE STREAM PIXELS LABEL QEMU_ARGS...
nm=$1; plugin=$2; image=$3; stream=$4; pixels=$5; label=$6; shift 6
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
a=$("$nm" "$image" | awk '$3 == "tdc_board_panel_show" { print "0x" $1 }')
b=$("$nm" "$image" | awk '$3 == "tdc_board_vsync_wait" { print "0x" $1 }')
[ -n "$a" ] && [ -n "$b" ] || { echo "loop-cost: marks not found in $image" >&2; exit 1; }
if ! timeout 600 qemu-system-arm "$@" -display none -nodefaults -semihosting-config enable=on,target=native \
        -plugin "$plugin,mark=$a+$b,out=$tmp/marks" -kernel "$image" -append "$stream" >"$tmp/out" 2>"$tmp/err"; then
    grep -v 'has no peer' "$tmp/err" >&2; echo "loop-cost: QEMU run failed ($image)" >&2; exit 1
fi
awk -v px="$pixels" -v label="$label" '
    $1 == "total" { next }
    $3 == 1 { last_vsync = $2; have = 1; next }
    $3 == 0 && have { sum += $2 - last_vsync; n++ }
    END { if (!n) { print "loop-cost: fewer than two frames shown" > "/dev/stderr"; exit 1 }
          printf "%s\t%.0f\t%.1f\n", label, sum / n, sum / n / px }' "$tmp/marks"
