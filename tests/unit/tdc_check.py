"""tdc_check - the pass/fail counting of the Python tests in tests/unit:
check(cond, what) prints "ok   what" or "FAIL what"; done(name) prints the
summary line and exits 1 when anything failed (0 checks is a failure too)."""
import sys

_passed = 0
_failed = []


def check(cond, what):
    global _passed
    if cond:
        _passed += 1
        print("ok   " + what)
    else:
        _failed.append(what)
        print("FAIL " + what)


def done(name):
    print("%s: %d passed, %d failed" % (name, _passed, len(_failed)))
    sys.exit(1 if _failed or not _passed else 0)
