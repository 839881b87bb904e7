#!/bin/sh
# Firmware rules on linked target images: no floating-point helper
# (__aeabi_f*, __aeabi_d*, __*sf3, __*df3, ...) and no heap function
# (malloc, _malloc_r, free, _sbrk, ...) may be in the image.  Same symbol
# list as the object check (tests/rules/check_fw_symbols.sh), applied to every
# symbol of the image; prints each offending symbol.
# Usage: tests/arm/check_image_symbols.sh ARM_NM image.elf...
ARM_NM=$1; shift
export ARM_NM
dir=$(dirname "$0")
for img in "$@"; do
    if ! "$ARM_NM" "$img" >/dev/null 2>&1; then echo "image rules: cannot read $img"; exit 1; fi
    n=$("$ARM_NM" "$img" | wc -l)
    if [ "$n" -lt 10 ]; then echo "image rules: $img has only $n symbols (stripped?)"; exit 1; fi
done
out=$("$dir/../rules/check_fw_symbols.sh" "$dir/nm_all.sh" "$@"); rc=$?
printf '%s\n' "$out" | sed 's/referenced by/linked into/; s/objects, no float/images, no float/'
exit $rc
