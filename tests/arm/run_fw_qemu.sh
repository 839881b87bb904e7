#!/bin/sh
# End-to-end check of a firmware image: the frame loop runs in QEMU on a
# link stream file and must show exactly the frames (same checksums, same
# order) as the same loop built for the host (tests/arm/tdc_board_host.c).
# If STREAM.expected exists (tests/arm/fw_stream.c writes it for plain
# streams on panels that show decoded codes), the host build must also show
# exactly those frames: the loop's result, not just its consistency.
# Usage: tests/arm/run_fw_qemu.sh LABEL TIMEOUT_S IMAGE HOST_DOUBLE STREAM QEMU_ARGS...
label=$1; limit=$2; image=$3; host=$4; stream=$5; shift 5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if ! "$host" "$stream" >"$tmp/host" 2>"$tmp/host.err"; then
    echo "fw[$label]: host reference failed on $stream:"; cat "$tmp/host.err"; exit 1
fi
if [ -f "$stream.expected" ] && ! cmp -s "$stream.expected" "$tmp/host"; then
    echo "fw[$label]: the host build of the loop does not show the expected frames ($stream.expected):"
    diff "$stream.expected" "$tmp/host" | head -20
    exit 1
fi
timeout "$limit" qemu-system-arm "$@" -display none -nodefaults -semihosting-config enable=on,target=native \
    -kernel "$image" -append "$stream" >"$tmp/arm" 2>"$tmp/arm.err"
status=$?
grep -v 'has no peer' "$tmp/arm.err" | sed "s/^/    /"
if [ "$status" -eq 124 ]; then echo "fw[$label]: QEMU timed out after ${limit} s"; exit 1; fi
if [ "$status" -ne 0 ]; then echo "fw[$label]: firmware exited with status $status"; exit 1; fi
n=$(wc -l <"$tmp/host")
if [ "$n" -eq 0 ]; then echo "fw[$label]: the host reference showed no frame ($stream)"; exit 1; fi
if ! cmp -s "$tmp/host" "$tmp/arm"; then
    echo "fw[$label]: panel output differs from the host build ($stream):"
    diff "$tmp/host" "$tmp/arm" | head -20
    exit 1
fi
echo "fw[$label]: $n frames bit-exact with the host build ($(basename "$stream"))$([ -f "$stream.expected" ] && echo ', and as expected')"
