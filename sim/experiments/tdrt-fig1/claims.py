"""TDRT §2 / Fig. 1: jittered 1-spp frames fused by the eye, per refresh rate (contents: 5 edge angles)."""
SWEEP = "fig1"
Q_F1 = ("TDRT §2 / Fig. 1: 'Four images, each rendered with one sample per pixel (SPP) from the standard 4× MSAA "
        "pattern, are shown after each other in succession. The higher the display rate, the more we see the combined, "
        "antialiased effect of all four images.'")


def claims(exp):
    """The sentence says what is seen at the highest rate and how it grows with the rate; it says nothing of
    60 Hz against one centred sample, so no row tests that (the table of the group shows those cells).
    Judged in JOD (what an observer sees), FLIP and PSNR beside it."""
    rows = exp.rows(SWEEP)
    rates = sorted({r["refresh"] for r in rows}, key=int)
    hi = rates[-1]
    exp.judge_seen("TDRT Fig. 1", Q_F1, "%s Hz: 4 jittered 1-spp frames better than one centred sample" % hi,
                   "antialiased", rows, {"mode": "jitter1", "refresh": hi}, {"mode": "full", "refresh": hi}, "better",
                   "jitter1", "1 spp", run="%s/%s refresh=%s" % (exp.group, SWEEP, hi))
    for lo in rates[:-1]:
        exp.judge_seen("TDRT Fig. 1", Q_F1, "jittered frames closer to antialiased at %s Hz than at %s Hz" % (hi, lo),
                       "the higher the rate, the more antialiased", rows, {"mode": "jitter1", "refresh": hi},
                       {"mode": "jitter1", "refresh": lo}, "better", "%s Hz" % hi, "%s Hz" % lo,
                       run="%s/%s" % (exp.group, SWEEP))
    s = exp.stats
    lines = ["| Hz | mode | JOD | FLIP | PSNR dB |", "| ---: | --- | ---: | ---: | ---: |"]
    for hz in rates:
        for m in ("full", "jitter1"):
            lines.append("| %s | %s | %s |" % (hz, m, " | ".join(
                s.fmt_ms(s.summary(exp.values(rows, c, mode=m, refresh=hz)), d) if all(
                    r.get(c, "") not in ("", "nan") for r in exp.select(rows, mode=m, refresh=hz)) else "-"
                for c, d in (("jod", 3), ("flip", 4), ("psnr_db", 2)))))
    exp.write_extra("Mean ± spread over the 5 edges (every rate and mode):\n\n" + "\n".join(lines) + "\n")
