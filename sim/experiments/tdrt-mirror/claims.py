"""TDRT Figs. 5-6: reflected motion vectors at mirror hits vs primary ones."""


def claims(exp):
    on, off = exp.rows("reflected"), exp.rows("primary")
    lines = ["| mode | MVs | FLIP | PSNR dB | flicker |", "| --- | --- | ---: | ---: | ---: |"]
    for mode, paper in (("taa", "TDRT Fig. 6 (TAA [Kar14])"), ("asm-adaptive", "TDRT §3.1.2 (any reprojection)")):
        for col, label, hib, d in (("flip", "FLIP", False, 4), ("psnr_db", "PSNR dB", True, 2)):
            a, b = exp.values(on, col, mode=mode), exp.values(off, col, mode=mode)
            c = exp.stats.compare(a, b, higher_is_better=hib)
            got = c["verdict"]
            verdict = "agree" if got == "A beats B" else ("disagree" if got == "B beats A" else "inconclusive")
            exp.claim(paper, "mirror scene, %s: reflected MVs beat primary MVs (%s)" % (mode, label),
                      "reflection considerably better",
                      "%s reflected %s vs primary %s" % (label, exp.stats.fmt_ms(exp.stats.summary(a), d),
                                                         exp.stats.fmt_ms(exp.stats.summary(b), d)),
                      verdict, "%s (difference %s, spread of the paired differences %s; whole frame, the mirror "
                      "floor is about half of it)" % (got.replace("A", "reflected").replace("B", "primary"),
                                                      exp.stats.fmt(c["diff"], d), exp.stats.fmt(c["spread"], d)),
                      spread=exp.stats.fmt(c["spread"], d), n=c["n"], run="%s/reflected vs primary" % exp.group)
    for mode in ("full", "taa", "asm-adaptive"):
        for name, rows in (("reflected", on), ("primary", off)):
            cells = [exp.stats.fmt_ms(exp.stats.summary(exp.values(rows, col, mode=mode)), d)
                     for col, d in (("flip", 4), ("psnr_db", 2), ("legacy_flicker", 2))]
            lines.append("| %s | %s | %s |" % (mode, name, " | ".join(cells)))
    exp.write_extra("Mean ± spread over the 5 stretches of the animation:\n\n" + "\n".join(lines) + "\n")
