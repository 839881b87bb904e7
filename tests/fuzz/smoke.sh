#!/bin/sh
# Bounded libFuzzer run (ASan + UBSan) of one fuzz target for `make test`,
# from its committed seeds; new inputs go to a scratch directory, never
# into the committed corpus.
# Usage: tests/fuzz/smoke.sh FUZZ_BINARY SECONDS ARTIFACT_DIR SEED_CORPUS
bin=$1; secs=$2; art=$3; seeds=${4:-tests/fuzz/corpus}
work=$(mktemp -d) || exit 1
log=$work/log
mkdir -p "$work/corpus" "$art"
"$bin" -max_total_time="$secs" -timeout=10 -close_fd_mask=2 -print_final_stats=1 -artifact_prefix="$art/" \
    "$work/corpus" "$seeds" > "$log" 2>&1
rc=$?
grep -E '^(stat::|SUMMARY|==[0-9]+==|Done )|INFO: seed corpus|ERROR|crash-|leak' "$log"
if [ $rc -ne 0 ]; then tail -40 "$log"; fi
echo "fuzz-smoke: $(basename "$bin"): libFuzzer exit status $rc after ${secs} s"
rm -rf "$work"
exit $rc
