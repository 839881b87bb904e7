#!/usr/bin/env python3
"""Host layers point one way (docs/design.md §10): each top folder may include
only its own files and the folders below it.

    firmware  <  common  <  ref  <  render  <  sim
                 common  <  ref  <  hosttools
    tests and boards above all of them

An #include "x" is resolved as the compiler would (the including file's own
folder, then the build's -I folders); a header the build generates (no such
file in the tree) is passed over.  A line that reaches up or sideways (sim/
including hosttools/, hosttools/ including sim/, common/ including sim/, ...)
is printed as `file:line: includes path (area A may not include area B)`.

    check_include_dirs.py [ROOT]       exit 1 on any such line
    check_include_dirs.py --selftest   the same on ROOT=., after proving on a
                                       small planted tree that it finds a
                                       reach in each direction and passes a
                                       clean one
"""
import os
import re
import sys
import tempfile

# What each area may include besides itself.
ALLOWED = {
    "firmware": set(),
    "common": {"firmware"},
    "ref": {"common", "firmware"},
    "render": {"ref", "common", "firmware"},
    "sim": {"render", "ref", "common", "firmware"},
    "hosttools": {"ref", "common", "firmware"},
    "boards": {"firmware", "common"},
    "tests": {"firmware", "common", "ref", "render", "sim", "hosttools", "boards"},
}
# Reaches left on purpose, each with its reason.
EXCEPTIONS = {
    # tdc-run's built-in contents are the golden vectors' deterministic
    # frames (one generator; it is test support of ARM images too).
    ("hosttools/tdcrun/tdc_run.c", "tests/golden/tdc_content.h"),
}
# The -I folders of the host builds (Makefile HOST_CFLAGS, mk/*.mk extras).
SEARCH = ["firmware", "common", "sim", "ref", ".", "tests", "tests/golden", "render",
          "sim/link", "hosttools/usb", "hosttools/gpio", "firmware/board"]
INCLUDE = re.compile(r'\s*#\s*include\s+"([^"]+)"')


def area(path):
    top = path.split("/", 1)[0]
    return top if top in ALLOWED else None


def resolve(root, src, name):
    for d in [os.path.dirname(src)] + SEARCH:
        p = os.path.normpath(os.path.join(d, name))
        if os.path.isfile(os.path.join(root, p)):
            return p
    return None


def sources(root):
    for top in sorted(ALLOWED):
        for d, _, files in os.walk(os.path.join(root, top)):
            for f in sorted(files):
                if f.endswith((".c", ".h")):
                    yield os.path.relpath(os.path.join(d, f), root)


def check(root):
    bad = []
    for src in sources(root):
        a = area(src)
        with open(os.path.join(root, src), encoding="utf-8", errors="replace") as fh:
            for n, line in enumerate(fh, 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                dst = resolve(root, src, m.group(1))
                b = area(dst) if dst else None
                if b is None or b == a or b in ALLOWED[a] or (src, dst) in EXCEPTIONS:
                    continue
                bad.append("%s:%d: includes %s (%s may not include %s)" % (src, n, dst, a, b))
    return bad


def selftest():
    with tempfile.TemporaryDirectory() as t:
        def put(path, text):
            os.makedirs(os.path.dirname(os.path.join(t, path)), exist_ok=True)
            with open(os.path.join(t, path), "w") as fh:
                fh.write(text)
        put("firmware/tdc_fixed.h", "")
        put("common/tdc_png.h", '#include "tdc_fixed.h"\n')
        put("sim/lcd/tdc_lcd_ref.h", '#include "tdc_png.h"\n')
        put("hosttools/calib/tdc_calib.c", '#include "tdc_png.h"\n')
        if check(t):
            print("include dirs selftest: FAIL: a clean planted tree was reported:", check(t))
            return False
        put("hosttools/calib/tdc_calib.c", '#include "../../sim/lcd/tdc_lcd_ref.h"\n')
        put("common/tdc_png.h", '#include "lcd/tdc_lcd_ref.h"\n')
        put("firmware/tdc_fixed.h", '#include "tdc_png.h"\n')
        found = check(t)
        want = ["hosttools/calib/tdc_calib.c:1: includes sim/lcd/tdc_lcd_ref.h (hosttools may not include sim)",
                "common/tdc_png.h:1: includes sim/lcd/tdc_lcd_ref.h (common may not include sim)",
                "firmware/tdc_fixed.h:1: includes common/tdc_png.h (firmware may not include common)"]
        if sorted(found) != sorted(want):
            print("include dirs selftest: FAIL: planted reaches not found as expected:\n  " + "\n  ".join(found))
            return False
        print("include dirs selftest: the 3 planted reaches are found")
        return True


def main(argv):
    if argv[1:2] == ["--selftest"]:
        if not selftest():
            return 1
        argv = argv[:1] + argv[2:]
    root = argv[1] if len(argv) > 1 else "."
    bad = check(root)
    for b in bad:
        print(b)
    n = sum(1 for _ in sources(root))
    print("include dirs: %d files, %d includes that reach up or sideways" % (n, len(bad)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
