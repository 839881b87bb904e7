#!/bin/sh
# tdc-zeng's command line (sim/zeng/zeng_main.c, docs/tools.md): each bad
# argument gets one "tdc-zeng: ...: why" line and its named exit code before
# any ground truth is traced; a tiny run writes every method's row and the
# cost rows.  Usage: tests/unit/test_zeng_cli.sh TDC_ZENG
zeng=$1
. tests/unit/tool_expect.sh
expect 1 "unknown scene" "tdc-zeng: arguments: --scene" -- "$zeng" --scene nope
expect 1 "no scene" "tdc-zeng: arguments: --scene" -- "$zeng"
expect 1 "size too small" "tdc-zeng: arguments: --size" -- "$zeng" --scene fence --size 3x3
expect 1 "ground truth not a square" "tdc-zeng: arguments: --gt-spp" -- "$zeng" --scene fence --gt-spp 1000
expect 1 "evaluation starts after the last frame" "tdc-zeng: arguments: --frames" -- "$zeng" --scene fence --frames 4 --eval-from 4
expect 1 "option without value" "without its value" -- "$zeng" --scene
expect 1 "clamp source unknown" "tdc-zeng: arguments: --clamp-on: raw or filtered" -- "$zeng" --scene glossy --clamp-on median
expect 7 "csv in a missing folder" "tdc-zeng: --csv: cannot create $t/no/x.csv: No such file" -- "$zeng" --scene fence --csv "$t/no/x.csv"
expect 0 "tiny run" "" -- "$zeng" --scene glossy --size 16x16 --frames 3 --eval-from 2 --seeds "1 2" --gt-spp 4 --csv "$t/g.csv"
rows=$(grep -c '^glossy,' "$t/g.csv")
[ "$rows" -eq 12 ] && ok "tiny run: 6 methods x 2 seeds" || bad "tiny run: $rows rows, want 12"
grep -q '^cost,[0-9.]*,[0-9.]*,[0-9.]*$' "$t/g.csv" && ok "tiny run: cost row" || bad "tiny run: no cost row"
# the clamp over the filtered frame changes the clamped methods only
expect 0 "tiny run, clamp on the filtered frame" "" -- "$zeng" --scene glossy --size 16x16 --frames 3 --eval-from 2 --seeds "1 2" --gt-spp 4 --clamp-on filtered --csv "$t/f.csv"
d=$(paste -d, "$t/g.csv" "$t/f.csv" | awk -F, '$1 == "glossy" && $4 != $12 { print $3 }' | sort -u | tr '\n' ' ')
[ "$d" = "ours spec trad-clamp " ] && ok "filtered clamp: only the clamped methods move ($d)" || bad "filtered clamp: rows that moved: '$d'"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
