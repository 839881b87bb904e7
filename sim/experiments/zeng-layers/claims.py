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


def verdict_of(got):
    return "agree" if got == "A beats B" else ("inconclusive" if got in ("tie", "too few seeds") else "disagree")


def verdict_both(cr, cs):
    """A claim on RMSE and SSIM (two tdc_stats.compare results): agree when A beats B in both, disagree when B
    beats A in either, else inconclusive (also used by the zeng-reliable group)."""
    if cr["verdict"] == "A beats B" and cs["verdict"] == "A beats B":
        return "agree"
    if "B beats A" in (cr["verdict"], cs["verdict"]):
        return "disagree"
    return "inconclusive"


def both(exp, rows, sweep, a, b, paper, claim, paper_value, why_not=""):
    """A beats B in RMSE (lower) and SSIM (higher), each beyond the paired spread over the seeds."""
    cr = exp.stats.compare(col(exp, rows, a, "rmse"), col(exp, rows, b, "rmse"), higher_is_better=False)
    cs = exp.stats.compare(col(exp, rows, a, "ssim"), col(exp, rows, b, "ssim"), higher_is_better=True)
    verdict = verdict_both(cr, cs)
    sr, ss = exp.stats.summary(col(exp, rows, a, "rmse")), exp.stats.summary(col(exp, rows, b, "rmse"))
    tr, ts = exp.stats.summary(col(exp, rows, a, "ssim")), exp.stats.summary(col(exp, rows, b, "ssim"))
    tdc = "RMSE %s vs %s, SSIM %s vs %s" % (exp.stats.fmt_ms(sr, 2), exp.stats.fmt_ms(ss, 2),
                                            exp.stats.fmt_ms(tr, 4), exp.stats.fmt_ms(ts, 4))
    why = "RMSE: %s (difference %s, paired spread %s); SSIM: %s (difference %s, paired spread %s)" % (
        cr["verdict"].replace("A", a).replace("B", b), exp.stats.fmt(cr["diff"], 2), exp.stats.fmt(cr["spread"], 2),
        cs["verdict"].replace("A", a).replace("B", b), exp.stats.fmt(cs["diff"], 4), exp.stats.fmt(cs["spread"], 4))
    if verdict != "agree" and why_not:
        why += "; " + why_not
    exp.claim(paper, claim, paper_value, tdc, verdict, why, spread=exp.stats.fmt(cr["spread"], 2), n=cr["n"],
              run="%s/%s" % (exp.group, sweep))


GLOSSY_WHY = ("the glossy scene's camera is still and most of the floor reflects static objects: its ordinary "
              "vectors are zero, so the assembly keeps those pixels static and averages the 1-spp GGX layer over "
              "the 4-sample window, while the eq. 5 vectors (mean |m| 8.7 px at 128x96, 72 % of the glossy "
              "samples non-zero) make the floor dynamic: each pixel is one reprojected 1-spp sample, clamped to "
              "the 1-4 neighbours traced in the same refresh (docs/layers.md, 'Glossy goal: not met'); Zeng's Fig. 11 "
              "compares under TAA (exponential accumulation for both) with a moving camera")


def claims(exp):
    rows = {s: exp.rows(s) for s in MODES}
    both(exp, rows["glossy"], "glossy", "lasm-zeng", "lasm-ordinary", "Zeng §4.2, Fig. 11",
         "glossy floor: stochastic glossy vectors (layers, 3 sigma) beat ordinary reprojection in RMSE and SSIM",
         "glossy vectors: no ghosting; RMSE/SSIM better", GLOSSY_WHY)
    both(exp, rows["glossy"], "glossy", "lasm-zeng-clean", "lasm-ordinary", "Zeng §5 + §4.2",
         "glossy floor: glossy vectors + clean-up filter beat ordinary reprojection in RMSE and SSIM",
         "clean-up removes the noisy vectors' artefacts", GLOSSY_WHY)
    both(exp, rows["blocker"], "blocker", "lasm-zeng", "lasm-ordinary", "Zeng §4.1, Fig. 9",
         "moving blocker (soft shadow): shadow vectors per layer beat ordinary vectors in RMSE and SSIM",
         "shadow vectors: the shadow follows its blocker",
         "the soft shadow of a 1-sample area light is noise: shadow vectors make its visibility dynamic, so it "
         "loses the static window's 4-sample mean as the glossy layer does, and the shadow is a small part of "
         "the frame; the 1-sigma variant lasm-zeng-tdrt is the best layered mode here (extra table)")
    both(exp, rows["blocker"], "blocker", "lasm-zeng", "asm-adaptive-smv", "Zeng §4 (layers)",
         "moving blocker: layers with Zeng vectors beat one colour moved by the shadow vector",
         "components reused separately",
         "one colour moved by the shadow vector drags the floor texture, but the blocker's soft shadow is "
         "small next to the disocclusions and the block itself, which both paths reproject the same way")
    both(exp, rows["fence"], "fence", "lasm-zeng", "lasm-ordinary", "Zeng §4.1, Fig. 1/10",
         "Embree fence: shadow vectors per layer beat ordinary vectors in RMSE and SSIM",
         "shadow vectors: no smeared shadow")
    # issue 16's goal on the Embree fence
    best, bs = None, None
    for m in ("lasm-zeng", "lasm-zeng-tdrt", "lasm-zeng-clean"):
        s = exp.stats.summary(exp.values(rows["fence"], "psnr_db", mode=m))
        if best is None or s["mean"] > bs["mean"]:
            best, bs = m, s
    full = exp.stats.summary(exp.values(rows["fence"], "psnr_db", mode="full"))
    single = exp.stats.summary(exp.values(rows["fence"], "psnr_db", mode="asm-adaptive"))
    met = bs["mean"] - bs["spread"] >= FENCE_GOAL_DB
    exp.claim("issue 16 goal", "Embree fence: Zeng vectors with layers recover half the gap 24.94 -> 32.41 dB",
              ">= %.2f dB" % FENCE_GOAL_DB,
              "%s %s dB (single-layer ordinary %s, full rate %s)" % (best, exp.stats.fmt_ms(bs, 2),
                                                                     exp.stats.fmt_ms(single, 2),
                                                                     exp.stats.fmt_ms(full, 2)),
              "agree" if met else "disagree",
              "met" if met else ("%.2f dB short; the full-rate stream (every pixel traced every refresh, 1 ray "
                                 "at the pixel centre) reaches only %.2f dB against the 16-ray ground truth on "
                                 "this scene and the assembly reaches 29.6 dB when nothing moves (4-sample window): the loss is edge "
                                 "aliasing where things move (dynamic pixels, the fence and the hard shadow edges, keep "
                                 "one pixel-centre ray), not the vectors; gamma, light colour and ground-truth samples "
                                 "moved it by at most 0.1 dB (docs/layers.md, 'Embree fence: what limits it')" %
                                 (FENCE_GOAL_DB - bs["mean"], full["mean"])),
              spread=exp.stats.fmt(bs["spread"], 2), n=bs["n"], run="%s/fence" % exp.group)
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
    exp.write_extra("RMSE in 8-bit code values from each run's PSNR (255 · 10^(−PSNR/20)); "
                    "whole evaluated frame.\n" + "\n".join(lines) + "\n")


