#!/bin/sh
# Joins the per-board bench results into one table.
# Usage: tests/arm/bench_table.sh BOARD=FILE...
awk '
    BEGIN { for (i = 1; i < ARGC; i++) { split(ARGV[i], a, "="); board[i] = a[1]; file[i] = a[2]; ARGV[i] = "" }
            nb = ARGC - 1
            cpu["mps2-an500"] = "Cortex-M7"; cpu["mps3-an547"] = "Cortex-M55"
            for (i = 1; i <= nb; i++) while ((getline l < file[i]) > 0) {
                split(l, f, "\t"); if (!(f[1] in seen)) { seen[f[1]] = 1; order[++n] = f[1] } v[f[1], i] = f[2] }
            printf "instructions per output pixel (QEMU TCG plugin count, 640 x 360 frames, gcc %s, soft-float ABI)\n", (ENVIRON["ARM_OPT"] != "" ? ENVIRON["ARM_OPT"] : "-O2")
            printf "%-48s", "stage"; for (i = 1; i <= nb; i++) printf " %12s", (board[i] in cpu ? cpu[board[i]] : board[i]); printf "\n"
            for (k = 1; k <= n; k++) { printf "%-48s", order[k]
                for (i = 1; i <= nb; i++) printf " %12s", ((order[k], i) in v ? v[order[k], i] : "-"); printf "\n" } }'  "$@"
