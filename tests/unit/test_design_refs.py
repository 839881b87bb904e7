#!/usr/bin/python3
"""docs/design.md points at things that exist:

  1. README.md links its "where is X" table (two hops: README -> table -> place);
  2. every repository path named in backticks exists;
  3. in the "where is X" table, every identifier named in backticks
     (`name()`, `TDC_...`, `k_families`) occurs in a file named in its row,
     so a renamed or moved symbol fails here instead of sending a newcomer
     to nothing.

Usage: tests/unit/test_design_refs.py (from the repository root)
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tdc_check import check, done  # noqa: E402



design = open("docs/design.md").read()
check("docs/design.md#9-where-is-x" in open("README.md").read(), "README.md links docs/design.md#9-where-is-x")
check("\n## 9. Where is X\n" in design and "\n## 10. Layers\n" in design, "docs/design.md has §9 and §10")

# 2. paths
PATH = re.compile(r"`([A-Za-z0-9_.][A-Za-z0-9_./-]*/[A-Za-z0-9_.-]*)`")
missing = []
for p in sorted(set(PATH.findall(design))):
    if p.startswith("build/") or p.startswith("../") or (p.endswith("/") and p.count("/") == 1):
        continue  # generated, outside, or a sub-folder named within its parent's row
    if not os.path.exists(p):
        missing.append(p)
check(not missing, "every path named in docs/design.md exists %s" % (missing or ""))

# 3. the where-is-X table
sec = design[design.find("## 9. Where is X"):design.find("## 10. Layers")]
rows = [l for l in sec.splitlines() if l.startswith("| ") and not l.startswith("| what") and "---" not in l]
check(len(rows) >= 5, "the where-is-X table has its rows (%d)" % len(rows))
IDENT = re.compile(r"`([A-Za-z_][A-Za-z0-9_]*)(\(\))?`")
for row in rows:
    files = [p for p in PATH.findall(row) if os.path.isfile(p)]
    files += [os.path.join(d, p) for p in re.findall(r"`([a-z0-9_]+\.[ch])`", row)
              for d in ("firmware", "sim/simulator") if os.path.isfile(os.path.join(d, p))]
    text = "".join(open(f, errors="replace").read() for f in files)
    gone = [m.group(1) for m in IDENT.finditer(row)
            if (m.group(2) or m.group(1).isupper() or "_" in m.group(1)) and "<" not in m.group(1)
            and m.group(1) not in text]
    what = row.split("|")[1].strip()
    named = [p for p in PATH.findall(row) if os.path.exists(p)]
    check(named and not gone, "where is X '%s': %d file(s), symbols found %s" % (what, len(files), gone or ""))

done("design refs")
