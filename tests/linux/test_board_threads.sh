#!/bin/sh
# make test: the Linux board's row workers (tdc-board --threads N: TRM's
# D(I) and output rows as bands on N threads, tdc_fw_trm.c) show the bytes
# of the one-threaded loop.  Each stream runs through the host double of the
# board's very loop objects (its board stub has one core: no bands, the
# reference) and through tdc-board --no-display with 2 and 3 threads (3:
# bands of unequal rows, band boundaries inside D's kernel reach); every
# "frame N fnv1a64" line must match the reference.  Streams (htc-vive,
# 2x1080x1200 @ 90 Hz): trm (eye 1's first REDUCED frame unpaired), trm-drop
# (eye 0's FULL of frame 2 rejected: its next REDUCED unpaired), trm-fov
# (foveated TRM: a corrupted payload, a refused header and the
# unpaired REDUCED slot after it).  A stream that
# shows no frame fails: identical empty outputs prove nothing.
# Usage: test_board_threads.sh TDC_BOARD HOST_DOUBLE FW_STREAM W H EYES
set -u
board=$1; host=$2; gen=$3; w=$4; h=$5; eyes=$6
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rc=0
for spec in trm:3 trm-drop:4 trm-fov:6; do
    m=${spec%%:*}; n=${spec#*:}
    "$gen" "$m" "$w" "$h" "$eyes" "$n" "$tmp/s.tdcs" > /dev/null || { echo "board-threads: $m: stream not made"; rc=1; continue; }
    "$host" "$tmp/s.tdcs" 2> /dev/null | grep '^frame ' > "$tmp/ref"
    shown=$(wc -l < "$tmp/ref")
    if [ "$shown" -eq 0 ]; then echo "board-threads: $m: the host double shows no frame"; rc=1; continue; fi
    for t in 2 3; do
        "$board" --stream "$tmp/s.tdcs" --no-display --threads "$t" > "$tmp/out" 2> "$tmp/log" ||
            { echo "board-threads: $m: tdc-board --threads $t failed"; tail -n 5 "$tmp/log"; rc=1; continue; }
        if ! cmp -s "$tmp/ref" "$tmp/out"; then
            echo "board-threads: $m: --threads $t shows other frames than the one-threaded loop:"
            diff "$tmp/ref" "$tmp/out" | head -6; rc=1
        else
            echo "board-threads: $m: --threads $t: $shown frames identical"
        fi
    done
done
exit $rc
