"""TDRT Fig. 10 / §3.2.3 (eqs. 4-5): tile orderings against motion direction and speed."""

SWEEP = "fig10"
ORDERINGS = ("asm-hourglass", "asm-bowtie", "asm-adaptive")
# metric column, label, digits (lower is better for both)
METRICS = (("flip", "FLIP", 4), ("legacy_flicker", "flicker", 2))
MOTION = {"0": "horizontal", "30": "diagonal (below the random band)", "45": "diagonal (in the random band)",
          "60": "diagonal (above the random band)", "90": "vertical"}
HZ = 240.0


def frac(speed):
    l = float(speed) / HZ
    return l - int(l)


def pooled(exp, rows, mode, col, angle, speeds):
    """Values of col for mode at angle over speeds x contents, in job order (paired across modes)."""
    v = []
    for s in speeds:
        v += exp.values(rows, col, mode=mode, angle=angle, speed=s)
    return v


def verdict_of(c, expect):
    got = c["verdict"]
    if got == "too few seeds":
        return "inconclusive", "fewer than 5 contents"
    if got == expect:
        return "agree", ""
    return ("inconclusive" if got == "tie" else "disagree"), ""


def compare_claim(exp, rows, a, b, angle, speeds, col, label, digits, paper, claim, paper_value, expect="A beats B"):
    va, vb = pooled(exp, rows, a, col, angle, speeds), pooled(exp, rows, b, col, angle, speeds)
    if not va or len(va) != len(vb):
        return
    c = exp.stats.compare(va, vb, higher_is_better=False)
    verdict, why = verdict_of(c, expect)
    sa, sb = exp.stats.summary(va), exp.stats.summary(vb)
    res = c["verdict"].replace("A", a).replace("B", b)
    exp.claim(paper, claim, paper_value,
              "%s %s: %s vs %s" % (label, a, exp.stats.fmt_ms(sa, digits), exp.stats.fmt_ms(sb, digits)), verdict,
              (why + "; " if why else "") + "%s: %s (difference %s, spread of the paired differences %s)" %
              (label, res, exp.stats.fmt(c["diff"], digits), exp.stats.fmt(c["spread"], digits)),
              spread=exp.stats.fmt(c["spread"], digits), n=c["n"],
              run="%s/%s angle=%s speed=%s" % (exp.group, SWEEP, angle, " ".join(speeds)))


def claims(exp):
    rows = exp.rows(SWEEP)
    angles = sorted({r["angle"] for r in rows}, key=float)
    speeds = sorted({r["speed"] for r in rows}, key=float)
    mid = [s for s in speeds if 0.25 < frac(s) < 0.75]        # eq. 4: hourglass band (horizontal)
    out = [s for s in speeds if not (0.25 < frac(s) < 0.75)]  # bowtie band (horizontal)
    for col, label, d in METRICS:
        # eq. 4 (horizontal) and eq. 5 (vertical): which fixed ordering wins in which band
        for angle, hg_band, what in (("0", mid, "eq. 4"), ("90", out, "eq. 5")):
            if angle not in angles:
                continue
            bt_band = out if hg_band is mid else mid
            for win, lose, band in (("hourglass", "bowtie", hg_band), ("bowtie", "hourglass", bt_band)):
                if band:
                    compare_claim(exp, rows, "asm-" + win, "asm-" + lose, angle, band, col, label, d,
                                  "TDRT §3.2.3 %s" % what,
                                  "%s motion, l_f in {%s}: %s beats %s" % (
                                      MOTION[angle], ", ".join(sorted({"%.3f" % frac(s) for s in band})), win, lose),
                                  "%s chosen" % win)
        # Fig. 10 right: the adaptive decision function against either fixed ordering, per motion
        for angle in angles:
            for fixed in ("asm-hourglass", "asm-bowtie"):
                compare_claim(exp, rows, "asm-adaptive", fixed, angle, speeds, col, label, d,
                              "TDRT Fig. 10 (right)",
                              "%s motion, %s deg, all speeds: adaptive beats %s" % (MOTION.get(angle, "diagonal"), angle,
                                                                                     fixed[4:]),
                              "adaptive function chosen (best on the website's cameras)")
    # per (direction, speed): is the adaptive choice ever beaten by a fixed ordering beyond the spread?
    beaten, cells = [], 0
    for a in angles:
        for sp in speeds:
            ad = exp.values(rows, "flip", mode="asm-adaptive", angle=a, speed=sp)
            if len(ad) < exp.stats.MIN_SEEDS:
                continue
            cells += 1
            for f in ("asm-hourglass", "asm-bowtie"):
                c = exp.stats.compare(exp.values(rows, "flip", mode=f, angle=a, speed=sp), ad, higher_is_better=False)
                if c["verdict"] == "A beats B":
                    beaten.append((a, sp, f[4:], -c["diff"]))
    if cells:
        cells_beaten = len({(a, sp) for a, sp, _, _ in beaten})
        big = [b for b in beaten if b[3] >= 0.003]
        exp.claim("TDRT Fig. 10 (right)", "adaptive not worse than the better fixed ordering at each direction and speed",
                  "adaptive function chosen", "beaten beyond the spread in %d of %d cells (%d by >= 0.003 FLIP)" % (
                      cells_beaten, cells, len(big)),
                  "agree" if not beaten else "disagree",
                  "cells where a fixed ordering wins (FLIP margin): " + "; ".join(
                      "%s deg %.3f px/frame %s (%.4f)" % (a, float(sp) / HZ, f, d) for a, sp, f, d in beaten) +
                  ("; the clear losses are at 30 and 60 deg with l_f 0.875 / 0.125, where Fig. 10's smooth "
                   "transitions pick the ordering that loses on these photographs" if big else ""),
                  n=cells, run="%s/%s (per direction and speed, 5 contents each)" % (exp.group, SWEEP))
    # the table beside the claims: every (angle, speed), mean +- spread over the contents
    lines = ["| angle | px/frame | l_f | " + " | ".join("%s %s" % (m[4:], lab) for lab in ("FLIP", "flicker")
                                                      for m in ORDERINGS) + " | best (FLIP, beyond spread) |",
             "| ---: | ---: | ---: |" + " ---: |" * (2 * len(ORDERINGS)) + " --- |"]
    for a in angles:
        for s in speeds:
            cells = []
            for col, _, d in METRICS:
                for m in ORDERINGS:
                    cells.append(exp.stats.fmt_ms(exp.stats.summary(exp.values(rows, col, mode=m, angle=a, speed=s)), d))
            vals = {m: exp.values(rows, "flip", mode=m, angle=a, speed=s) for m in ORDERINGS}
            best = min(ORDERINGS, key=lambda m: exp.stats.mean(vals[m]))
            beaten = [m for m in ORDERINGS if m != best and
                      exp.stats.compare(vals[best], vals[m], higher_is_better=False)["verdict"] == "A beats B"]
            tag = best[4:] + (" (beats %s)" % ", ".join(m[4:] for m in beaten) if beaten else " (tie)")
            lines.append("| %s | %.3f | %.3f | %s | %s |" % (a, float(s) / HZ, frac(s), " | ".join(cells), tag))
    exp.write_extra("Mean ± spread over the contents (photographs), per direction and speed:\n\n" +
                    "\n".join(lines) + "\n")
