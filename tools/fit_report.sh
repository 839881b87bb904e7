#!/bin/sh
# Turns the linker's region-overflow errors into the memory-fit verdict of a
# board/panel pair, and lists the large static buffers that were placed.
# Usage: tests/arm/fit_report.sh BOARD WHAT LINKER_LOG [NM object...]
# Prints, for every region that overflowed, its name and the shortfall in
# bytes and MiB; exits 1 if any region overflowed.
board=$1; what=$2; log=$3; shift 3
awk -v board="$board" -v what="$what" '
    /region `?[A-Za-z0-9_]+.? overflowed by [0-9]+ bytes/ {
        match($0, /region `?[A-Za-z0-9_]+/); r = substr($0, RSTART + 7, RLENGTH - 7); sub(/^`/, "", r)
        match($0, /overflowed by [0-9]+/); n = substr($0, RSTART + 14, RLENGTH - 14) + 0
        if (!(r in seen)) { seen[r] = 1
            printf "memory fit: %s does not fit board %s: region %s short by %d bytes (%.2f MiB)\n", what, board, r, n, n / 1048576 }
        bad = 1 }
    END { exit bad ? 1 : 0 }' "$log"
bad=$?
if [ "$bad" -ne 0 ] && [ $# -gt 1 ]; then
    nm=$1; shift
    echo "memory fit: static buffers of 64 KiB or more (sized from the panel and the stages):"
    "$nm" -S --size-sort -t d "$@" 2>/dev/null | awk '{ n = $2 + 0; if (n >= 65536) printf "    %-24s %10d bytes (%.2f MiB)\n", $4, n, n / 1048576 }'
fi
exit "$bad"
