#!/bin/sh
# Where the instructions go: runs one group of the ARM bench image
# (link|trm|assemble|lcd) under the counting plugin with its per-block
# profile, and prints the functions that executed the most instructions
# (static functions the compiler inlined count in their caller).
# Usage: tests/arm/profile_arm.sh NM PLUGIN IMAGE GROUP QEMU_ARGS...
nm=$1; plugin=$2; image=$3; group=$4; shift 4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mark=$("$nm" "$image" | awk '$3 == "tdc_bench_mark" { print "0x" $1 }')
if ! timeout 600 qemu-system-arm "$@" -display none -nodefaults -semihosting-config enable=on,target=native \
        -plugin "$plugin,mark=$mark,out=$tmp/marks,tbprof=$tmp/prof" -kernel "$image" -append "$group" \
        >"$tmp/labels" 2>"$tmp/err"; then
    grep -v 'has no peer' "$tmp/err" >&2; echo "profile-arm: QEMU run failed" >&2; exit 1
fi
"$nm" -S -t d --defined-only "$image" | awk 'NF == 4 && ($3 == "T" || $3 == "t") { print $1, $2, $4 }' |
    sort -n >"$tmp/syms"
awk -v group="$group" '
    function hex(s,  i, c, n) { n = 0; s = tolower(s)
        for (i = 1; i <= length(s); i++) { c = index("0123456789abcdef", substr(s, i, 1)) - 1; n = n * 16 + c } return n }
    FNR == NR { a[++ns] = $1 + 0; z[ns] = $2 + 0; name[ns] = $3; next }
    { addr = hex($1); ins = $2 * $3; total += ins; f = "?"
      lo = 1; hi = ns; while (lo <= hi) { mid = int((lo + hi) / 2); if (a[mid] <= addr) { best = mid; lo = mid + 1 } else hi = mid - 1 }
      if (best && addr < a[best] + z[best]) f = name[best]
      per[f] += ins }
    END { printf "instructions by function, bench group %s (whole run incl. input set-up): %.0f\n", group, total
          n = 0; for (f in per) { n++; k[n] = f }
          for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (per[k[j]] > per[k[i]]) { t = k[i]; k[i] = k[j]; k[j] = t }
          for (i = 1; i <= n && i <= 15; i++) printf "  %6.2f %%  %14.0f  %s\n", 100 * per[k[i]] / total, per[k[i]], k[i] }' \
    "$tmp/syms" "$tmp/prof"
