"""TRM under imperfect smooth pursuit (gain 0.8-1)."""
SWEEP = "gain"
GAINS = ["0.8", "0.9", "0.95", "1"]
GAZE_TOL_FLIP, GAZE_TOL_TERR = 0.005, 0.25  # as trm-fixation


def claims(exp):
    rows = exp.rows(SWEEP)
    table = ["| gain | full FLIP | reduced50 FLIP | trm50 FLIP | trm50g FLIP | trm50 terr | reduced50 terr | trm50g terr |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for g in GAINS:
        v = {m: exp.values(rows, "flip", mode=m, gain=g) for m in ("full", "reduced50", "trm50", "trm50g")}
        t = {m: exp.values(rows, "legacy_terr", mode=m, gain=g) for m in ("reduced50", "trm50", "trm50g")}
        table.append("| %s | %s | %s |" % (g, " | ".join(exp.stats.fmt_ms(exp.stats.summary(v[m]), 4)
                                                         for m in ("full", "reduced50", "trm50", "trm50g")),
                                           " | ".join(exp.stats.fmt_ms(exp.stats.summary(t[m]), 2)
                                                      for m in ("trm50", "reduced50", "trm50g"))))
        # gaze-aware TRM (issue 15): under pursuit - every gain here - within the stated tolerance of
        # plain TRM, and never worse than reduced-only frames beyond the spread
        for col, vals, tol in (("FLIP", v, GAZE_TOL_FLIP), ("terr", t, GAZE_TOL_TERR)):
            c = exp.stats.compare(vals["trm50g"], vals["trm50"], higher_is_better=False)
            ok = c["diff"] <= tol
            exp.claim("tdc (beyond the paper)", "gain %s: gaze-aware TRM within %s of TRM (%s)" % (g, tol, col),
                      "within %s" % tol, "%s trm50g - trm50 %s" % (col, exp.stats.fmt(c["diff"], 4)),
                      "agree" if ok else "disagree",
                      c["verdict"].replace("A", "trm50g").replace("B", "trm50") + (
                          "" if c["diff"] <= c["spread"] else ": the eye's slip (%.2f px/frame) is inside the ramp, "
                          "so k < 1 there" % ((1 - float(g)) * 4.25)),
                      spread=exp.stats.fmt(c["spread"], 4), n=c["n"], run="%s/%s gain=%s" % (exp.group, SWEEP, g))
            c = exp.stats.compare(vals["trm50g"], vals["reduced50"], higher_is_better=False)
            exp.claim("tdc (beyond the paper)", "gain %s: gaze-aware TRM not worse than reduced-only (%s)" % (g, col),
                      "never worse", "%s trm50g - reduced50 %s" % (col, exp.stats.fmt(c["diff"], 4)),
                      "agree" if c["verdict"] != "B beats A" else "disagree",
                      c["verdict"].replace("A", "trm50g").replace("B", "reduced50"),
                      spread=exp.stats.fmt(c["spread"], 4), n=c["n"], run="%s/%s gain=%s" % (exp.group, SWEEP, g))
        if g == "1":
            continue
        for col, vals in (("FLIP", v), ("terr", t)):
            c = exp.stats.compare(vals["trm50"], vals["reduced50"], higher_is_better=False)
            ok = c["verdict"] == "A beats B"
            exp.claim("TRM §3/§4.1", "gain %s (SPEM lag %d %%): TRM beats reduced-only (%s)" % (g, round(100 * (1 - float(g))), col),
                      "TRM works under real SPEM", "%s trm50 - reduced50 %s" % (col, exp.stats.fmt(c["diff"], 4)),
                      "agree" if ok else ("inconclusive" if c["verdict"] == "tie" else "disagree"),
                      c["verdict"].replace("A", "trm50").replace("B", "reduced50") + ("" if ok else ": the lag moves TRM's "
                      "sharpening off the reduced frame on the retina"),
                      spread=exp.stats.fmt(c["spread"], 4), n=c["n"], run="%s/%s gain=%s" % (exp.group, SWEEP, g))
    exp.write_extra("Mean ± spread over the seeds:\n\n" + "\n".join(table) + "\n")
