"""TRM Fig. 11: threshold r per refresh rate (trend) from the refresh x r sweep."""
SWEEP = "refresh"
RATES = [90, 100, 120, 144, 165]
FLIP_TOL = 0.05  # stated tolerance: TRM's FLIP (mean over instants) may exceed full rate's by this much


def excess(exp, rows, col, scene, rate, r):
    """Per seed: TRM r's col minus full rate's (same job)."""
    return [t - f for t, f in paired(rows, col, scene, rate, r)]


def paired(rows, col, scene, rate, r):
    """Per seed: (TRM r's col, full rate's col) of the same job."""
    out = []
    for job in sorted({x["job"] for x in rows if x["scene"] == scene and x["refresh"] == str(rate) and x["r"] == str(r)},
                      key=int):
        f = [x for x in rows if x["job"] == job and x["mode"] == "full"]
        t = [x for x in rows if x["job"] == job and x["mode"] == "trm%d" % r]
        if f and t and f[0][col] != "" and t[0][col] != "":
            out.append((float(t[0][col]), float(f[0][col])))
    return out


def claims(exp):
    s = exp.stats
    rows = exp.rows(SWEEP)
    seeds = sorted({int(x["seed"]) for x in rows})
    rs = sorted({int(x["r"]) for x in rows})  # the demo scale runs a subset
    scenes = [sc for sc in ("pan", "discs") if any(x["scene"] == sc for x in rows)]
    has_terr = any(x["legacy_terr"] != "" for x in rows)
    th_table = ["| scene | " + " | ".join("%d Hz" % h for h in RATES) + " |", "| --- |" + " ---: |" * len(RATES)]
    ex_table = ["| scene | r | " + " | ".join("%d Hz" % h for h in RATES) + " |", "| --- | --- |" + " ---: |" * len(RATES)]
    for sc in scenes:
        ex = {(h, r): excess(exp, rows, "flip", sc, h, r) for h in RATES for r in rs}
        for r in rs:
            ex_table.append("| %s | %.2f | %s |" % (sc, r / 100, " | ".join(s.fmt_ms(s.summary(ex[(h, r)]), 3) for h in RATES)))
        # threshold per seed: the smallest r from which every larger r of the set stays within FLIP_TOL
        per_rate = {}
        for h in RATES:
            th = []
            for i in range(len(seeds)):
                best = 1.0
                for r in sorted(rs, reverse=True):
                    v = ex[(h, r)]
                    if i < len(v) and v[i] <= FLIP_TOL:
                        best = r / 100
                    else:
                        break
                th.append(best)
            per_rate[h] = th
        th_table.append("| %s | %s |" % (sc, " | ".join(s.fmt_ms(s.summary(per_rate[h]), 2) for h in RATES)))
    fig11(exp)
    exp.write_extra(
        "On the HTC Vive's OLED at 90-165 Hz (not the paper's set-up; the claims are judged on fig11.sweep, the "
        "pg279q LCD at 56 px/deg). Threshold r per refresh rate: the smallest r of {%s} from which every larger r keeps FLIP within %.2f of full "
        "rate's (per seed; mean ± spread; 1.00 = none):\n\n%s\n\nTRM's FLIP minus full rate's per r and rate (mean ± spread "
        "over the seeds). The excess is nearly flat in r: D's Gaussian has sigma 2.5 full-res px at every r (TRM §4.3), "
        "so above r = 0.4 the reduced frame carries the same band and r only moves the upsampling error.\n\n%s\n" %
        (", ".join("%.2f" % (r / 100) for r in rs), FLIP_TOL, "\n".join(th_table), "\n".join(ex_table)))


Q_04 = ("§5 (Experiment 1): 'Overall, the experiment showed that a reduction factor of 0.4 or less produces animation "
        "that is indistinguishable from rendering frames at the full-resolution.'")
Q_HZ = ("§5 (Experiment 1): 'For all animations, except Sports hall, the resolution of odd-numbered frames can be "
        "further reduced for higher refresh-rate displays.'")
WHY_EYE = ("the paper's 'indistinguishable' is below its observers' 75 %% discrimination threshold (QUEST), about "
           "1 JOD; %s's margin asks for a far smaller difference, so a difference under that threshold can exceed it")
# "Indistinguishable" is the paper's own criterion: below the reduction at which observers noticed the
# difference with 75 % probability (§5: 'the threshold reduction factor at which the observers could notice
# the difference between TRM and standard rendering with 75% probability'), and the paper itself equates
# that with 1 JOD (§8: 'A difference of 1 JOD means that 75% of the population can spot a difference').  So
# the equivalence margin of these rows is 1 JOD, not the 0.1 JOD of a claim without a stated criterion.
THRESHOLD_JOD = 1.0
WHY_04 = ("the difference exceeds the paper's own threshold (75 % of observers notice it = 1 JOD, §5 and §8): "
          "the visual model sees TRM r = 0.4 on this content at this rate as distinguishable")


def fig11(exp):
    """Fig. 11 in the paper's set-up (fig11.sweep): per scene and rate, never pooled."""
    try:
        rows = exp.rows("fig11")
    except Exception:  # noqa: BLE001 - a cached run from before the sweep existed
        return
    rates = sorted({int(x["refresh"]) for x in rows})
    rs = sorted({int(x["r"]) for x in rows})
    # terr (the temporal CSF) runs on the OLED path only; on the LCD the temporal measure is flicker
    cols = ("flip", "legacy_terr") if any(x["legacy_terr"] != "" for x in rows) else ("flip", "legacy_flicker")
    has_jod = exp.has_jod(rows)
    prim = "jod" if has_jod else cols[0]
    sec = [c for c in ("flip",) + cols if c != prim]
    sec = sorted(set(sec), key=sec.index)
    digits = {"jod": 3, "flip": 4, "legacy_flicker": 2, "legacy_terr": 2}
    for sc in sorted({x["scene"] for x in rows}):
        # judged in JOD (the paper's threshold is what observers see), FLIP and the temporal measure beside it
        if 40 in rs:
            for h in rates:
                eq = {"scene": sc, "refresh": h, "r": 40}
                exp.judge_seen("TRM §5 Fig. 11", Q_04, "%s, %d Hz: TRM r = 0.4 equal to full rate" % (sc, h),
                               "indistinguishable", rows, dict(eq, mode="trm40"), dict(eq, mode="full"), "equal",
                               "trm40", "full", secondary=[(c, digits[c]) for c in ("flip",) + cols[1:]],
                               run="%s/fig11 scene=%s refresh=%d (pg279q, 56 px/deg; 100 Hz not characterised; margin "
                                   "1 JOD = the paper's 75 %% threshold)" % (exp.group, sc, h),
                               cls="model limit", why=WHY_04 if prim == "jod" else WHY_EYE % prim,
                               jod_margin=THRESHOLD_JOD)
        lo, hi = min(rates), max(rates)
        r = 50 if 50 in rs else max(rs)
        if lo != hi:
            exp.judge("TRM §5 Fig. 11", Q_HZ, "%s: TRM r = %.2f closer to full at %d Hz than at %d Hz (%s of TRM - "
                      "full)" % (sc, r / 100, hi, lo, prim), "threshold r falls with the rate",
                      excess(exp, rows, prim, sc, hi, r), excess(exp, rows, prim, sc, lo, r), "better", prim,
                      "%d Hz" % hi, "%d Hz" % lo, digits[prim],
                      secondary=[(c, excess(exp, rows, c, sc, hi, r), excess(exp, rows, c, sc, lo, r), digits[c])
                                 for c in sec],
                      run="%s/fig11 scene=%s r=%.2f (pg279q, 56 px/deg)" % (exp.group, sc, r / 100),
                      cls="model limit",
                      why="the eye model fuses 2 frames at every rate, so the faster alternation gets no extra "
                          "masking; " + WHY_EYE % prim)
