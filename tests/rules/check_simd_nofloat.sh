#!/bin/sh
# Firmware rule check on compiled x86-64 and AArch64 objects: no floating-point
# instructions.  -mgeneral-regs-only makes float a compile error for gcc, but
# clang builds and the SIMD kernels (tdc_trm_avx2.c, compiled with vector
# registers on purpose) need the check on the machine code itself: scalar or
# packed float arithmetic, float compares and conversions, x87.  Integer
# SIMD and bit moves (loads, stores, blends, shuffles, even when the compiler
# picks a "ps" form of a bitwise move) are allowed.  AArch64 (the NEON
# kernels, firmware/tdc_trm_neon.c): scalar or vector float arithmetic,
# compares, conversions (fadd ... fsqrt, fcvt*, scvtf/ucvtf, frint*); fmov
# between a general and a vector register is a bit move and allowed.
# Usage: tests/check_simd_nofloat.sh OBJDUMP object...
objdump_tool=$1; shift
bad=0
for o in "$@"; do
    hits=$("$objdump_tool" -d --no-show-raw-insn "$o" 2>/dev/null | awk -F'\t' 'NF >= 2 { split($2, w, " "); print w[1] }' |
        grep -E '^v?(add|sub|mul|div|sqrt|min|max|rcp|rsqrt|round|comi|ucomi|hadd|hsub|dp|addsub|fn?m(add|sub)[0-9]*)(ss|sd|ps|pd|sh|ph)$|^v?cvt|^f(ld|st|add|sub|mul|div|sqrt|ild|ist|com|ucom)|^f(cvt|n?madd|n?msub|cmp|ccmp|abs|neg|max|min|rint|ml[as]|recp|rsqrt|csel)|^[su]cvtf' |
        sort | uniq -c)
    if [ -n "$hits" ]; then
        echo "firmware rule broken: floating-point instructions in $o:"; echo "$hits"; bad=1
    fi
done
if [ "$bad" -ne 0 ]; then exit 1; fi
echo "firmware rules: $# objects, no floating-point instructions"
