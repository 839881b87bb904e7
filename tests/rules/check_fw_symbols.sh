#!/bin/sh
# Firmware rule check on compiled objects: no floating-point helpers, no heap.
# Usage: tests/check_fw_symbols.sh NM object...
# Prints every offending symbol with the object that references it.
nm_tool=$1; shift
bad=0
for o in "$@"; do
    syms=$("$nm_tool" -u "$o" 2>/dev/null | awk '{print $NF}')
    for s in $syms; do
        case "$s" in
            malloc|calloc|realloc|free|_malloc_r|_free_r|_calloc_r|_realloc_r|_sbrk|_sbrk_r|sbrk|aligned_alloc|posix_memalign|memalign|alloca)
                echo "firmware rule broken: heap symbol '$s' referenced by $o"; bad=1 ;;
            __aeabi_f*|__aeabi_d*|__aeabi_i2f|__aeabi_i2d|__aeabi_ui2f|__aeabi_ui2d|__aeabi_l2f|__aeabi_l2d|__*sf3|__*df3|__*sf2|__*df2|__*tf3|__float*|__fix*|__extend*|__trunc*|sqrt|sqrtf|pow|powf|exp|expf|log|logf|floor|ceil|round|lround|fabs)
                echo "firmware rule broken: floating-point symbol '$s' referenced by $o"; bad=1 ;;
        esac
    done
done
if [ "$bad" -ne 0 ]; then exit 1; fi
echo "firmware rules: $# objects, no float or heap symbols"
