#!/bin/sh
# The image check must be able to fail: on an image built to break the
# rules (tests/arm/bad_rules.c: float division, double multiply, malloc,
# free) it has to fail and name those symbols.
# Usage: tests/arm/test_image_rules.sh ARM_NM BAD_IMAGE
nm=$1; bad=$2
dir=$(dirname "$0")
out=$("$dir/check_image_symbols.sh" "$nm" "$bad" 2>&1)
if [ $? -eq 0 ]; then echo "image rules self-test: the check passed an image with float and heap:"; echo "$out"; exit 1; fi
rc=0
for s in __aeabi_fdiv __aeabi_dmul malloc free _sbrk; do
    if ! printf '%s\n' "$out" | grep -q "'$s'"; then echo "image rules self-test: '$s' not reported"; rc=1; fi
done
[ "$rc" -eq 0 ] && echo "image rules self-test: the check fails on the bad image and names: $(printf '%s\n' "$out" | grep -o "'[^']*'" | sort -u | tr '\n' ' ')"
exit $rc
