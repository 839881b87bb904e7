"""TRM §4.2, Fig. 6: over- and undershoot of a moving square after TRM, D and U in gamma codes (TRM's and
tdc's choice) or in linear light, read out in linear luminance and in Stevens brightness.  No tdc-sim
jobs: a 1-D computation of the figure's stimulus with TRM's equations (fig6.py); one row per panel of
the figure and per square, paired over 8 sub-pixel positions of the square."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fig6  # noqa: E402

PHASES = [p / 8.0 for p in range(8)]
# (codes of the background, of the square): the figure's white square on black, and one inside the range
SQUARES = ((0.0, 1.0, "white on black"), (0.1, 0.9, "codes 0.9 on 0.1"))
# "balanced" / "equally sized": the two excursions within 20 % of their mean size - about the 10-20 %
# increment a suprathreshold contrast needs to be told apart (Legge & Foley 1980, as tdc_stats' margins)
REL = 0.20
Q6 = ("Fig. 6: 'Left: In linear luminance space over- and undershoot artifacts are equally sized; however, such "
      "representation is misleading, as brightness perception is non-linear. Center: better estimation of perceived "
      "signal using Stevens's brightness, where overshoot artifacts are shown to be more noticeable. Right: TRM "
      "performs sampling in γ-compressed space, the perceptual impact of over- and undershoot artifacts are "
      "balanced.'")
WHY_BAL = ("the 1-D square with TRM's equations: sampling in gamma codes shrinks the imbalance of the two excursions "
           "in Stevens brightness (the dark side's bump against the bright side's dip; next row) but does not remove "
           "it: on a dark background the cube root's steep start magnifies any bump, and the clamp of beta at 0 "
           "leaves one whatever the space; the paper's figure is a sketch without its luminances")


def claims(exp):
    run = "%s (fig6.py: 1-D, r = 1/2, sigma %.1f px, gamma %.1f, 8 sub-pixel positions)" % (
        exp.group, fig6.SIGMA, fig6.GAMMA)
    for lo, hi, name in SQUARES:
        art = {(sp, ro): [fig6.artefacts(p, lo, hi, sp, ro) for p in PHASES]
               for sp in ("gamma", "linear") for ro in ("luminance", "brightness")}
        over = lambda k: [a[0] for a in art[k]]  # noqa: E731
        under = lambda k: [a[1] for a in art[k]]  # noqa: E731
        size = lambda k: sum(over(k) + under(k)) / (2.0 * len(PHASES))  # noqa: E731
        k = ("linear", "luminance")
        if lo == 0.0 and hi == 1.0:  # the left panel's "equally sized" holds for the figure's full-range square
            exp.judge("TRM §4.2 Fig. 6 (left)", Q6, "%s, D/U in linear light, luminance: over- and "
                      "undershoot equally sized" % name, "equal", over(k), under(k), "equal", "luminance",
                      "overshoot", "undershoot", 4, run=run, margin=REL * size(k), higher_is_better=True)
        k = ("linear", "brightness")
        exp.judge("TRM §4.2 Fig. 6 (centre)", Q6, "%s, D/U in linear light, Stevens brightness: overshoot more "
                  "noticeable than undershoot" % name, "overshoot larger", over(k), under(k), "better",
                  "brightness", "overshoot", "undershoot", 4, run=run, margin=REL * size(k), higher_is_better=True)
        k = ("gamma", "brightness")
        exp.judge("TRM §4.2 Fig. 6 (right)", Q6, "%s, D/U in gamma codes (TRM, tdc), Stevens brightness: over- and "
                  "undershoot balanced" % name, "balanced", over(k), under(k), "equal", "brightness", "overshoot",
                  "undershoot", 4, run=run, margin=REL * size(k), higher_is_better=True, why=WHY_BAL)
        imb = lambda k: [abs(a - b) for a, b in art[k]]  # noqa: E731
        kg, kl = ("gamma", "brightness"), ("linear", "brightness")
        exp.judge("TRM §4.2 Fig. 6 (right vs centre)", Q6, "%s, Stevens brightness: gamma-code D/U more balanced "
                  "than linear-light D/U (|overshoot - undershoot|)" % name, "gamma balances",
                  imb(kg), imb(kl), "better", "brightness imbalance", "gamma codes", "linear light", 4, run=run,
                  margin=REL * size(kl), higher_is_better=False)
