#!/bin/sh
# Prints the allocated sections of a linked image (arm-none-eabi-size -A)
# and how full each memory region of the board is.
# Usage: tests/arm/size_report.sh SIZE_TOOL IMAGE "BOARD_MEM"
#   BOARD_MEM: name:origin:length:attrs ... (from board.mk)
size=$1; image=$2; mem=$3
"$size" -A "$image" | awk -v mem="$mem" '
    function bytes(s,  n, u) { n = s + 0; u = substr(s, length(s)); if (u == "K") n *= 1024; else if (u == "M") n *= 1048576; return n }
    function hex(s,  i, c, n) { n = 0; s = tolower(s); sub(/^0x/, "", s)
        for (i = 1; i <= length(s); i++) { c = index("0123456789abcdef", substr(s, i, 1)) - 1; n = n * 16 + c } return n }
    BEGIN { nr = split(mem, r, " ")
            for (i = 1; i <= nr; i++) { split(r[i], f, ":"); name[i] = f[1]; org[i] = hex(f[2]); len[i] = bytes(f[3]); used[i] = 0 }
            printf "    %-14s %12s  %s\n", "section", "size", "address" }
    $1 ~ /^\./ && $1 !~ /^\.(debug|comment|ARM\.attributes)/ && $2 > 0 {
        printf "    %-14s %12d  0x%08x\n", $1, $2, $3
        for (i = 1; i <= nr; i++) if ($3 >= org[i] && $3 < org[i] + len[i]) used[i] += $2
        if ($1 == ".data") used[1] += $2 }  # .data also has a load image in the first (code) region
    END { for (i = 1; i <= nr; i++)
            printf "    region %-8s %10d of %10d bytes used (%5.1f %%)\n", name[i], used[i], len[i], 100.0 * used[i] / len[i] }'
