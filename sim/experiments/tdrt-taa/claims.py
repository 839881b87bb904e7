"""TDRT §4: assembly at 240 Hz vs rendering + TAA: cost per frame and cost at equal perceived error."""

SWEEP = "taa"
SWEEP_US = "userstudy"
TAA = (("taa60", 60.0), ("taa80", 80.0), ("taa120", 120.0), ("taa", 240.0))
ASM = "asm-adaptive"
PAPER_RATIO = 3.5
TOL = 0.25  # the equal-error analysis below (not a paper claim): within 25 % of the ratio
ABOUT = 0.10  # "about 3.5x": 10 % below it still reads "about"
Q35 = ("§4: 'The rationale for this is that our method renders a frame about 3.5× faster than vanilla rendering "
       "with TAA.'")
Q_US = ("§4 (user study): 'we randomly placed a rendering with 1 SPP at 60 FPS on either the left or right side, and our "
        "technique at 240 FPS, on the other side ... When asked to identify the rendering that best resembled the "
        "ground truth, 94% selected our technique'")
Q_Q = ("§1: 'Our results include an increase in performance by a factor of approximately 3.5× with increased "
       "quality, compared to TAA'")


def per_frame_us(t):
    return float(t["render_us_per_frame"]) + float(t["fw_us_per_frame"])


def equal_error_rate(flip_asm, taa_flips):
    """TAA rate at which its FLIP equals flip_asm, linear in rate between the measured rates;
    None with a direction when outside them."""
    pts = sorted(taa_flips)  # (rate, flip)
    if flip_asm <= min(f for _, f in pts) and flip_asm < pts[-1][1]:
        return None, ">"  # better than TAA at every measured rate
    for (r0, f0), (r1, f1) in zip(pts, pts[1:]):
        if (f0 - flip_asm) * (f1 - flip_asm) <= 0 and f0 != f1:
            return r0 + (r1 - r0) * (f0 - flip_asm) / (f0 - f1), ""
    return None, "<" if flip_asm > pts[0][1] else ">"


def claims(exp):
    rows, tim = exp.rows(SWEEP), exp.timings(SWEEP)
    scenes = sorted({r["rscene"] for r in rows})
    # the contents: (scene, stretch of its animation); a run without the start axis has one stretch
    contents = sorted({(r["rscene"], r.get("start", "0")) for r in rows}, key=lambda c: (c[0], int(c[1])))
    sel_c = lambda c, **eq: exp.select(rows, rscene=c[0], **({"start": c[1]} if "start" in rows[0] else {}), **eq)  # noqa: E731
    tkey = lambda t: (t["job"], t["mode"])
    tmap = {tkey(t): t for t in tim}
    ratio_t, ratio_r, eq_rate, eq_rays, eq_time, notes = [], [], [], [], [], []
    lines = ["| scene | start frame | mode | Hz | FLIP | PSNR dB | rays/s (M) | renderer + filter us/frame |",
             "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: |"]
    for c in contents:
        sc = "%s@%s" % c
        sel = {r["mode"]: r for r in sel_c(c)}
        if ASM not in sel or "taa" not in sel:
            continue
        a, t240 = sel[ASM], sel["taa"]
        ta, tt = tmap[tkey(a)], tmap[tkey(t240)]
        ratio_t.append(per_frame_us(tt) / per_frame_us(ta))
        ratio_r.append(float(t240["rays_per_s"]) / float(a["rays_per_s"]))
        pts = [(hz, float(sel[m]["flip"])) for m, hz in TAA if m in sel]
        r, side = equal_error_rate(float(a["flip"]), pts)
        if r is None:
            notes.append("%s: assembly %s TAA at every measured rate" % (sc, "better than" if side == ">" else "worse than"))
        else:
            eq_rate.append(r)
            eq_rays.append(r * (float(t240["rays_per_s"]) / 240.0) / float(a["rays_per_s"]))
            # TAA's cost per frame at 240 Hz stands for its cost per frame at the lower rate
            eq_time.append(r * per_frame_us(tt) / (240.0 * per_frame_us(ta)))
        for m in ("full", "full60") + tuple(x for x, _ in TAA) + (ASM,):
            if m in sel:
                s = sel[m]
                lines.append("| %s | %s | %s | %s | %.4f | %.2f | %.2f | %.0f |" % (
                    c[0], c[1], m, s["display_hz"], float(s["flip"]), float(s["psnr_db"]), float(s["rays_per_s"]) / 1e6,
                    per_frame_us(tmap[tkey(s)])))
    st = exp.stats
    run = "%s/%s (%s; %d contents: scenes x stretches)" % (exp.group, SWEEP, " ".join(scenes), len(contents))
    if ratio_t:
        # "about 3.5x" per frame: the ratio is at least 3.5 x (1 - 10 %) ("about"), within the ratio's 5 % margin
        exp.judge("TDRT §4", Q35, "a frame of assembly vs a frame of rendering + TAA: time ratio, about 3.5×",
                  "≈ 3.5× per frame", ratio_t, [PAPER_RATIO * (1 - ABOUT)] * len(ratio_t), "not worse", "ratio",
                  "assembly", "%.2f×" % (PAPER_RATIO * (1 - ABOUT)), 2, run=run, cls="setting",
                  why="renderer + filter CPU time per frame at 240 Hz, same resolution; on this CPU renderer the "
                      "firmware assembly (the filter) and the fixed per-frame costs do not shrink with the rays")
    def per_scene(mode, col="flip"):
        out = []
        for c in contents:
            v = [float(r[col]) for r in sel_c(c, mode=mode)]
            out.append(v[0] if v else float("nan"))
        return out

    # what an observer sees: JOD decides (the paper's quality is the fused 240 Hz sequence), FLIP beside it
    has_jod = exp.has_jod(rows)
    prim, d = ("jod", 3) if has_jod else ("flip", 4)
    sec = [("flip", per_scene(ASM), per_scene("taa60"), 4)] if has_jod else []
    j = exp.judge("TDRT §1/§4", Q_Q, "assembly at 240 Hz better than rendering + TAA at 60 Hz (quality)",
                  "increased quality", per_scene(ASM, prim), per_scene("taa60", prim), "better", prim,
                  "assembly 240 Hz", "TAA 60 Hz", d, run=run, secondary=sec)
    if j["verdict"] not in ("agree", "equivalent") and exp.scale == "demo" and has_jod:
        behind = [(c, a - t) for c, a, t in zip(contents, per_scene(ASM, prim), per_scene("taa60", prim)) if a < t]
        exp.class_last("setting", ("demo scale: in %dx%d frames the assembly trails TAA at 60 Hz only on %s (%s JOD), "
                                   "where the "
                       "room's taps and bottle necks are a tenth of a pixel wide and its window light is traced with 2 "
                       "noisy shadow rays; the paper rendered 1920x1080, and at 256x144 (headset scale) the assembly "
                       "no longer trails on the room and this row agrees (docs/experiments.md)" % (
                           int(rows[0]["width"]), int(rows[0]["height"]),
                           ", ".join("%s@%s" % c for c, _ in behind), ", ".join("%+.2f" % g for _, g in behind))))
    if "full60" in {r["mode"] for r in rows}:
        sec = [("flip", per_scene(ASM), per_scene("full60"), 4)] if has_jod else []
        j = exp.judge("TDRT §4 (user study)", Q_US, "renderer scenes: assembly at 240 Hz better than 1 spp at 60 Hz "
                      "(no TAA)", "94 % of 35 subjects chose the assembly", per_scene(ASM, prim),
                      per_scene("full60", prim), "better", prim, "assembly 240 Hz", "1 spp 60 Hz", d, secondary=sec,
                      run=run + " (scenes as contents; the paper: BISTRO only)")
        if j["verdict"] not in ("agree", "equivalent") and has_jod:
            # the study's premise: 1 spp at 60 Hz visibly worse than at 240 Hz on the content
            prem = st.judge(per_scene("full", prim), per_scene("full60", prim), "better", prim)
            behind = [(c, a - f) for c, a, f in zip(contents, per_scene(ASM, prim), per_scene("full60", prim))
                      if a < f - prem["margin"]]
            exp.class_last("setting", ("the study's premise is absent from these scenes: their cameras move a "
                                       "fraction of a "
                           "pixel per refresh, so 1 spp at 240 Hz is only %.2f JOD [%.2f, %.2f] ahead of 1 spp at 60 "
                           "Hz (the difference the study was built to show; on moving detail it is 1-4 JOD, next "
                           "rows), and what is left is the assembly's own cost, beyond the margin on %s (%s JOD): the "
                           "fence's thin slats moving over the shadow they cast on a static floor (the two failure "
                           "cases TDRT §4 names: 'rapidly moving, thin features', 'dynamic shadows cast on static "
                           "objects'), the room's sub-pixel taps and 2-ray window light, the panorama's texture "
                           "resampled bilinearly at sub-pixel motion (3 of every 4 pixels are reprojected each "
                           "refresh)" % (
                               prem["gain"], prem["lo"], prem["hi"], ", ".join("%s@%s" % c for c, _ in behind),
                               ", ".join("%+.2f" % g for _, g in behind))))
    user_study_photos(exp)
    # not a paper claim (the 3.5x is per frame): the cost at equal FLIP, beside the table
    eq = ""
    if eq_rate:
        stt = st.summary(eq_time)
        eq = ("TAA's cost at the assembly's FLIP (rate interpolated between 60/80/120/240 Hz): %s× the assembly's "
              "(%d contents)." % (st.fmt_ms(stt, 2), stt["n"]))
    if notes:
        eq += " " + "; ".join(notes) + "."
    exp.write_extra("Per content (scene and stretch, one run each; the claims pair the contents). %s\n\n" % eq.strip() + "\n".join(lines) + "\n")


def user_study_photos(exp):
    """The user study on moving detail (userstudy.sweep): the tdrt-fig10 photographs panned at 1.5 and 4
    px/frame, one row per speed, paired over the photographs."""
    try:
        rows = exp.rows(SWEEP_US)
    except Exception:  # noqa: BLE001 - a run made before the sweep existed
        return
    for sp in sorted({r["speed"] for r in rows}, key=float):
        n = len(exp.select(rows, mode=ASM, speed=sp))
        j = exp.judge_seen("TDRT §4 (user study)", Q_US, "photographs panned at %.1f px/frame: assembly at 240 Hz better "
                       "than 1 spp at 60 Hz (no TAA)" % (float(sp) / 240.0), "94 % of 35 subjects chose the assembly",
                       rows, {"mode": ASM, "speed": sp}, {"mode": "full60", "speed": sp}, "better", "assembly 240 Hz",
                       "1 spp 60 Hz", secondary=(("flip", 4), ("psnr_db", 2)),
                       run="%s/%s speed=%s (%d photographs)" % (exp.group, SWEEP_US, sp, n))
        if j["verdict"] in ("agree", "equivalent") or not exp.has_jod(rows):
            continue
        # the study's premise per photograph: 1 spp at 60 Hz visibly (by the margin) worse than at 240 Hz
        v = lambda m: exp.values(rows, "jod", mode=m, speed=sp)  # noqa: E731
        key = lambda r: (int(r.get("seed", 0) or 0), int(r.get("job", 0)))  # noqa: E731 (values' order)
        names = [r["image"].rsplit("/", 1)[-1].rsplit(".", 1)[0]
                 for r in sorted(exp.select(rows, mode=ASM, speed=sp), key=key)]
        prem = [(c, a - f60) for c, f, f60, a in zip(names, v("full"), v("full60"), v(ASM)) if f - f60 > j["margin"]]
        flat = [c for c, f, f60 in zip(names, v("full"), v("full60")) if f - f60 <= j["margin"]]
        ahead = sum(1 for _, g in prem if g > 0)
        if flat and 2 * ahead > len(prem):
            exp.class_last("setting", (
                "the study's premise holds on %d of %d photographs (1 spp at 60 Hz worse than at 240 Hz by more than "
                "the margin), and there the assembly is ahead on %d (%s JOD); on the other %d (%s: smooth, 60 Hz "
                "costs nothing) there is no difference for it to win; the study's BISTRO was chosen for its "
                "thin moving detail" % (len(prem), n, ahead, ", ".join("%+.2f" % g for _, g in prem), len(flat),
                                        ", ".join(flat))))
