#!/bin/sh
# make test-aarch64: the Linux board program cross-built for arm64 (static,
# with Debian's arm64 libdrm/libgpiod from multiarch) runs under
# qemu-aarch64 on .tdcs streams (--stream FILE --no-display: one "frame N
# fnv1a64" line per shown frame) and shows the frames the x86-64 build of the
# same board shows, byte for byte.  A stream that shows no frame fails:
# identical empty outputs prove nothing.
# Usage: arm64_board_check.sh X86_BOARD ARM64_BOARD STREAM...
set -u
x86=$1; a64=$2; shift 2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rc=0
# ELF e_machine (offset 18, little-endian): 0xb7 = EM_AARCH64
[ "$(od -An -tx1 -j18 -N2 "$a64" | tr -d ' ')" = b700 ] || { echo "arm64-board: $a64 is not an AArch64 program"; exit 1; }
for s in "$@"; do
    name=$(basename "$s")
    "$x86" --stream "$s" --no-display > "$tmp/x86" 2> "$tmp/x86.log" || { echo "arm64-board: $name: x86-64 board failed"; cat "$tmp/x86.log"; rc=1; continue; }
    qemu-aarch64 "$a64" --stream "$s" --no-display > "$tmp/a64" 2> "$tmp/a64.log" || { echo "arm64-board: $name: arm64 board failed under qemu-aarch64"; tail -n 5 "$tmp/a64.log"; rc=1; continue; }
    n=$(grep -c '^frame ' "$tmp/x86")
    if [ "$n" -eq 0 ]; then echo "arm64-board: $name: no frame shown"; rc=1
    elif ! cmp -s "$tmp/x86" "$tmp/a64"; then echo "arm64-board: $name: arm64 frames differ from x86-64:"; diff "$tmp/x86" "$tmp/a64" | head -10; rc=1
    else echo "arm64-board: $name: $n frames identical (arm64 under qemu-aarch64 = x86-64)"; fi
done
exit $rc
