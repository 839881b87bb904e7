#!/usr/bin/python3
"""Mean and spread over seeds of tdc-sim summary.csv files (docs/layers.md).

Usage: layers_seeds.py DIR...   (each DIR holds one run's summary.csv)
Prints a markdown table: per mode PSNR, RMSE (8-bit code values, from the
mean PSNR: 255 * 10^(-PSNR/20)), SSIM and FLIP as mean +- sample standard
deviation over the runs, and the paired difference to the mode named
first (mean +- std of the per-seed differences): a mode beats another only
when the difference exceeds its spread.
"""
import csv
import math
import sys


def load(d):
    with open(f"{d}/summary.csv") as f:
        return {r["mode"]: r for r in csv.DictReader(f) if r["available"] == "1"}


def ms(xs):
    m = sum(xs) / len(xs)
    s = math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1)) if len(xs) > 1 else 0.0
    return m, s


def main():
    runs = [load(d) for d in sys.argv[1:]]
    if not runs:
        print("layers_seeds.py: no runs", file=sys.stderr)
        return 1
    modes = [m for m in runs[0] if all(m in r for r in runs)]
    base = "asm-adaptive-smv" if "asm-adaptive-smv" in modes else modes[0]
    print(f"{len(runs)} seeds; differences are paired per seed against {base}\n")
    print("| mode | PSNR dB | RMSE (codes) | SSIM | FLIP | ΔPSNR vs " + base + " | ΔFLIP vs " + base + " |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for m in modes:
        p = [float(r[m]["psnr_db"]) for r in runs]
        s = [float(r[m]["ssim"]) for r in runs]
        fl = [float(r[m]["flip"]) for r in runs]
        dp = [float(r[m]["psnr_db"]) - float(r[base]["psnr_db"]) for r in runs]
        df = [float(r[m]["flip"]) - float(r[base]["flip"]) for r in runs]
        pm, ps = ms(p)
        sm, ss = ms(s)
        fm, fs = ms(fl)
        dpm, dps = ms(dp)
        dfm, dfs = ms(df)
        rmse = 255.0 * 10 ** (-pm / 20.0)
        print(f"| {m} | {pm:.2f} ± {ps:.2f} | {rmse:.2f} | {sm:.4f} ± {ss:.4f} | {fm:.4f} ± {fs:.4f} | "
              f"{dpm:+.2f} ± {dps:.2f} | {dfm:+.4f} ± {dfs:.4f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
