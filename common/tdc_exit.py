#!/usr/bin/python3
"""tdc_exit - the exit-code table of tdc_exit.h for Python tools and docs.

    from tdc_exit import EXIT          # EXIT.OK == 0, EXIT.ARGS == 1, ...
    EXIT.name(13)                      # 'INPUT'

    python3 common/tdc_exit.py markdown   # the table of docs/tools.md
    python3 common/tdc_exit.py short      # '0 OK, 1 ARGS, ...' (README)
    python3 common/tdc_exit.py list       # 'CODE NAME' lines (tests)

The table is written once, in tdc_exit.h (an X-macro the C programs
compile); this reads the same lines, so C, Python and the docs cannot
disagree.
"""
import os
import re
import sys

HEADER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "tdc_exit.h")
_ROW = re.compile(r'^\s*X\((\d+),\s*([A-Z_]+),\s*"((?:[^"\\]|\\.)*)",\s*"((?:[^"\\]|\\.)*)"\)')


def read_table(path=HEADER):
    """[(code, name, meaning, programs)] in code order; raises on a gap."""
    rows = []
    with open(path) as f:
        for line in f:
            m = _ROW.match(line)
            if m:
                rows.append((int(m.group(1)), m.group(2), m.group(3), m.group(4)))
    if [r[0] for r in rows] != list(range(len(rows))) or not rows:
        raise ValueError("%s: the codes are not 0..N-1 in order" % path)
    return rows


class _Exit(object):
    def __init__(self, rows):
        self.rows = rows
        for code, name, _, _ in rows:
            setattr(self, name, code)

    def name(self, code):
        return self.rows[code][1] if 0 <= code < len(self.rows) else "?"


EXIT = _Exit(read_table())


def markdown(rows=EXIT.rows):
    out = ["| code | name | meaning | programs |", "| --- | --- | --- | --- |"]
    out += ["| %d | %s | %s | %s |" % r for r in rows]
    return "\n".join(out)


def short(rows=EXIT.rows):
    return ", ".join("%d %s" % (r[0], r[1]) for r in rows)


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) == 2 else ""
    if what == "markdown":
        print(markdown())
    elif what == "short":
        print(short())
    elif what == "list":
        print("\n".join("%d %s" % (r[0], r[1]) for r in EXIT.rows))
    elif what in ("-h", "--help"):
        print(__doc__.strip())
    else:
        sys.stderr.write("tdc_exit.py: usage: tdc_exit.py markdown|short|list: try 'tdc_exit.py --help'\n")
        sys.exit(EXIT.ARGS)
