"""ASW with the renderer's exact motion vectors vs motion estimated from the decoded frames."""

SWEEP = "asw"


Q_ASW = ("TRM Table 1 (ASW row): 'Reprojection (ASW, Didyk et al. [10]) ... reduced [motion blur] ... reprojection "
         "artifacts ... varies; 50% max.'; tdc's own design claims (exact vs block-matched vectors)")


def pair(exp, rows, a, b, col, label, d, paper, claim, paper_value, speed):
    exp.judge(paper, Q_ASW, "%s px/s: %s" % (speed, claim), paper_value,
              exp.values(rows, col, mode=a, speed=speed), exp.values(rows, col, mode=b, speed=speed), "better", col,
              a, b, d, run="%s/%s speed=%s" % (exp.group, SWEEP, speed))


def claims(exp):
    rows = exp.rows(SWEEP)
    for sp in sorted({r["speed"] for r in rows}, key=float):  # per speed, never pooled
        for col, label, d in (("flip", "FLIP", 4), ("psnr_db", "PSNR dB", 2)):
            pair(exp, rows, "asw", "asw-est", col, label, d, "issue 15 (ASW)",
                 "exact renderer MVs better than block-matched motion (%s)" % label, "exact-vector ASW is optimistic", sp)
            pair(exp, rows, "asw-est", "half", col, label, d, "TRM Table 1 (ASW)",
                 "estimated-motion ASW better than repeating the frame (%s)" % label, "extrapolation helps", sp)
            pair(exp, rows, "full", "asw-est", col, label, d, "TRM Table 1 (ASW)",
                 "full rate better than estimated-motion ASW (%s)" % label, "reprojection artifacts", sp)
    lines = ["| speed px/s | mode | FLIP | PSNR dB | flicker |", "| ---: | --- | ---: | ---: | ---: |"]
    for sp in sorted({r["speed"] for r in rows}, key=float):
        for m in ("full", "half", "asw", "asw-est"):
            cells = [exp.stats.fmt_ms(exp.stats.summary(exp.values(rows, c, mode=m, speed=sp)), d)
                     for c, d in (("flip", 4), ("psnr_db", 2), ("legacy_flicker", 2))]
            lines.append("| %s | %s | %s |" % (sp, m, " | ".join(cells)))
    exp.write_extra("Mean ± spread over the 5 photographs:\n\n" + "\n".join(lines) + "\n")
