#!/bin/sh
# Firmware rule "layers without circles", checked on the #include lines:
# a module is a file stem (tdc_wire.h and tdc_wire.c are module tdc_wire);
# module A uses B when a file of A includes "B.h".  A circle (A uses B, B
# uses ... A) means neither can be read, tested or replaced without the
# other; the check prints each circle with the include lines that close it.
#   check_include_cycles.sh DIR...        the modules of DIR/*.[ch] (exit 1 on a circle)
#   check_include_cycles.sh --selftest DIR...
#       the same, then on a copy of DIR with a circle planted (the first
#       module that includes another made to be included back): must fail
if [ "$1" = "--selftest" ]; then
    shift
    "$0" "$@" || exit 1
    tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
    for d in "$@"; do mkdir -p "$tmp/$d" && cp "$d"/*.[ch] "$tmp/$d/"; done
    # plant: a header every other module builds on (tdc_fixed.h) includes a
    # module that includes it (tdc_math.h)
    f="$tmp/$1/tdc_fixed.h"
    [ -f "$f" ] || { echo "include circles selftest: no $1/tdc_fixed.h to plant a circle in"; exit 1; }
    sed -i '0,/^#include "tdc_status.h"/s//#include "tdc_status.h"\n#include "tdc_math.h"/' "$f"
    grep -q '"tdc_math.h"' "$f" || { echo "include circles selftest: could not plant the circle"; exit 1; }
    if (cd "$tmp" && "$OLDPWD/$0" "$@") >"$tmp/out" 2>&1; then
        echo "include circles selftest: FAIL: a planted circle (tdc_fixed.h -> tdc_math.h -> tdc_fixed.h) was not found"
        exit 1
    fi
    grep -q 'tdc_fixed' "$tmp/out" || { echo "include circles selftest: FAIL: the report does not name the circle:"; cat "$tmp/out"; exit 1; }
    echo "include circles selftest: a planted circle is found:"; sed 's/^/    /' "$tmp/out"
    exit 0
fi
exec python3 - "$@" <<'PY'
import glob, os, re, sys
uses = {}  # module -> {module: "file:line"}
for d in sys.argv[1:]:
    for f in sorted(glob.glob(os.path.join(d, "*.[ch]"))):
        a = os.path.splitext(os.path.basename(f))[0]
        uses.setdefault(a, {})
        for n, line in enumerate(open(f, encoding="utf-8", errors="replace"), 1):
            m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if m:
                b = os.path.splitext(os.path.basename(m.group(1)))[0]
                if b != a:
                    uses[a].setdefault(b, "%s:%d" % (f, n))
# strongly connected components (iterative Tarjan): each with > 1 module is a circle
index, low, on, stack, comps, n = {}, {}, set(), [], [], 0
for root in sorted(uses):
    if root in index:
        continue
    work = [(root, iter(sorted(uses[root])))]
    index[root] = low[root] = n; n += 1; stack.append(root); on.add(root)
    while work:
        v, it = work[-1]
        w = next((x for x in it if x in uses), None)
        if w is not None:
            if w not in index:
                index[w] = low[w] = n; n += 1; stack.append(w); on.add(w)
                work.append((w, iter(sorted(uses[w]))))
            elif w in on:
                low[v] = min(low[v], index[w])
            continue
        work.pop()
        if work:
            low[work[-1][0]] = min(low[work[-1][0]], low[v])
        if low[v] == index[v]:
            comp = []
            while True:
                x = stack.pop(); on.discard(x); comp.append(x)
                if x == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))
for comp in comps:
    print("include circle: " + " <-> ".join(comp))
    for a in comp:
        for b, where in sorted(uses[a].items()):
            if b in comp:
                print("    %s uses %s (%s)" % (a, b, where))
if comps:
    sys.exit(1)
print("include circles: none among %d modules (%s)" % (len(uses), " ".join(sys.argv[1:])))
PY
