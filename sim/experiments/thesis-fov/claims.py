"""Foveated-upscaling thesis ch. 5: Tables 5.1-5.3, §5.3, eq. 5.1 / Fig. 5.2 (and what cannot be run)."""

THESIS_X = "0.12443"
Q51 = ("Thesis §5.1.3 / Tables 5.1, 5.3: weighted median FLIP, baseline foveated mode 0.187-0.272, TAA mode "
       "0.200-0.304 - 'we see almost no difference' from DLSS mode, so the TAA mode's per-frame error is above the "
       "baseline's on every view")
Q53 = ("Thesis §5.3: 'We then further show in the video for the TAA mode that TAA mode reduces the temporal artifacts "
       "greatly.'")
Q52 = ("Thesis §5.2: 'In this case we see that the minimum render time was achieved at a foveation threshold set to "
       "12.443% of the distance to the furthest corner from the foveal point. ... the observed render times and the "
       "estimation derived above follow a similar pattern'")
Q54 = ("Thesis §5.2 / Table 5.4: 'the render time ratio between foveated mode and DLSS mode 5.193/9.158 = 0.567'; "
       "Table 5.2: DLSS mode's weighted median FLIP")


def per_scene(exp, rows, mode, col, **eq):
    scenes = sorted({r["rscene"] for r in rows})
    out = []
    for sc in scenes:
        v = exp.values(rows, col, mode=mode, rscene=sc, **eq)
        out.append(v[0] if v else float("nan"))
    return out


def claims(exp):
    rows = exp.job_rows("quality", "foveation.csv")  # the foveation metrics (weighted median, periphery)
    run = "%s/quality (renderer scenes as contents)" % exp.group
    exp.judge("thesis Tables 5.1/5.3", Q51, "per-frame weighted-median FLIP: baseline foveated better than TAA mode",
              "TAA mode +0.011 to +0.041", per_scene(exp, rows, "fov", "flip_wmedian"),
              per_scene(exp, rows, "fov-taa", "flip_wmedian"), "better", "flip", "fov", "fov-taa", run=run,
              cls="setting", why="the thesis's TAA mode runs on DLSS's upscaled output (Table 5.3 carries DLSS's loss, "
              "Table 5.2); tdc's fov-taa is TAA on the foveated frame without DLSS, which has no implementation here")
    # §5.3 is what the viewer sees in the periphery: JOD of the periphery decides, its flicker beside it
    q = exp.rows("quality")
    fl = [("legacy_flicker", per_scene(exp, rows, "fov-taa", "legacy_flicker_periphery"),
           per_scene(exp, rows, "fov", "legacy_flicker_periphery"), 2)]
    ok = lambda c: exp.has_jod(q, c)  # noqa: E731
    # the periphery's JOD where the frame has a periphery at the run's density (none at the demo's 96x54:
    # the whole frame is within the fovea's radius, jod_periphery nan), else the whole frame's
    col = "jod_periphery" if ok("jod_periphery") else "jod"
    if ok(col):
        exp.judge("thesis §5.3", Q53, "periphery: TAA mode better than the baseline foveated mode (temporal artifacts)",
                  "reduces the temporal artifacts greatly", per_scene(exp, q, "fov-taa", col),
                  per_scene(exp, q, "fov", col), "better", "jod", "fov-taa", "fov", 3,
                  run=run + ("" if col == "jod_periphery" else "; JOD of the whole frame: no periphery at this size"),
                  secondary=fl, cls="setting",
                  why="the thesis's TAA mode is TAA on DLSS's upscaled output (Tables 5.2-5.3), which has no "
                      "implementation here; tdc's fov-taa is TAA on the foveated frame")
    else:
        exp.judge("thesis §5.3", Q53, "periphery: TAA mode better than the baseline foveated mode (temporal artifacts)",
                  "reduces the temporal artifacts greatly", fl[0][1], fl[0][2], "better", "legacy_flicker", "fov-taa",
                  "fov", 2, run=run, why="no JOD in these results (a run without --jod)")
    # eq. 5.1 / Fig. 5.2: the threshold of the fewest samples, and of the least render time
    d = exp.rows("disk")
    tim = exp.timings("disk")
    disks = sorted({r["disk"] for r in d}, key=float)
    scenes = sorted({r["rscene"] for r in d})
    at = []
    lines = ["| scene | " + " | ".join("x = %s" % x for x in disks) + " |", "| --- |" + " ---: |" * len(disks)]
    for sc in scenes:
        f = {x: exp.values(d, "rays_vs_full", mode="fov", rscene=sc, disk=x) for x in disks}
        best = min(disks, key=lambda x: f[x][0] if f[x] else 9)
        at.append(best)
        t = {x: [float(r["render_us_per_frame"]) for r in tim if r["rscene"] == sc and r["disk"] == x] for x in disks}
        lines.append("| %s | %s |" % (sc, " | ".join("f %.4f, %.0f us" % (f[x][0], t[x][0]) if f[x] and t[x] else ""
                                                     for x in disks)))
    hit = sum(1 for b in at if b == THESIS_X)
    exp.claim("thesis §5.2 eq. 5.1", "the sample-count estimate f(x) is smallest at x = 12.443 %% (grid %s)" %
              " ".join(disks), "minimum at 12.443 %", "minimum at %s" % ", ".join(at),
              "agree" if hit == len(at) and at else "disagree",
              "" if hit == len(at) else "f(x) is the log-polar buffer's size plus the disk's samples at tdc's alpha "
              "and delta; its minimum moves with them", n=len(at), run="%s/disk (per scene; a count, no spread)" %
              exp.group, quote=Q52)
    if THESIS_X in disks:
        for other in (disks[0], disks[-1]):
            if other == THESIS_X:
                continue
            sav = []
            # the contents: (scene, stretch of its animation); older runs have one stretch per scene
            for c in sorted({(r["rscene"], r.get("start", "0")) for r in tim}):
                t_at = lambda x: [float(r["render_us_per_frame"]) for r in tim  # noqa: E731
                                  if (r["rscene"], r.get("start", "0")) == c and r["disk"] == x]
                ts, to = t_at(THESIS_X), t_at(other)
                if ts and to and to[0] > 0:
                    sav.append(100.0 * (1.0 - ts[0] / to[0]))
            exp.judge("thesis §5.2 Fig. 5.2", Q52, "render time at x = 12.443 %% below that at x = %s" % other,
                      "minimum at 12.443 %", sav, [0.0] * len(sav), "better", "saving_pct", "saving", "0 %", 1,
                      run="%s/disk (renderer scenes x stretches as %d contents)" % (exp.group, len(sav)))
    exp.claim("thesis Tables 5.2, 5.4", "DLSS mode: per-frame FLIP and render time (5.193 / 9.158 ms = 0.567)",
              "0.567", "-", "inconclusive", "DLSS is NVIDIA's proprietary upscaler (NGX SDK, RTX GPU): no "
              "implementation in Debian or here, none can be written from the thesis", run="(not run)", quote=Q54,
              cls="not reproducible")
    exp.write_extra("Foveation threshold x (share of the distance to the farthest corner): f(x) = rays traced / a "
                    "full frame's (eq. 5.1) and renderer time per frame:\n\n" + "\n".join(lines) + "\n")
