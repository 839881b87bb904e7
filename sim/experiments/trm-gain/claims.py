"""TRM under imperfect smooth pursuit (gain 0.8-1)."""
SWEEP = "gain"
GAINS = ["0.8", "0.9", "0.95", "1"]
Q_GAZE = ("tdc (beyond the paper; firmware/tdc_trm_gaze.h): gaze-aware TRM is never worse than reduced-only under "
          "fixation and equal to TRM under pursuit")
Q_SPEM = ("TRM §3: 'the eye tends to lag behind an object, moving approximately 5-20% slower [8]'; §4.1: 'the gaze "
          "follows an object or scene motion ... thus fixing the image on the retina'")


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
        # gaze-aware TRM (the ★ claim): under pursuit - every gain here - equal to plain TRM within the
        # margin, and never worse than reduced-only frames
        # judged in JOD (what an observer sees), FLIP and the temporally filtered error beside it
        sec = (("flip", 4), ("legacy_terr", 2))
        run = "%s/%s gain=%s" % (exp.group, SWEEP, g)
        note = exp.saccade_note(SWEEP, gain=float(g))  # "" in this sweep's views (the set-up check)
        exp.judge_seen("tdc ★ (beyond the paper)", Q_GAZE, "gain %s: gaze-aware TRM equal to TRM" % g, "equal", rows,
                       {"mode": "trm50g", "gain": g}, {"mode": "trm50", "gain": g}, "equal", "trm50g", "trm50",
                       secondary=sec, run=run, note=note)
        exp.judge_seen("tdc ★ (beyond the paper)", Q_GAZE, "gain %s: gaze-aware TRM not worse than reduced-only" % g,
                       "never worse", rows, {"mode": "trm50g", "gain": g}, {"mode": "reduced50", "gain": g},
                       "not worse", "trm50g", "reduced50", secondary=sec, run=run, note=note)
        if g != "1":
            exp.judge_seen("TRM §3/§4.1", Q_SPEM, "gain %s (SPEM lag %d %%): TRM better than reduced-only" % (
                g, round(100 * (1 - float(g)))), "TRM works under real SPEM", rows, {"mode": "trm50", "gain": g},
                {"mode": "reduced50", "gain": g}, "better", "trm50", "reduced50", secondary=sec, run=run, note=note)
    exp.write_extra("Mean ± spread over the seeds:\n\n" + "\n".join(table) + "\n")
