"""TDRT Figs. 5-6: reflected motion vectors at mirror hits vs primary ones."""


Q_MIR = ("TDRT §3.1.2 / Fig. 6: 'For mirrors, we compute the reflected motion vector ... it does improve the "
         "reprojection results significantly in many cases' ; Fig. 6: 'the reflection is considerably better with "
         "reflected motion vectors.'")


def claims(exp):
    on, off = exp.rows("reflected"), exp.rows("primary")
    lines = ["| mode | MVs | FLIP | PSNR dB | flicker |", "| --- | --- | ---: | ---: | ---: |"]
    for mode, paper in (("taa", "TDRT Fig. 6 (TAA [Kar14])"), ("asm-adaptive", "TDRT §3.1.2 (any reprojection)")):
        # what an observer sees: JOD decides, FLIP and PSNR beside it (FLIP decides in a run without --jod)
        cols = [("jod", 3), ("flip", 4), ("psnr_db", 2)]
        if not exp.has_jod(on + off):
            cols = cols[1:]
        (col, d), sec = cols[0], cols[1:]
        exp.judge(paper, Q_MIR, "mirror scene, %s: reflected MVs better than primary MVs" % mode,
                  "reflection considerably better", exp.values(on, col, mode=mode), exp.values(off, col, mode=mode),
                  "better", col, "reflected", "primary", d,
                  secondary=[(c, exp.values(on, c, mode=mode), exp.values(off, c, mode=mode), dd) for c, dd in sec],
                  run="%s/reflected vs primary (whole frame; the mirror floor is about half)" % exp.group)
    for mode in ("full", "taa", "asm-adaptive"):
        for name, rows in (("reflected", on), ("primary", off)):
            cells = [exp.stats.fmt_ms(exp.stats.summary(exp.values(rows, col, mode=mode)), d)
                     for col, d in (("flip", 4), ("psnr_db", 2), ("legacy_flicker", 2))]
            lines.append("| %s | %s | %s |" % (mode, name, " | ".join(cells)))
    exp.write_extra("Mean ± spread over the %d stretches of the animation:\n\n" % len(exp.values(on, "flip", mode="full"))
                    + "\n".join(lines) + "\n")
