#!/bin/sh
# Firmware rule check on Cortex-M objects built with vector registers on
# purpose (the Helium kernels, firmware/tdc_trm_mve.c): no floating-point
# instructions in the machine code -- MVE or VFP arithmetic on .f16/.f32/
# .f64 lanes, conversions (vcvt, vrint*), or moves to/from s/d registers
# for arithmetic.  Integer MVE (.i/.s/.u lanes, gathers, predication) is
# allowed.  (The object is compiled with +nofp, so this is the backstop.)
# Usage: check_arm_nofloat.sh OBJDUMP object...
objdump_tool=$1; shift
bad=0
for o in "$@"; do
    n=$("$objdump_tool" -d --no-show-raw-insn "$o" | grep -cE '^ +[0-9a-f]+:' )
    hits=$("$objdump_tool" -d --no-show-raw-insn "$o" | awk -F'\t' 'NF >= 2 { print $2 }' |
        grep -E '\.f(16|32|64)( |$)|^vcvt|^vrint|^vsqrt|^vdiv|^vfm' | sort | uniq -c)
    if [ -n "$hits" ]; then
        echo "firmware rule broken: floating-point instructions in $o:"; echo "$hits"; bad=1
    elif [ "$n" -eq 0 ]; then
        echo "firmware rule check: no instructions in $o (not built for this board?)"; bad=1
    fi
done
[ "$bad" -ne 0 ] && exit 1
echo "firmware rules: $# Helium objects, no floating-point instructions"
