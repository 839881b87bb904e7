#!/usr/bin/python3
"""Run the reference FovVideoVDP (github.com/gfxdisp/FovVideoVDP, PyTorch,
CC BY-NC: read and run beside the project, never part of it) on the frames
`tdc-fvvdp-validate dump DIR` wrote, and print one CSV row per condition:

    condition,reference_jod,seconds

Usage (Debian's python3-torch, CPU):
    /usr/bin/python3 sim/metrics/validation/fvvdp_reference.py REF_CHECKOUT DIR > out.csv

REF_CHECKOUT is a checkout of the reference (its pyfvvdp/ is imported from
there).  Not run by `make test`: the stored output is
sim/metrics/validation/fvvdp_reference.csv.
"""
import csv
import math
import os
import sys
import time

if len(sys.argv) != 3:
    sys.exit("fvvdp_reference.py: usage: fvvdp_reference.py REF_CHECKOUT FRAMES_DIR")
ref_dir, frames_dir = sys.argv[1], sys.argv[2]
sys.path.insert(0, ref_dir)
sys.path.insert(0, os.path.join(ref_dir, "pyfvvdp"))

import types  # noqa: E402

# pyfvvdp/__init__ imports its file readers (imageio.v2, ffmpeg-python),
# which Debian 12 lacks (imageio 2.4) and which arrays in memory never use:
# stand-ins so the import succeeds.
for _mod in ("imageio.v2", "ffmpeg"):
    try:
        __import__(_mod)
    except ImportError:
        sys.modules[_mod] = types.ModuleType(_mod)

import numpy as np  # noqa: E402
import torch  # noqa: E402
import pyfvvdp  # noqa: E402
from pyfvvdp.fvvdp_display_model import fvvdp_display_photo_absolute, fvvdp_display_geometry  # noqa: E402

torch.set_num_threads(int(os.environ.get("FVVDP_THREADS", "2")))
print(f"# reference: {ref_dir} (pyfvvdp {getattr(pyfvvdp, '__version__', '?')}), torch {torch.__version__}, "
      f"{torch.get_num_threads()} CPU threads", flush=True)
print("condition,reference_jod,seconds")
with open(os.path.join(frames_dir, "manifest.csv")) as mf:
    for row in csv.DictReader(mf):
        w, h, n = int(row["width"]), int(row["height"]), int(row["frames"])
        fps = float(row["fps"])
        width_m, dist = float(row["width_m"]), float(row["distance_m"])
        fov_h = 2.0 * math.degrees(math.atan(width_m / (2.0 * dist)))
        geom = fvvdp_display_geometry((w, h), distance_m=dist, fov_horizontal=fov_h)
        gx, gy = float(row["gaze_x"]), float(row["gaze_y"])
        foveated = not math.isnan(gx)
        data = np.fromfile(os.path.join(frames_dir, row["name"] + ".f32"), dtype=np.float32).reshape(2, n, h, w)
        test, ref = torch.tensor(data[0]), torch.tensor(data[1])
        metric = pyfvvdp.fvvdp(display_name="standard_4k", display_photometry=fvvdp_display_photo_absolute(),
                               display_geometry=geom, foveated=foveated, heatmap=None, quiet=True,
                               device=torch.device("cpu"))
        fix = torch.tensor([gx, gy]) if foveated else None
        t0 = time.perf_counter()
        with torch.no_grad():
            if n == 1:
                q, _ = metric.predict(test[0], ref[0], dim_order="HW", fixation_point=fix)
            else:
                q, _ = metric.predict(test, ref, dim_order="FHW", frames_per_second=fps, fixation_point=fix)
        dt = time.perf_counter() - t0
        print(f"{row['name']},{float(q):.6f},{dt:.4f}", flush=True)
