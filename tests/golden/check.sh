#!/bin/sh
# Compares a golden runner's output with tests/golden/*.expected, exactly.
# Names every vector and frame that differs, is missing or is unexpected.
# Usage: tests/golden/check.sh LABEL RUNNER_OUTPUT_FILE
#    or: tests/golden/check.sh LABEL -- command args...   (runs it)
label=$1; shift
dir=$(dirname "$0")
out=$(mktemp); exp=$(mktemp)
trap 'rm -f "$out" "$exp"' EXIT
if [ "$1" = "--" ]; then
    shift
    if ! "$@" > "$out"; then echo "golden[$label]: runner failed: $*"; exit 1; fi
else
    cat "$1" > "$out"
fi
cat "$dir"/*.expected 2>/dev/null | grep -v '^#' | grep -v '^$' > "$exp"
awk -v label="$label" '
    FNR == NR { want[$1 " " $2] = $3; next }
    { key = $1 " " $2; got[key] = $3
      if (!(key in want)) { printf "golden[%s]: UNEXPECTED %s frame %s = %s (no expected value)\n", label, $1, $2, $3; bad++ }
      else if (want[key] != $3) { printf "golden[%s]: MISMATCH %s frame %s: got %s want %s\n", label, $1, $2, $3, want[key]; bad++ } }
    END { for (k in want) if (!(k in got)) { split(k, a, " "); printf "golden[%s]: MISSING %s frame %s\n", label, a[1], a[2]; bad++ }
          n = 0; for (k in want) n++
          if (bad) { printf "golden[%s]: %d of %d checksums wrong\n", label, bad, n; exit 1 }
          printf "golden[%s]: %d checksums bit-exact\n", label, n }' "$exp" "$out"
