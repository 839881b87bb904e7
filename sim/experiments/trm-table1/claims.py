"""TRM Table 1: flicker ranking and savings of every technique."""
SWEEP = "table1"
MODES = ["full", "half", "interlace", "bfi", "ncsfi", "trm50", "trm25", "asw"]
PAPER = {"asw": ("none", "varies; 50% max."), "half": ("none", "50%"), "interlace": ("moderate", "50%"),
         "bfi": ("severe", "50%"), "ncsfi": ("mild", "50%"), "trm50": ("mild", "37-49% (37.5% at r=1/2)"),
         "trm25": ("mild", "37-49% (46.9% at r=1/4)")}
SAVING = {"half": 0.5, "interlace": 0.5, "bfi": 0.5, "ncsfi": 0.5, "trm50": 0.375, "trm25": 1 - (1 + 1 / 16) / 2}


Q_T1 = ("TRM Table 1: 'Comparison of alternative techniques' - Flicker column: Half frame rate none, Interlace "
        "moderate, BFI severe, NCSFI mild, TRM mild; performance saving: 50 % / 37-49 % (TRM)")


Q16 = ("TRM §8 / Fig. 16: 'the participants could not observe much difference between our method and the original "
       "90 Hz rendering. The NCSFI method improved slightly over the repeated frames (45 Hz) but was much worse than TRM "
       "or full-resolution rendering (90 Hz).' ... 'ASW was seen to perform best in the football scene'")
Q72 = ("TRM §7.2: 'Such alternating binocular presentation will not result in higher visibility of motion artifacts "
       "than the corresponding monocular presentation.'")
Q_BLUR = ("TRM Table 1, Motion Blur column: 'Half frame rate ... strong'; Reprojection, Interlace, BFI, NCSFI, TRM: "
          "'reduced'")


def claims(exp):
    rows = exp.rows(SWEEP)
    s = exp.stats
    fl = {m: exp.values(rows, "legacy_flicker", mode=m) for m in MODES}  # the table
    te = {m: exp.values(rows, "legacy_terr", mode=m) for m in MODES}
    table = ["| mode | paper flicker | flicker | terr | rays saved | link saved | paper saving |",
             "| --- | --- | ---: | ---: | ---: | ---: | --- |"]
    for m in MODES:
        rays = s.summary(exp.values(rows, "rays_vs_full", mode=m))
        link = s.summary(exp.values(rows, "link_vs_full", mode=m))
        table.append("| %s | %s | %s | %s | %.1f %% | %.1f %% | %s |" % (
            m, PAPER.get(m, ("-", "-"))[0], s.fmt_ms(s.summary(fl[m]), 2), s.fmt_ms(s.summary(te[m]), 2),
            100 * (1 - rays["mean"]), 100 * (1 - link["mean"]), PAPER.get(m, ("-", "-"))[1]))
        if m in SAVING:
            got = 1 - rays["mean"]
            ok = abs(got - SAVING[m]) < 0.01
            exp.claim("TRM Table 1", "%s: performance saving (rays)" % m, PAPER[m][1], "%.1f %%" % (100 * got),
                      "agree" if ok else "disagree", "" if ok else "rays saved differ from the table's by > 1 point",
                      spread=s.fmt(rays["spread"], 4), n=rays["n"], run="%s/%s mode=%s" % (exp.group, SWEEP, m),
                      quote=Q_T1)
    # flicker ranking of the table: severe (BFI) > moderate (interlace) > mild (NCSFI, TRM) > none (half).  The
    # column is luminance flicker, judged on static content (flicker.sweep: no judder, blur or ghosting to mix
    # in); runs from before that sweep judge it on the pan, where the motion artifacts dominate the JOD.
    try:
        frows, frun, fmov = exp.rows("flicker"), "%s/flicker (static content)" % exp.group, False
    except Exception:  # noqa: BLE001 - a cached run from before the sweep
        frows, frun, fmov = rows, "%s/%s (pan, pursuit)" % (exp.group, SWEEP), True
    WHY = {("bfi", "interlace"): "under exact pursuit a BFI pair and an interlaced field pair fuse to the same "
                                 "half-bright image, so every per-instant and temporal figure is equal; the severity "
                                 "of BFI is its 45 Hz full-field modulation, which the 2-frame fusion integrates away",
           ("trm50", "half"): "half rate's 'none' is luminance flicker; on moving content half rate's judder (the "
                              "same frame at two retinal positions) is the largest change on the retina",
           ("interlace", "ncsfi"): "NCSFI's residual, always added, ghosts at this speed (5 px/frame): its error "
                                   "changes frame to frame more than the interlaced fields'"}
    LUM = "interlace and BFI also halve the peak luminance (Table 1's first column), which JOD counts too"
    # Judged in JOD (what an observer sees; the visual model of docs/visual-model.md), the error measures beside
    # it.  "A flickers more than B" is read as: B is seen closer to the reference than A.
    has_jod = exp.has_jod(rows)
    run = "%s/%s" % (exp.group, SWEEP)
    # (the legacy flicker is 0 on static content: it measures the change of the error along the pursuit)
    fsec = (("legacy_flicker", 2), ("legacy_terr", 2)) if fmov else (("flip", 4),)
    for a, b, what in (("bfi", "interlace", "severe > moderate"), ("interlace", "trm50", "moderate > mild"),
                       ("interlace", "ncsfi", "moderate > mild"), ("trm50", "half", "mild > none")):
        exp.judge_seen("TRM Table 1", Q_T1, "flicker: %s more than %s (%s seen better)" % (a, b, b), what, frows,
                       {"mode": b}, {"mode": a}, "better", b, a, secondary=fsec, run=frun,
                       cls="model limit" if fmov else "",
                       why=WHY.get((a, b), "tdc's flicker and terr measure the change of the error on the retina, "
                                           "not luminance flicker") if fmov else "",
                       note=LUM if not fmov and "interlace" in (a, b) and "bfi" not in (a, b) else "")
    # the Motion Blur column: half frame rate "strong", every other technique "reduced" (judged under pursuit,
    # where hold-type blur is what the tracked pan shows)
    for m in ("interlace", "bfi", "ncsfi", "trm50", "asw"):
        exp.judge_seen("TRM Table 1", Q_BLUR, "motion blur: %s less than half frame rate (pursuit)" % m,
                       "reduced < strong", rows, {"mode": m}, {"mode": "half"}, "better", m, "half",
                       secondary=(("flip", 4),), run=run, cls="model limit",
                       why="BFI's black frame and interlace's missing field are error at every instant; the blur the "
                           "column means is what the eye fuses over the pair",
                       note=exp.saccade_note(SWEEP))
    exp.judge_seen("TRM Table 1", Q_T1, "flicker: TRM equal to NCSFI (both mild)", "mild = mild", frows,
                   {"mode": "trm50"}, {"mode": "ncsfi"}, "equal", "trm50", "ncsfi",
                   secondary=fsec, run=frun, cls="model limit" if fmov else "",
                   why="NCSFI's residual, always added, ghosts at this speed: its error changes more" if fmov else "")
    # Fig. 16 (Experiments 2 and 3, JOD from pairwise comparisons in VR): TRM ~ 90 Hz, NCSFI and 45 Hz below,
    # ASW ~ TRM on the football scene; judged under pursuit on the pan (the football scene's followed motion)
    for a, b, kind, what in (("trm50", "full", "equal", "TRM ≈ 90 Hz"), ("trm50", "ncsfi", "better", "TRM > NCSFI"),
                             ("trm50", "half", "better", "TRM > 45 Hz"), ("ncsfi", "half", "better", "NCSFI > 45 Hz"),
                             ("asw", "trm50", "equal", "ASW ≈ TRM (football)")):
        exp.judge_seen("TRM Fig. 16", Q16, "%s %s %s" % (a, {"equal": "equal to", "better": "better than"}[kind], b),
                       what, rows, {"mode": a}, {"mode": b}, kind, a, b, secondary=(("flip", 4), ("legacy_terr", 2)),
                       run="%s/%s (pursuit)" % (exp.group, SWEEP), cls="model limit",
                       why="the paper's JOD comes from observers' pairwise preference in VR on its own scenes; "
                           "tdc's is the visual model's on a textured pan",
                       note=exp.saccade_note(SWEEP))
    # §7.2 binocular: the alternating-eye presentation not worse than the monocular one (per eye: the mean of
    # the two eyes' figures against the monocular TRM eye)
    try:
        st = exp.rows("stereo")
    except Exception:  # noqa: BLE001 - a cached run from before the sweep
        st = []
    if st:
        def per_eye(col):
            return [(float(r[col + "_eye0"]) + float(r[col + "_eye1"])) / 2 for r in
                    sorted(exp.select(st, mode="trm50"), key=lambda r: int(r["seed"]))]
        sec = [("flip", per_eye("flip"), exp.values(rows, "flip", mode="trm50"), 4)]
        sjod = exp.has_jod(st, "jod_eye0") and has_jod
        prim = ("jod", per_eye("jod"), exp.values(rows, "jod", mode="trm50"), 3) if sjod else sec.pop(0)
        exp.judge("TRM §7.2", Q72, "binocular (eyes alternate full/reduced) not worse than monocular TRM (per eye)",
                  "not more visible", prim[1], prim[2], "not worse", prim[0], "binocular", "monocular", prim[3],
                  secondary=sec + [(c, exp.values(st, c, mode="trm50"), exp.values(rows, c, mode="trm50"), 2)
                                   for c in ("legacy_terr", "legacy_flicker")],
                  run="%s/stereo vs %s" % (exp.group, SWEEP))
    exp.write_extra("Every technique of Table 1 (mean ± spread over the seeds; savings against full rate):\n\n"
                    + "\n".join(table) + "\n")
