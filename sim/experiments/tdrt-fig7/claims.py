"""TDRT §3.2.1 / Fig. 7: the variance-sampling neighbourhood of the clamp (the paper's box against the two
it rejects), per speed, paired over the photographs."""

SWEEP = "fig7"
HZ = 240.0
PAPER = "asm-ref"
ALTS = (("asm-ref-all", "all 8 immediate neighbours (old pixels included)"),
        ("asm-ref-sub3x3", "a 3x3 area of the most recent subframe"))
SECONDARY = (("flip", 4), ("legacy_flicker", 2))
Q_FIG7 = ("§3.2.1: 'One can, for example, use all immediate neighbors in the variance sampling, which means that "
          "old pixel information would be used. Another possibility would be to do variance sampling with samples "
          "from a 3×3 area in the most recent subframe, but this also reduces the quality of the final frame.'")


def claims(exp):
    rows = exp.rows(SWEEP)
    for sp in sorted({r["speed"] for r in rows}, key=float):
        for alt, what in ALTS:
            exp.judge_seen("TDRT §3.2.1 Fig. 7", Q_FIG7,
                           "horizontal pan, %.3f px/frame: the paper's box (newest immediate neighbours) better than "
                           "%s" % (float(sp) / HZ, what), "the paper's choice best", rows,
                           {"mode": PAPER, "speed": sp}, {"mode": alt, "speed": sp}, "better", "newest neighbours",
                           alt[8:], secondary=SECONDARY,
                           run="%s/%s speed=%s (%d photographs)" % (exp.group, SWEEP, sp,
                                                                    len(exp.select(rows, mode=PAPER, speed=sp))))
