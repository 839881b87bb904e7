"""Zeng et al. §4-§6 through the layered tile assembly (issue 16): glossy floor, moving blocker, Embree fence."""


# issue 16's fence goal: half of the gap between single-layer ordinary
# vectors (24.94 dB) and the procedural exact-vector result (32.41 dB)
FENCE_GOAL_DB = (24.94 + 32.41) / 2.0
MODES = {
    "glossy": ("full", "asm-adaptive", "lasm-ordinary", "lasm-zeng", "lasm-zeng-tdrt", "lasm-zeng-clean"),
    "blocker": ("full", "asm-adaptive", "asm-adaptive-smv", "lasm-ordinary", "lasm-zeng", "lasm-zeng-tdrt",
                "lasm-zeng-clean"),
    "fence": ("full", "asm-adaptive", "asm-adaptive-smv", "lasm-ordinary", "lasm-zeng", "lasm-zeng-tdrt",
              "lasm-zeng-clean"),
}


def rmse(psnr_db):
    """RMSE in 8-bit code values of a run from its PSNR (tdc-sim's PSNR is the mean over the evaluated
    instants of 20 log10(255 / RMSE) on gamma-encoded images)."""
    return 255.0 * 10.0 ** (-psnr_db / 20.0)


def col(exp, rows, mode, name):
    if name == "rmse":
        return [rmse(v) for v in exp.values(rows, "psnr_db", mode=mode)]
    return exp.values(rows, name, mode=mode)


Q_GLOSSY = ("Zeng §6 (Figs. 1, 11): 'The comparison indicates that our glossy reflection motion vectors do not "
            "introduce ghosting artifacts. However, with traditional motion vectors, naive filtering produces significant "
            "ghosting.' ... 'Our method produces the closest result to the ground truth'")
Q_CLEAN = ("Zeng §4.2: 'when the roughness is high, the glossy reflection motion vectors will be more noisy, but the "
           "temporally filtered result will be then spatially cleaned up in a more aggressive manner.'")
Q_SHADOW = ("Zeng §6 (Fig. 8): 'our shadow motion vectors are able to produce shadows that are closely attached to "
            "the fence. In comparison, traditional motion vectors produce significant ghosting artifacts.'")
Q_LAYERS = ("Zeng §5: 'One benefit from filtering separately for different effects is that we can use small spatial "
            "filters for each of them.'")
# why the layered assembly is not Zeng's set-up (the rows that do not agree are setting differences;
# Zeng's own pipeline, TAA with a moving camera, is the zeng-reliable group)
SETTING = ("tdc's layered tile assembly at 240 Hz is not Zeng's pipeline: Zeng accumulates every pixel under TAA "
           "(exponential history, eq. 2) with a moving camera, where the assembly keeps a static pixel's 4-sample "
           "window mean and shows a dynamic pixel as one reprojected sample; Zeng's set-up is the zeng-reliable group")


def both(exp, rows, sweep, a, b, paper, quote, claim, paper_value, why_not=""):
    """A beats B in RMSE (lower) and SSIM (higher): each judged by tdc_stats (95 % interval of the paired
    gain over the seeds against the metric's margin), the row holding only when both hold."""
    exp.judge_all(paper, quote, claim, paper_value,
                  [("rmse", col(exp, rows, a, "rmse"), col(exp, rows, b, "rmse"), 2),
                   ("ssim", col(exp, rows, a, "ssim"), col(exp, rows, b, "ssim"), 4)],
                  "better", a, b, run="%s/%s" % (exp.group, sweep), why=why_not + "; " + SETTING if why_not else SETTING,
                  cls="setting")


GLOSSY_WHY = ("the glossy scene's camera is still and most of the floor reflects static objects: its ordinary "
              "vectors are zero, so the assembly keeps those pixels static and averages the 1-spp GGX layer over "
              "the 4-sample window, while the eq. 5 vectors (mean |m| 8.7 px at 128x96, 72 % of the glossy "
              "samples non-zero) make the floor dynamic: each pixel is one reprojected 1-spp sample, clamped to "
              "the 1-4 neighbours traced in the same refresh (docs/layers.md, 'Glossy goal: not met'); Zeng's Fig. 11 "
              "compares under TAA (exponential accumulation for both) with a moving camera")


def claims(exp):
    rows = {s: exp.rows(s) for s in MODES}
    both(exp, rows["glossy"], "glossy", "lasm-zeng", "lasm-ordinary", "Zeng §4.2, Fig. 11", Q_GLOSSY,
         "glossy floor: stochastic glossy vectors (layers, 3 sigma) beat ordinary reprojection in RMSE and SSIM",
         "glossy vectors: no ghosting; RMSE/SSIM better", GLOSSY_WHY)
    both(exp, rows["glossy"], "glossy", "lasm-zeng-clean", "lasm-ordinary", "Zeng §5 + §4.2", Q_CLEAN,
         "glossy floor: glossy vectors + clean-up filter beat ordinary reprojection in RMSE and SSIM",
         "clean-up removes the noisy vectors' artefacts", GLOSSY_WHY)
    both(exp, rows["blocker"], "blocker", "lasm-zeng", "lasm-ordinary", "Zeng §4.1, Fig. 9", Q_SHADOW,
         "moving blocker (soft shadow): shadow vectors per layer beat ordinary vectors in RMSE and SSIM",
         "shadow vectors: the shadow follows its blocker",
         "the soft shadow of a 1-sample area light is noise: shadow vectors make its visibility dynamic, so it "
         "loses the static window's 4-sample mean as the glossy layer does, and the shadow is a small part of "
         "the frame; the 1-sigma variant lasm-zeng-tdrt is the best layered mode here (extra table)")
    both(exp, rows["blocker"], "blocker", "lasm-zeng", "asm-adaptive-smv", "Zeng §4 (layers)", Q_LAYERS,
         "moving blocker: layers with Zeng vectors beat one colour moved by the shadow vector",
         "components reused separately",
         "one colour moved by the shadow vector drags the floor texture, but the blocker's soft shadow is "
         "small next to the disocclusions and the block itself, which both paths reproject the same way")
    both(exp, rows["fence"], "fence", "lasm-zeng", "lasm-ordinary", "Zeng §4.1, Fig. 1/10", Q_SHADOW,
         "Embree fence: shadow vectors per layer beat ordinary vectors in RMSE and SSIM",
         "shadow vectors: no smeared shadow")
    # issue 16's goal on the Embree fence: tdc's own target, not a sentence of the paper (its 32.41 dB is
    # the procedural scene's exact-vector result), so it is reported beside the claims, not as a row
    best, bs = None, None
    for m in ("lasm-zeng", "lasm-zeng-tdrt", "lasm-zeng-clean"):
        s = exp.stats.summary(exp.values(rows["fence"], "psnr_db", mode=m))
        if best is None or s["mean"] > bs["mean"]:
            best, bs = m, s
    full = exp.stats.summary(exp.values(rows["fence"], "psnr_db", mode="full"))
    single = exp.stats.summary(exp.values(rows["fence"], "psnr_db", mode="asm-adaptive"))
    met = bs["mean"] - bs["spread"] >= FENCE_GOAL_DB
    goal = ("Issue 16's goal (tdc's, not the paper's): on the Embree fence, Zeng vectors with layers recover half "
            "the gap 24.94 -> 32.41 dB (>= %.2f dB): best layered mode %s %s dB (single-layer ordinary %s, full "
            "rate %s): %s" % (FENCE_GOAL_DB, best, exp.stats.fmt_ms(bs, 2), exp.stats.fmt_ms(single, 2),
                              exp.stats.fmt_ms(full, 2), "met" if met else (
                                  "not met, %.2f dB short; the full-rate stream (1 ray at the pixel centre) reaches "
                                  "only %.2f dB against the ground truth on this scene: the loss is edge aliasing "
                                  "where things move, not the vectors (docs/layers.md, 'Embree fence: what limits "
                                  "it')" % (FENCE_GOAL_DB - bs["mean"], full["mean"]))))
    lines = []
    for s, modes in MODES.items():
        lines += ["", "**%s** (mean ± spread over the 5 %s):" % (s, "stretches" if s == "fence" else "seeds"), "",
                  "| mode | PSNR dB | RMSE (codes) | SSIM | FLIP |", "| --- | ---: | ---: | ---: | ---: |"]
        for m in modes:
            cells = [exp.stats.fmt_ms(exp.stats.summary(col(exp, rows[s], m, c)), d)
                     for c, d in (("psnr_db", 2), ("rmse", 2), ("ssim", 4), ("flip", 4))]
            if not all(c and not c.startswith("nan") for c in cells):
                continue
            lines.append("| %s | %s |" % (m, " | ".join(cells)))
    exp.write_extra(goal + "\n\nRMSE in 8-bit code values from each run's PSNR (255 · 10^(−PSNR/20)); "
                    "whole evaluated frame.\n" + "\n".join(lines) + "\n")


