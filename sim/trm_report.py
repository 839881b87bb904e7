#!/usr/bin/python3
"""TRM demo report: runs of tdc-run on built-in contents -> report/trm/index.md
with pictures (input, full-res drive frame, reduced drive frame, perceived
pair, error heat map) and a table of perceived error.

Usage: sim/trm_report.py REPORT_DIR RUN_DIR... (each RUN_DIR from
`tdc-run --save-input --perceived --frames auto`, named after its content).
Perceived = Talbot-Plateau mean of two consecutive drive frames in linear
light (panel gamma) on the retina of an eye that pursues the content's known
motion; ideal = the same mean of the two input frames."""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

GAMMA = np.array([2.2912, 2.2520, 2.1940])  # htc-vive, TRM paper 4.4
# Known motion of the built-in contents in pixels/frame (x, y): the eye
# pursues it (smooth pursuit, TRM paper 3), so the earlier frame of a pair
# lands on the retina shifted by this much.
VELOCITY = {"edge": (3, 0), "text": (0, -2), "gradient": (-1, 0), "checker": (0, 0),
            "primaries": (0, 0), "black": (0, 0), "white": (0, 0)}
BORDER = 8  # pixels left out at the frame edge (content enters there)


def pursue(img, v):
    """Frame t-1 as the pursuing eye sees it at time t."""
    return np.roll(img, shift=(v[1], v[0]), axis=(0, 1))


def load(path):
    img = mpimg.imread(path)[..., :3]
    return np.round(img * 255.0).astype(np.float64)


def lin(code):
    return (code / 255.0) ** GAMMA


def enc(light):
    return np.round(255.0 * np.clip(light, 0, 1) ** (1.0 / GAMMA))


def main():
    out, runs = sys.argv[1], sys.argv[2:]
    os.makedirs(out, exist_ok=True)
    rows = []
    md = ["# TRM on built-in contents", "",
          "Produced by `make demo` (target `demo-trm`): `tdc-run --frames auto --save-input --perceived "
          "--builtin CONTENT` (r = 1/2, s = 10, sigma = 2.5 px, panel htc-vive) and `sim/trm_report.py`.",
          "Full-res frames alternate with reduced frames made by the firmware's own prefilter D.",
          "Perceived = mean of two consecutive drive frames in linear light (Talbot-Plateau, TRM paper eq. 3)",
          "on the retina of an eye pursuing the content's known motion (edge 3 px/frame, text 2 px/frame,",
          "gradient 1 px/frame, checker static); ideal = the same for the input frames. An 8-pixel border is",
          "left out (new content enters there). Error figures are in 8-bit codes over every pair of the run.", ""]
    for run in runs:
        name = os.path.basename(run.rstrip("/"))
        frames = sorted(f for f in os.listdir(run) if f.startswith("perceived_"))
        if not frames:
            continue
        errs, within = [], []
        v = VELOCITY.get(name, (0, 0))
        b = BORDER
        for f in frames:
            k = int(f[10:15])
            drv = [load(os.path.join(run, "drive_%05d.png" % j)) for j in (k - 1, k)]
            inp = [load(os.path.join(run, "input_%05d.png" % j)) for j in (k - 1, k)]
            perc = enc((lin(pursue(drv[0], v)) + lin(drv[1])) / 2)[b:-b, b:-b]
            ideal = enc((lin(pursue(inp[0], v)) + lin(inp[1])) / 2)[b:-b, b:-b]
            d = np.abs(perc - ideal)
            errs.append(d.max())
            within.append((d <= 1).mean())
            mse = np.mean((lin(perc) - lin(ideal)) ** 2)
        psnr = 10 * np.log10(1.0 / mse) if mse > 0 else float("inf")
        rows.append((name, max(errs), 100 * min(within), psnr))
        # picture strip for the pair (2, 3)
        k = 3 if len(frames) >= 3 else int(frames[-1][10:15])
        pics = [("input t=%d" % (k - 1), load(os.path.join(run, "input_%05d.png" % (k - 1)))),
                ("drive t=%d (full, beta)" % (k - 1), load(os.path.join(run, "drive_%05d.png" % (k - 1)))),
                ("drive t=%d (reduced, alpha')" % k, load(os.path.join(run, "drive_%05d.png" % k))),
                ("perceived pair (pursuit)", enc((lin(pursue(load(os.path.join(run, "drive_%05d.png" % (k - 1))), v))
                                                  + lin(load(os.path.join(run, "drive_%05d.png" % k)))) / 2))]
        ideal = enc((lin(pursue(pics[0][1], v)) + lin(load(os.path.join(run, "input_%05d.png" % k)))) / 2)
        fig, ax = plt.subplots(1, 5, figsize=(17, 3.4))
        for a, (title, img) in zip(ax, pics):
            a.imshow(img.astype(np.uint8), interpolation="nearest")
            a.set_title(title, fontsize=9)
            a.axis("off")
        im = ax[4].imshow(np.abs(pics[3][1] - ideal).max(axis=2), cmap="magma", vmin=0, vmax=8,
                          interpolation="nearest")
        ax[4].set_title("|perceived - ideal| (codes)", fontsize=9)
        ax[4].axis("off")
        fig.colorbar(im, ax=ax[4], fraction=0.046)
        fig.suptitle("TRM: %s" % name)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "%s.png" % name), dpi=80)
        plt.close(fig)
        md.append("## %s\n\n![%s](%s.png)\n" % (name, name, name))
    md[9:9] = ["| content | max perceived error (codes) | within 1 code (worst pair) | PSNR of perceived light (dB) |",
               "| --- | --- | --- | --- |"] + \
        ["| %s | %.0f | %.2f %% | %.1f |" % r for r in rows] + [""]
    with open(os.path.join(out, "index.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("wrote %s/index.md (%d contents)" % (out, len(rows)))


if __name__ == "__main__":
    main()
