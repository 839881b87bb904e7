#!/bin/sh
# Firmware rule "no recursion", checked on the call graph gcc builds:
# compiles each firmware source at -O0 (no inlining hides a cycle) with
# -fcallgraph-info and looks for a cycle across all translation units.
# Indirect calls (function pointers) are listed: they are not followed.
# Usage: tests/check_no_recursion.sh CFLAGS -- source.c...
flags=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do flags="$flags $1"; shift; done
shift
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
i=0
for src in "$@"; do
    i=$((i+1))
    # shellcheck disable=SC2086
    (cd "$tmp" && gcc -O0 $flags -fcallgraph-info -c "$OLDPWD/$src" -o "$tmp/$i.o") || { echo "recursion check: cannot compile $src"; exit 1; }
done
python3 - "$tmp" <<'PY'
import glob, re, sys
edges, indirect = {}, []
for ci in glob.glob(sys.argv[1] + "/*.ci"):
    for line in open(ci):
        m = re.match(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"(?: label: "([^"]*)")?', line)
        if m:
            if m.group(2) == "__indirect_call":
                indirect.append("%s (%s)" % (m.group(1), m.group(3)))
            else:
                edges.setdefault(m.group(1), set()).add(m.group(2))
# iterative DFS cycle detection
WHITE, GREY, BLACK = 0, 1, 2
color, cycle = {}, None
for root in list(edges):
    if color.get(root, WHITE) != WHITE or cycle:
        continue
    stack = [(root, iter(sorted(edges.get(root, ()))))]
    path = [root]
    color[root] = GREY
    while stack and not cycle:
        node, it = stack[-1]
        nxt = next(it, None)
        if nxt is None:
            color[node] = BLACK
            stack.pop(); path.pop()
        elif color.get(nxt, WHITE) == GREY:
            cycle = path[path.index(nxt):] + [nxt]
        elif color.get(nxt, WHITE) == WHITE:
            color[nxt] = GREY
            stack.append((nxt, iter(sorted(edges.get(nxt, ())))))
            path.append(nxt)
nfun = len(set(edges) | {t for s in edges.values() for t in s})
if cycle:
    print("firmware rule broken: recursion: " + " -> ".join(cycle))
    sys.exit(1)
print("no recursion: %d functions in the firmware call graph, no cycle; %d indirect call sites not followed%s"
      % (nfun, len(indirect), (": " + ", ".join(indirect[:6])) if indirect else ""))
PY
