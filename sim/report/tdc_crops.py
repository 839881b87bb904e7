#!/usr/bin/python3
"""tdc_crops.py RUNDIR [--crop N] [--thumb W] [--pick-diff A,B] [--keep-strips]

Picture strips of a large tdc-sim run as a report can show them: 1:1 crops
where the artefacts are, plus downscaled full frames.

tdc-sim writes RUNDIR/strip_<mode>.png = drive codes | perceived | perceived
ground truth | FLIP map (heat colours) over the evaluated interior, 4 px
white gaps, each panel magnified s x (s = 4/3/2/1 for widths < 80/160/320/
above).  For every run this picks ONE window of N x N panel pixels (default
192), the same for every mode so the modes compare side by side: the window
with the largest FLIP error summed over the modes other than `full` (the
artefacts the reduced modes add), or over all modes when `full` is the only
one; with --pick-diff A,B the window where the perceived frames of modes A
and B differ most (summed absolute difference: e.g. the shadow or the
reflection region, where two kinds of motion vectors part).  It writes
    RUNDIR/crops.png     one row per mode: ground truth | perceived | FLIP, 1:1
    RUNDIR/frames.png    full perceived frames downscaled to W px (default 480)
                         per mode, the crop window outlined in the first
    RUNDIR/crops.json    the window and the modes, for the report
and, unless --keep-strips, deletes the full-size strips (at 1920x1080 each is
several MB).

Foveated runs (RUNDIR/strip_gaze.json, written by tdc-sim at the strip's
instant: the true gaze and the foveal disk radius in panel pixels): two
windows per mode, the fovea (centred on the gaze) and the periphery (the
largest FLIP outside the disk), ground truth | perceived | FLIP each; the
downscaled frames show the gaze (cross) and the disk (circle)."""
import json
import os
import sys

import numpy as np
from PIL import Image, ImageDraw


def panels(path):
    a = np.asarray(Image.open(path).convert("RGB"))
    h, W = a.shape[:2]
    pw = (W - 12) // 4
    return [a[:, k * (pw + 4):k * (pw + 4) + pw] for k in range(4)]


def heat_to_error(p):
    # inverse of tdc_report.c heat(): r = min(1, 3e), g = clamp(3e - 1), b = clamp(3e - 2)
    return p.astype(np.float64).sum(axis=2) / (3.0 * 255.0)


def best_window(err, n):
    h, w = err.shape
    n = min(n, h, w)
    s = np.zeros((h + 1, w + 1))
    s[1:, 1:] = err.cumsum(0).cumsum(1)
    win = s[n:, n:] - s[:-n, n:] - s[n:, :-n] + s[:-n, :-n]
    y, x = np.unravel_index(np.argmax(win), win.shape)
    return int(x), int(y), n


def downscale(img, width):
    h, w = img.shape[:2]
    if w <= width:
        return Image.fromarray(img)
    return Image.fromarray(img).resize((width, max(1, round(h * width / w))), Image.BOX)


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    run = argv[1]
    crop = int(argv[argv.index("--crop") + 1]) if "--crop" in argv else 192
    thumb = int(argv[argv.index("--thumb") + 1]) if "--thumb" in argv else 480
    strips = sorted(f for f in os.listdir(run) if f.startswith("strip_") and f.endswith(".png"))
    if not strips:
        print("tdc_crops: %s: no strip_*.png" % run, file=sys.stderr)
        return 1
    modes = [f[6:-4] for f in strips]
    order = []  # the run's own mode order (summary.csv), then any others
    if os.path.isfile(os.path.join(run, "summary.csv")):
        import csv
        with open(os.path.join(run, "summary.csv"), newline="") as f:
            order = [r["mode"] for r in csv.DictReader(f)]
    modes = [m for m in order if m in modes] + [m for m in modes if m not in order]
    P = {m: panels(os.path.join(run, "strip_%s.png" % m)) for m in modes}
    others = [m for m in modes if m != "full"] or modes
    err = sum(heat_to_error(P[m][3]) for m in others)
    picked_by = "max FLIP summed over " + ",".join(others)
    if "--pick-diff" in argv:
        pa, pb = argv[argv.index("--pick-diff") + 1].split(",")
        if pa not in P or pb not in P:
            print("tdc_crops: %s: --pick-diff %s,%s: no such strips" % (run, pa, pb), file=sys.stderr)
            return 1
        err = np.abs(P[pa][1].astype(np.float64) - P[pb][1].astype(np.float64)).sum(axis=2)
        picked_by = "largest difference between the perceived frames of %s and %s" % (pa, pb)
    gz = None
    gzp = os.path.join(run, "strip_gaze.json")
    if os.path.isfile(gzp) and "--pick-diff" not in argv:  # a region of interest instead of the gaze
        gz = json.load(open(gzp))
        sc0 = P[modes[0]][1].shape[1] / max(1, gz["width"])  # panel magnification
        gx, gy, gr = gz["x"] * sc0, gz["y"] * sc0, gz["r"] * sc0
        yy, xx = np.mgrid[0:err.shape[0], 0:err.shape[1]]
        err = np.where((xx + 0.5 - gx) ** 2 + (yy + 0.5 - gy) ** 2 > gr * gr, err, 0.0)
    x, y, n = best_window(err, crop)
    wins = [(x, y)]
    titles = ("ground truth", "perceived", "FLIP error")
    if gz:
        fx = int(min(max(gx - n / 2, 0), err.shape[1] - n))
        fy = int(min(max(gy - n / 2, 0), err.shape[0] - n))
        wins = [(fx, fy), (x, y)]
        titles = ("fovea: ground truth", "perceived", "FLIP", "periphery: ground truth", "perceived", "FLIP")
    gap, lab = 4, 110
    ncol = 3 * len(wins)
    wd = lab + ncol * n + (ncol - 1) * gap + (len(wins) - 1) * 3 * gap
    rows = []
    for m in modes:
        row = np.full((n, wd, 3), 255, np.uint8)
        for w_i, (wx, wy) in enumerate(wins):
            for k, src in enumerate((2, 1, 3)):
                c = w_i * 3 + k
                x0 = lab + c * (n + gap) + w_i * 3 * gap
                row[:, x0:x0 + n] = P[m][src][wy:wy + n, wx:wx + n]
        rows.append(row)
    head = 14
    grid = np.full((head + len(rows) * (n + gap) - gap, wd, 3), 255, np.uint8)
    for i, r in enumerate(rows):
        grid[head + i * (n + gap):head + i * (n + gap) + n] = r
    im = Image.fromarray(grid)
    d = ImageDraw.Draw(im)
    for k, t in enumerate(titles):
        d.text((lab + k * (n + gap) + (k // 3) * 3 * gap + 2, 1), t, fill=(0, 0, 0))
    for i, m in enumerate(modes):
        d.text((2, head + i * (n + gap) + n // 2 - 6), m, fill=(0, 0, 0))
    im.save(os.path.join(run, "crops.png"), optimize=True)
    h, w = P[modes[0]][1].shape[:2]
    thumbs = []
    sc = min(1.0, thumb / w)
    first = downscale(P[modes[0]][2], thumb)
    d = ImageDraw.Draw(first)
    for wx, wy in wins:
        d.rectangle([wx * sc, wy * sc, (wx + n) * sc, (wy + n) * sc], outline=(255, 0, 0), width=2)
    thumbs.append(first)
    thumbs += [downscale(P[m][1], thumb) for m in modes]
    if gz:
        for t in thumbs:  # the gaze and the foveal disk
            d = ImageDraw.Draw(t)
            cx, cy, rr = gx * sc, gy * sc, gr * sc
            d.ellipse([cx - rr, cy - rr, cx + rr, cy + rr], outline=(0, 255, 255), width=1)
            d.line([cx - 5, cy, cx + 5, cy], fill=(0, 255, 255), width=1)
            d.line([cx, cy - 5, cx, cy + 5], fill=(0, 255, 255), width=1)
    tw, th = thumbs[0].size
    cols = 3
    nr = (len(thumbs) + cols - 1) // cols
    sheet = Image.new("RGB", (cols * tw + (cols - 1) * gap, nr * th + (nr - 1) * gap), (255, 255, 255))
    for i, t in enumerate(thumbs):
        sheet.paste(t, ((i % cols) * (tw + gap), (i // cols) * (th + gap)))
    sheet.save(os.path.join(run, "frames.png"), optimize=True)
    with open(os.path.join(run, "crops.json"), "w") as f:
        j = {"x": x, "y": y, "n": n, "width": int(w), "height": int(h), "thumb_scale": sc,
             "modes": modes, "picked_by": picked_by}
        if gz:
            j["fovea"] = {"x": wins[0][0], "y": wins[0][1], "gaze": [gx, gy], "r": gr}
        json.dump(j, f)
    if "--keep-strips" not in argv:
        for s in strips:
            os.remove(os.path.join(run, s))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
