#!/usr/bin/python3
"""The exit-code table is written once (common/tdc_exit.h); every
other place that shows it must agree:

  1. docs/tools.md's table is exactly `tdc_exit.py markdown`;
  2. README.md lists exactly `tdc_exit.py short`;
  3. every "| N | NAME |" row of a "| code | name |" table and every "N NAME" pair after "exit
     codes" in README.md and docs/*.md names a code of the table with its
     number (per-program tables with examples, hosttools.md, sweeps.md);
  4. the C names: tdc_tool.c and tdc_tool.h hold no table of their own;
  5. the Python tools take their numbers from the table (no literals) and a
     bad command line exits ARGS.

Usage: tests/unit/test_exit_table.py (from the repository root)
"""
import glob
import os
import re
import subprocess
import sys

REPO = os.getcwd()
sys.path.insert(0, os.path.join(REPO, "common"))
import tdc_exit  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tdc_check import check, done  # noqa: E402

names = {code: name for code, name, _, _ in tdc_exit.EXIT.rows}
PAIR = re.compile(r"\b(\d{1,2}) ([A-Z][A-Z_]{1,15})\b")

def bad_pairs(text):
    return ["%s %s" % (n, w) for n, w in PAIR.findall(text) if names.get(int(n)) != w]

# 1. docs/tools.md: the table, exactly
doc = open("docs/tools.md").read()
start = doc.find("| code | name | meaning | programs |")
table = doc[start:doc.find("\n\n", start)].strip() if start >= 0 else ""
check(table == tdc_exit.markdown(), "docs/tools.md table == tdc_exit.py markdown")

# 2. README: the short list, exactly (line breaks aside)
readme = open("README.md").read()
check(tdc_exit.short() in " ".join(readme.split()), "README.md lists tdc_exit.py short")

# 3. every code named anywhere in the docs
for path in ["README.md"] + sorted(glob.glob("docs/*.md")):
    lines = open(path).read().splitlines()
    wrong = []
    in_table = False  # inside a table headed "| code | name |"
    for i, line in enumerate(lines):
        in_table = line.startswith("|") and (in_table or line.startswith("| code | name |"))
        m = re.match(r"^\| (\d+) \| ([A-Z_]+) \|", line)
        if in_table and m and names.get(int(m.group(1))) != m.group(2):
            wrong.append("line %d: %s %s" % (i + 1, m.group(1), m.group(2)))
        if re.search(r"exit codes", line, re.I):
            # the list goes on over the next lines of the paragraph
            para = []
            for nxt in lines[i:i + 5]:
                if not nxt.strip():
                    break
                para.append(nxt)
            wrong += ["line %d: %s" % (i + 1, p) for p in bad_pairs(" ".join(para))]
    check(not wrong, "%s names every exit code with its number %s" % (path, wrong or ""))

# 4. C: the names come from the X-macro, nothing written by hand
for path in ("common/tdc_tool.c", "common/tdc_tool.h"):
    src = open(path).read()
    check('"NO_DEVICE"' not in src and "= 17" not in src and "TDC_EXIT_TABLE" in src,
          "%s builds on TDC_EXIT_TABLE, no table of its own" % path)

# 5. the Python tools: numbers from the table, ARGS for a bad command line
for path, argv in (("sim/sweep/tdc_sweep.py", ["local", "--no-such-option"]),
                   ("sim/experiments/tdc_experiments.py", ["list", "--no-such-option"])):
    src = open(path).read()
    check("from tdc_exit import EXIT" in src and not re.search(r"^EXIT_\w+.*= *\d", src, re.M),
          "%s takes its exit codes from tdc_exit" % path)
    p = subprocess.run([sys.executable, path] + argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    check(p.returncode == tdc_exit.EXIT.ARGS, "%s %s: exit %d (want %d ARGS)" % (
        os.path.basename(path), " ".join(argv), p.returncode, tdc_exit.EXIT.ARGS))

# the reader itself refuses a table with a gap
tmp = os.path.join(os.environ.get("TMPDIR", "/tmp"), "tdc_exit_gap.%d.h" % os.getpid())
with open(tmp, "w") as f:
    f.write('    X(0, OK, "a", "b") \\\n    X(2, ARGS, "a", "b")\n')
try:
    tdc_exit.read_table(tmp)
    check(False, "tdc_exit.read_table refuses a gap")
except ValueError:
    check(True, "tdc_exit.read_table refuses a gap")
os.remove(tmp)

done("exit table")
