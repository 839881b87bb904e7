"""Zeng §7: cost of each motion-vector pass per frame beside the primary rays (tdc-render stage timers)."""
import os
import re
import subprocess

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = ("fence", "discs", "room", "mirror", "panorama")
WINDOWS = (1, 61, 121)  # first frame of each stretch of 4 timed frames
SIZES = {"headset": "1080x1200", "dev": "540x600", "demo": "160x90"}
PASSES = (("mv", "primary MVs (Zeng eq. 1)"), ("mv-reflect", "reflected MVs (TDRT §3.1.2)"),
          ("mv-shadow", "shadow MVs (Zeng §4.1)"), ("mv-dual", "dual MVs (Zeng §4.3)"))
NEGLIGIBLE = 0.25  # of the primary pass


def render_binary():
    return os.environ.get("TDC_RENDER") or os.path.join(REPO, "build", "gcc-O2", "tdc-render")


def run_frames(exp, scene, a, b, size):
    """Per-stage CPU ms summed over frames a..b-1 of scene (cached)."""
    d = os.path.join(exp.out, exp.group)
    os.makedirs(d, exist_ok=True)
    path = os.path.join(d, "render-%s-%d-%d-%s.txt" % (scene, a, b, size))
    if not os.path.isfile(path):
        cmd = [render_binary(), "--builtin", scene, "--frames", "%d:%d" % (a, b), "--size", size,
               "--threads", "1", "--shadow-mv", "--dual-mv", "--quiet"]
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
        with open(path + ".tmp", "w", encoding="utf-8") as fh:
            fh.write(" ".join(cmd) + "\n" + out)
        os.replace(path + ".tmp", path)
    text = open(path, encoding="utf-8").read()
    ms = {}
    cam = re.search(r"\(camera (\d)", text)
    ms["camera_moves"] = int(cam.group(1)) if cam else 0
    for name, val, rest in re.findall(r"^[ \t]*([a-z-]+)[ \t]+([0-9.]+) ms[ \t]*(skipped)?", text, re.M):
        ms[name] = None if rest else float(val)
    return ms


def stages(exp, scene, f, size):
    """Per-stage CPU ms per frame over frames f..f+3 (4 frames: the stage timers are per-thread clocks that
    a loaded host inflates by preemption; sums over frames average it out)."""
    ms = run_frames(exp, scene, f, f + 4, size)
    return {k: (v if k == "camera_moves" or v is None else v / 4.0) for k, v in ms.items()}


def claims(exp):
    size = SIZES.get(exp.scale, SIZES["headset"])
    rows = []
    for sc in SCENES:
        for f in WINDOWS:
            rows.append((sc, f, stages(exp, sc, f, size)))
    st = exp.stats
    lines = ["| scene | frame | primary ms | shade ms | " + " | ".join(p for p, _ in PASSES) + " |",
             "| --- | ---: | ---: | ---: |" + " ---: |" * len(PASSES)]
    for sc, f, ms in rows:
        cells = [("%.1f (%.2f×)" % (ms[p], ms[p] / ms["primary"]) if ms["primary"] > 0 else "%.1f" % ms[p])
                 if ms.get(p) is not None else "skipped" for p, _ in PASSES]
        lines.append("| %s | %d | %.1f | %.1f | %s |" % (sc, f, ms["primary"], ms["shade"], " | ".join(cells)))
    run = "%s (tdc-render %s, frames %s of %s)" % (exp.group, size, "/".join(map(str, WINDOWS)), " ".join(SCENES))
    groups = []
    for p, label in PASSES:
        if p == "mv-dual":  # the renderer culls dual MVs under a still camera (docs/renderer.md): two claims
            groups.append((p, label + ", still camera", lambda ms: not ms["camera_moves"]))
            groups.append((p, label + ", moving camera", lambda ms: ms["camera_moves"]))
        else:
            groups.append((p, label, lambda ms: True))
    for p, label, want in groups:
        sel = [(sc, f, ms) for sc, f, ms in rows if want(ms)]
        ratios = [ms[p] / ms["primary"] for _, _, ms in sel if ms.get(p) is not None and ms["primary"] > 0]
        if not ratios:
            continue
        s = st.summary(ratios)
        if s["n"] < st.MIN_SEEDS:
            verdict = "inconclusive"
        else:
            verdict = "agree" if s["mean"] + s["spread"] <= NEGLIGIBLE else (
                "disagree" if s["mean"] - s["spread"] > NEGLIGIBLE else "inconclusive")
        why = "CPU ms of the pass / CPU ms of the primary rays, same frame; ran in %d of %d frames (%s)" % (
            len(ratios), len(sel), " ".join(sorted({sc for sc, _, _ in sel})))
        if p == "mv-dual" and verdict != "agree":
            why += ("; the dual pass traces a previous-frame ray per candidate pixel (Zeng reads the previous "
                    "G-buffer instead: a texture fetch on the GPU, a full ray on this CPU renderer); under a still "
                    "camera only pixels near the moving objects' previous screen rectangles get one")
        if p == "mv-shadow" and verdict != "agree":
            why += "; blocker-returning shadow rays (rtcIntersect1) plus one previous-frame ray per shadowed pixel"
        exp.claim("Zeng §7", "%s: cost per frame vs the primary rays" % label, "negligible (< 0.23 ms at 1080p, GPU)",
                  "%s× primary" % st.fmt_ms(s, 3), verdict, why, spread=st.fmt(s["spread"], 3), n=s["n"], run=run)
    exp.write_extra("CPU ms per frame, one thread, %s (ratio to the primary pass):\n\n" % size + "\n".join(lines) + "\n")
