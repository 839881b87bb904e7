#!/usr/bin/env python3
"""Paired comparison of `ours` against each baseline in tdc-zeng CSVs
(sim/zeng/zeng_main.c), per metric, with tdc_stats' 95 % intervals (paired
t over the seeds): what sim/zeng/README.md quotes for set-ups outside the
zeng-reliable group (e.g. --clamp-on filtered, --rough).

Usage: sim/zeng/judge_csv.py FILE.csv [FILE.csv ...]"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "experiments"))
import tdc_stats  # noqa: E402

COLUMNS = (("rmse", False), ("ssim", True), ("rmse_region", False), ("ssim_region", True), ("jod", True),
           ("jod_region", True))  # the JODs only in a run with --jod


def main(paths):
    if not paths:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 1
    for path in paths:
        try:
            rows = [r for r in csv.DictReader(open(path)) if r.get("method") and r["scene"] != "cost"]
        except OSError as e:
            print("judge_csv: %s: cannot read: %s" % (path, e.strerror), file=sys.stderr)
            return 7
        by = {}
        for r in rows:
            by.setdefault(r["method"], {})[int(r["seed"])] = r
        if "ours" not in by:
            print("judge_csv: %s: no 'ours' rows" % path, file=sys.stderr)
            return 1
        seeds = sorted(by["ours"])
        print("%s (%s, seeds %s)" % (path, rows[0]["scene"], " ".join(map(str, seeds))))
        for base in (m for m in by if m != "ours"):
            for col, hib in COLUMNS:
                if col not in by["ours"][seeds[0]]:
                    continue
                a = [float(by["ours"][s][col]) for s in seeds]
                b = [float(by[base][s][col]) for s in seeds]
                c = tdc_stats.compare(a, b, higher_is_better=hib)
                ma, mb = sum(a) / len(a), sum(b) / len(b)
                print("  ours vs %-10s %-11s %.4f vs %.4f (%+.1f %%): %s, ours' gain 95 %% CI [%.4f, %.4f]" % (
                    base, col, ma, mb, 100.0 * (ma - mb) / mb, c["verdict"].replace("A", "ours").replace("B", base),
                    c["lo"], c["hi"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
