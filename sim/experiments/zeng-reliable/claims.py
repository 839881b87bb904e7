"""Zeng et al. §6-§7 on the double-precision reference pipeline (tdc-zeng): RMSE/SSIM of the temporally reliable
vectors against traditional vectors (with and without clamping), specular vectors and SVGF, per scene, 5 seeds."""
import csv
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
SCENES = ("fence", "glossy", "occlusion", "pinkroom", "lights", "apples")
SEEDS = "1 2 3 4 5"
# size, frames, first evaluated frame (the history needs ~1/alpha = 10 frames to fill)
SCALES = {"demo": ("64x48", 20, 12), "dev": ("128x96", 36, 16), "headset": ("128x96", 36, 16)}
# the JOD judge (tdc-zeng --jod): each pixel seen as one pixel of a desktop display at 60 pixels per degree,
# as the paper's 1-spp pixels would be on one (its frames are 1920x1080; the paper names no display)
JOD_PPD = "60"
PIXELS = {"64x48": 64 * 48, "128x96": 128 * 96, "160x120": 160 * 120}
# §7's "negligible" against tdc-zeng's primary rays, the only other pass it times (no shading pass: the
# zeng-cost group's 0.10 of primary rays + shading has no counterpart here)
NEGLIGIBLE = 0.25
FIG = {"fence": "Zeng Fig. 8", "glossy": "Zeng Fig. 11 (and Fig. 1 middle)",
       "occlusion": "Zeng Fig. 12 (and Fig. 1 right)", "pinkroom": "Zeng Fig. 1 left (pink room; Fig. 9's moving light)",
       "lights": "Zeng Fig. 10 (the fence, another view, several moving lights)",
       "apples": "Zeng Fig. 9 (apples on a cloth, a rapidly moving area light on the right)"}
SENTENCE = {
    "fence": "\"our shadow motion vectors are able to produce shadows that are closely attached to the fence\"; "
             "\"With clamping, the results are less lagging but much more noisy\"",
    "glossy": "\"Our method produces the closest result to the ground truth\"",
    "occlusion": "\"our occlusion motion vectors are able to find their corresponding locations in the previous "
                 "frame, thus avoiding noise and repetitive patterns\"",
    "pinkroom": "\"We can see that our shadow motion vectors work well with complex occlusion conditions, even when the "
                "locally flat plane assumption is violated, thanks to our cosine falloff heuristic.\"",
    "lights": "\"our method naturally extends to multiple lights with negligible overhead. [...] we perform as usual "
              "- for each light sample, we compute its motion vector.\" (§4.1)",
    "apples": "\"Fig. 9 shows the Apples scene with highly curved apples and cloth on the desk, and a rapidly moving "
              "area light on the right. We demonstrate that our shadow motion vectors are still capable of producing "
              "visually pleasing results on non-planar shadow receivers.\" (§4.1)",
}
# Fig. 10's caption, the paper's own verdict on its several-light fence (§7 files it under "Failure due to mixed
# information": one vector per pixel where several shadows move differently)
FIG10 = ("\"Figure 10: Another view of the fence scene with multiple moving light sources. Compared with the ground "
         "truth, we found that our result tends to be blurred and less plausible.\"")


def binary():
    return os.environ.get("TDC_ZENG") or os.path.join(REPO, "build", "gcc-O2", "tdc-zeng")


def run_scene(exp, scene, variant=()):
    """Rows of tdc-zeng's CSV for one scene (cached in the group's result folder); variant: extra tdc-zeng
    arguments (a pipeline switched off for an ablation row)."""
    size, frames, first = SCALES.get(exp.scale, SCALES["headset"])
    d = os.path.join(exp.out, exp.group)
    os.makedirs(d, exist_ok=True)
    tag = "".join(a.strip("-") for a in variant)
    path = os.path.join(d, "%s-%s-%d-jod%s%s.csv" % (scene, size, frames, JOD_PPD, "-" + tag if tag else ""))
    if not os.path.isfile(path):
        cmd = [binary(), "--scene", scene, "--size", size, "--frames", str(frames), "--eval-from", str(first),
               "--seeds", SEEDS, "--gt-spp", "1024", "--jod", JOD_PPD, "--csv", path + ".tmp"] + list(variant)
        subprocess.run(cmd, check=True)
        os.replace(path + ".tmp", path)
    with open(path, newline="", encoding="utf-8") as f:
        lines = f.read().splitlines()
    rows = list(csv.DictReader([ln for ln in lines if not ln.startswith("cost")]))
    cost = [ln.split(",") for ln in lines if ln.startswith("cost,") and not ln.startswith("cost,primary")]
    return rows, (float(cost[0][1]), float(cost[0][2])) if cost else None, size, frames, first


def col(rows, method, name):
    sel = sorted((r for r in rows if r["method"] == method), key=lambda r: int(r["seed"]))
    return [float(r[name]) for r in sel]


def compare(exp, scene, rows, a, b, run, region):
    """Ours beats b as an observer sees it: JOD (FovVideoVDP, tdc-zeng --jod; margin 0.1 JOD) decides, judged by
    tdc_stats over the 5 seeds (95 % interval of the paired gain against the margin); the paper's own metrics,
    RMSE (lower) and SSIM (higher), stand beside it with their own intervals and verdicts.  region: the effect
    region's JOD (the test is the reference outside the region), RMSE and SSIM."""
    jk, rk, sk = ("jod_region", "rmse_region", "ssim_region") if region else ("jod", "rmse", "ssim")
    where = "effect region" if region else "whole frame"
    exp.judge(FIG[scene], SENTENCE[scene], "%s, %s: ours beats %s (JOD; RMSE and SSIM beside)" % (scene, where, b),
              "lower RMSE, higher SSIM than %s" % b, col(rows, a, jk), col(rows, b, jk), "better", "jod", a, b, 3,
              run=run, why=WHY_NOT.get((scene, b), "see sim/zeng/README.md") + (
                  OCCLUSION_SETTING if CLASS.get((scene, b)) == "setting" and scene == "occlusion" else ""),
              cls=CLASS.get((scene, b), ""),
              secondary=[("rmse", col(rows, a, rk), col(rows, b, rk), 4), ("ssim", col(rows, a, sk), col(rows, b, sk), 4)],
              note="JOD of the evaluated frames as a 60 Hz video at %s pixels per degree on a 200 cd/m^2 SDR "
                   "display (tdc-zeng --jod%s)" % (JOD_PPD, "; region: the test is the reference outside the "
                                                               "effect region" if region else ""))


# what a row that does not agree rests on (docs/experiments.md); filled per (scene, baseline)
# (the glossy rows are not classed: with [LLK*19]'s filter built, eq. 5's per-pixel fetch let through by the
# 3-sigma clamp is a finding about the method as written, sim/zeng/README.md, not a difference of set-up)
OCCLUSION_SETTING = ("; tdc-zeng's occlusion scene is an analytic room with smooth indirect light, not the paper's "
                     "PICA scene (whose indirect light Figs. 1 and 12 show scaled 10x)")
CLASS = {("occlusion", "trad"): "setting", ("occlusion", "asvgf"): "setting"}
WHY_NOT = {
    ("glossy", "trad-clamp"): "with the paper's glossy filter ([LLK*19], built) the loss stays: each pixel's eq. 5 "
                              "vector fetches the history at the virtual image of its own lobe sample, spread over "
                              "the lobe's footprint; fetched from the noise-free previous ground truth that alone "
                              "errs 6x the specular vector's (RMSE 0.027 vs 0.0042, 128x96, tdc-zeng "
                              "--fetch-error 1) and misses the floor on 19 % of pixels, and the 3-sigma clamp over "
                              "the 1-sample neighbourhood lets it through; at 128x96 (sim/zeng/README.md) the "
                              "1-sigma clamp recovers 0.61 of the 0.80 JOD lost, no spread 0.16, both leave -0.09 "
                              "[-0.22, 0.04] (a tie with spec)",
    ("glossy", "spec"): "as against trad-clamp: the specular vector is deterministic, so its history fetch adds no "
                        "noise, and in this scene its virtual image differs from the lobe's only at object edges",
    ("occlusion", "trad"): "traditional vectors reject the disoccluded history and fall back to the 4-level "
                           "a-trous filter, which on this smooth indirect light is already close to the ground "
                           "truth; the dual vectors fetch the background beside the occluder, whose irradiance "
                           "differs (the occluder's own contact shadow), and the 3-sigma clamp lets it through",
    ("occlusion", "asvgf"): "A-SVGF rejects the history where its gradient fires and otherwise filters as SVGF "
                            "does: on smooth indirect light its overblur costs little",
    ("glossy", "asvgf"): "as against trad-clamp: the eq. 5 vectors' noisy history fetch",
    ("lights", "asvgf"): "each pixel keeps the vector of the one light it sampled while its history mixes three "
                         "shadows moving at three speeds (Zeng §7, 'Failure due to mixed information': 'Another "
                         "example is in Fig. 10'); A-SVGF's gradient drops that history and it filters spatially",
    ("apples", "asvgf"): "at 64x48 only: at 128x96 ours beats A-SVGF by +0.39 JOD [0.37, 0.42] and in RMSE and SSIM "
                         "(sim/zeng/README.md); at 64x48 ours is ahead in RMSE and SSIM, not in JOD, cause not "
                         "looked into",
    ("lights", "trad"): "as against asvgf: one vector per pixel for three shadows moving differently (Zeng §7)",
}


def claims(exp):
    st = exp.stats
    extra = []
    for scene in SCENES:
        rows, cost, size, frames, first = run_scene(exp, scene)
        run = "%s (tdc-zeng %s, frames %d-%d, seeds %s, 1024-spp ground truth)" % (exp.group, size, first,
                                                                                    frames - 1, SEEDS)
        # no row against SVGF: §6 makes no quantitative claim there ('Note that sometimes SVGF is better in
        # quantity, and this is because it tends to produce a significant amount of overblur'); its numbers
        # are in the table beside the claims
        # nor against A-SVGF on the several-light fence: §7 files Fig. 10 under its failure cases ('Failure due
        # to mixed information. [...] Another example is in Fig. 10'), so the paper claims no win there; its
        # caption's verdict is judged below (lights vs fence) and A-SVGF's numbers are in the table
        baselines = (["trad-clamp", "trad"] + ([] if scene == "lights" else ["asvgf"]) +
                     (["spec"] if scene == "glossy" else []))
        for b in baselines:
            compare(exp, scene, rows, "ours", b, run, region=False)
        compare(exp, scene, rows, "ours", "trad-clamp", run, region=True)
        if scene == "pinkroom":
            # "... thanks to our cosine falloff heuristic": ours against ours with eq. 4 switched off (alpha^V =
            # alpha everywhere), the same seeds and frames
            nf, _, _, _, _ = run_scene(exp, scene, ("--no-falloff", "1"))
            exp.judge(FIG[scene], SENTENCE[scene], "pinkroom, whole frame: ours beats ours without eq. 4's cosine "
                      "falloff (JOD; RMSE and SSIM beside)", "the falloff helps where the flat receiver fails",
                      col(rows, "ours", "jod"), col(nf, "ours", "jod"), "better", "jod", "ours", "ours-no-falloff",
                      3, run=run + "; tdc-zeng --no-falloff 1 for the second",
                      secondary=[(m, col(rows, "ours", m), col(nf, "ours", m), 4) for m in ("rmse", "ssim")],
                      note="JOD of the evaluated frames as a 60 Hz video at %s pixels per degree (tdc-zeng --jod)" %
                      JOD_PPD)
        if scene == "lights":
            # Fig. 10's caption: ours falls further from the truth with several lights than with one.  Read as:
            # ours' JOD gain over traditional vectors with clamping is smaller here than on the one-light fence
            # (Fig. 8's scene, same fence motion, size, frames and seeds; paired by seed number)
            fr, _, _, _, _ = run_scene(exp, "fence")
            gain = lambda r: [a - b for a, b in zip(col(r, "ours", "jod"), col(r, "trad-clamp", "jod"))]  # noqa
            exp.judge(FIG[scene], FIG10, "lights vs fence: ours' JOD gain over trad-clamp is smaller with three "
                      "moving lights than with the fence's one (JOD)", "blurred and less plausible than the ground "
                      "truth with several lights", gain(fr), gain(rows), "better", "jod", "fence gain",
                      "lights gain", 3, run=run + "; the fence scene's run for the first",
                      secondary=[("rmse", [a - b for a, b in zip(col(fr, "ours", "rmse"), col(fr, "trad-clamp",
                                                                                             "rmse"))],
                                  [a - b for a, b in zip(col(rows, "ours", "rmse"), col(rows, "trad-clamp", "rmse"))],
                                  4)],
                      note="gains paired by seed number (the scenes share the fence and its motion, not the noise); "
                           "secondary: ours' RMSE minus trad-clamp's, lower (a larger gain) on the fence if the "
                           "claim holds")
        methods = [m for m in ("trad", "trad-clamp", "spec", "ours", "svgf", "asvgf") if col(rows, m, "rmse")]
        extra += ["", "**%s** %s, frames %d-%d (mean ± spread over 5 seeds):" % (scene, size, first, frames - 1), "",
                  "| method | JOD | RMSE | SSIM | JOD region | RMSE region | SSIM region |",
                  "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
        for m in methods:
            extra.append("| %s | %s |" % (m, " | ".join(st.fmt_ms(st.summary(col(rows, m, c)), 3 if "jod" in c else 4)
                                                       for c in ("jod", "rmse", "ssim", "jod_region", "rmse_region",
                                                                 "ssim_region"))))
        if scene == "occlusion" and cost:
            ratio = cost[1] / cost[0]
            exp.claim("Zeng §7", "dual vectors (eq. 6, a lookup in the previous frame's ids and depths): cost "
                      "per frame beside the primary rays", "negligible (< 0.23 ms at 1080p, GPU)",
                      "%.3f ms vs %.3f ms primary (%.3f×)" % (cost[1], cost[0], ratio),
                      "agree" if ratio <= NEGLIGIBLE else "disagree",
                      "thread CPU time over frames 1-%d of seed 1, one pass over every pixel each; 'negligible' "
                      "read as <= %.2f of the primary rays; the Embree renderer's dual "
                      "pass reads its previous FULL frame's depth / object-id G-buffer too (zeng-cost group)%s" % (
                          frames - 1, NEGLIGIBLE,
                          "" if ratio <= NEGLIGIBLE else
                          "; the lookup costs %.0f ns a pixel whatever the scene, while a primary ray into these "
                          "analytic scenes (5-12 objects, no hierarchy) costs only %.0f ns: the ratio says more "
                          "about the cheap rays than about the lookup" % (
                              1e6 * cost[1] / PIXELS[size], 1e6 * cost[0] / PIXELS[size])),
                      n=1, run=run, cls="" if ratio <= NEGLIGIBLE else "setting",
                      quote="Zeng §7: 'in practice, we observed only a negligible performance cost by "
                      "replacing with our motion vectors, which is always less than 0.23 ms.'")
    exp.write_extra("JOD: FovVideoVDP (tdc-zeng --jod " + JOD_PPD + ") of the evaluated frames as a 60 Hz video on a "
                    "200 cd/m^2 SDR display; the region's JOD judges the test with the reference outside the "
                    "region. RMSE and SSIM on gamma-encoded frames (values in [0, 1]); regions: fence, pinkroom, lights and apples = "
                    "where the ground-truth visibility is below 0.98 now or in the 3 frames before, glossy = the glossy "
                    "floor, occlusion = pixels disoccluded in the last 8 frames.\n" + "\n".join(extra) + "\n")
