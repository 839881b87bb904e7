#!/bin/sh
# The memory-fit check must fail a board/panel pair that does not fit, with
# a message naming the region and the shortfall.
# Usage: tests/arm/test_fit.sh BOARD PANEL STAGES REGION
#   STAGES: default (the board's), link (none), or stages joined by '+'
# (runs make; MAKE selects the make program)
board=$1; panel=$2; stages=$3; region=$4
log=$(mktemp)
trap 'rm -f "$log"' EXIT
case $stages in
    default) set -- ;;
    link) set -- "STAGES=" ;;
    *) set -- "STAGES=$(echo "$stages" | tr + ' ')" ;;
esac
if ${MAKE:-make} --no-print-directory BOARD="$board" PANEL="$panel" "$@" firmware >"$log" 2>&1; then
    echo "fit[$board/$panel]: the build succeeded, but it must not fit region $region"; exit 1
fi
msg=$(grep "^memory fit: .* does not fit board $board: region $region short by [0-9][0-9]* bytes" "$log")
if [ -z "$msg" ]; then
    echo "fit[$board/$panel]: the build failed without the memory-fit message for region $region:"
    tail -20 "$log"; exit 1
fi
echo "fit[$board/$panel]: fails as it must: $msg"
grep '^    g_' "$log"
