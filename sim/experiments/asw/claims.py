"""ASW with the renderer's exact motion vectors vs motion estimated from the decoded frames."""

SWEEP = "asw"


def pair(exp, rows, a, b, col, hib, label, d, paper, claim, paper_value, expect="A beats B"):
    va, vb = exp.values(rows, col, mode=a), exp.values(rows, col, mode=b)
    c = exp.stats.compare(va, vb, higher_is_better=hib)
    got = c["verdict"]
    verdict = "agree" if got == expect else ("inconclusive" if got in ("tie", "too few seeds") else "disagree")
    exp.claim(paper, claim, paper_value,
              "%s %s: %s vs %s" % (label, a, exp.stats.fmt_ms(exp.stats.summary(va), d),
                                   exp.stats.fmt_ms(exp.stats.summary(vb), d)), verdict,
              "%s (difference %s, spread of the paired differences %s)" % (
                  got.replace("A", a).replace("B", b), exp.stats.fmt(c["diff"], d), exp.stats.fmt(c["spread"], d)),
              spread=exp.stats.fmt(c["spread"], d), n=c["n"], run="%s/%s" % (exp.group, SWEEP))


def claims(exp):
    rows = exp.rows(SWEEP)
    for col, hib, label, d in (("flip", False, "FLIP", 4), ("psnr_db", True, "PSNR dB", 2)):
        pair(exp, rows, "asw", "asw-est", col, hib, label, d, "issue 15 (ASW)",
             "exact renderer MVs beat block-matched motion (%s)" % label, "exact-vector ASW is optimistic")
        pair(exp, rows, "asw-est", "half", col, hib, label, d, "ASW (compositor practice)",
             "estimated-motion ASW beats repeating the frame (%s)" % label, "extrapolation helps")
        pair(exp, rows, "full", "asw-est", col, hib, label, d, "ASW (compositor practice)",
             "full rate beats estimated-motion ASW (%s)" % label, "full rate best")
    lines = ["| speed px/s | mode | FLIP | PSNR dB | flicker |", "| ---: | --- | ---: | ---: | ---: |"]
    for sp in sorted({r["speed"] for r in rows}, key=float):
        for m in ("full", "half", "asw", "asw-est"):
            cells = [exp.stats.fmt_ms(exp.stats.summary(exp.values(rows, c, mode=m, speed=sp)), d)
                     for c, d in (("flip", 4), ("psnr_db", 2), ("legacy_flicker", 2))]
            lines.append("| %s | %s | %s |" % (sp, m, " | ".join(cells)))
    exp.write_extra("Mean ± spread over the 5 photographs:\n\n" + "\n".join(lines) + "\n")
