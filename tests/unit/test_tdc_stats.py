#!/usr/bin/python3
"""test_tdc_stats.py - sim/experiments/tdc_stats.py on synthetic data with known answers.

Student's t (cdf, quantile, the paired interval) against scipy.stats; the
seeded bootstrap (reproducible, close to scipy.stats.bootstrap's percentile
interval); the 95 % coverage of both intervals on 400 seeded normal samples
(binomial bounds); compare() against scipy.stats.ttest_rel / ttest_ind
(Welch); judge()'s four verdicts for each claim on constructed gains whose
interval is known; the margins table.  ~2 s.  Exit 0 when all hold."""
import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "sim", "experiments"))
import tdc_stats as s  # noqa: E402
from scipy import stats as sp  # noqa: E402
import numpy as np  # noqa: E402

fails = 0


def check(cond, what):
    global fails
    print("%s: %s" % ("ok" if cond else "FAIL", what))
    if not cond:
        fails += 1


# 1. Student's t against scipy
worst_cdf = max(abs(s.t_cdf(t, df) - sp.t.cdf(t, df)) for df in (1, 2, 3, 4, 7, 19, 60)
                for t in (-8.0, -2.5, -0.3, 0.0, 0.7, 2.1, 9.0))
check(worst_cdf < 1e-12, "t_cdf = scipy.stats.t.cdf (max |diff| %.1e over df 1-60)" % worst_cdf)
worst_ppf = max(abs(s.t_ppf(p, df) - sp.t.ppf(p, df)) / max(1.0, abs(sp.t.ppf(p, df))) for df in range(1, 41)
                for p in (0.005, 0.05, 0.5, 0.9, 0.95, 0.975, 0.995))
# scipy's stdtrit is good to ~1e-9 in probability (t_cdf of its quantile: 0.9500000007 at df 30)
check(worst_ppf < 1e-7, "t_ppf = scipy.stats.t.ppf (max relative diff %.1e over df 1-40, 7 levels)" % worst_ppf)
worst_rt = max(abs(s.t_cdf(s.t_ppf(p, df), df) - p) for df in range(1, 41) for p in (0.005, 0.05, 0.5, 0.975))
check(worst_rt < 1e-12, "t_cdf(t_ppf(p)) = p (max |diff| %.1e)" % worst_rt)
check(abs(s.t_ppf(0.975, 4) - 2.7764451051977987) < 1e-9, "t_{0.975, 4} = 2.776445 (tables)")

# 2. the paired t interval against scipy's
rng = random.Random(7)
worst_ci = 0.0
for n in (2, 5, 9, 20):
    d = [rng.gauss(0.3, 1.0) for _ in range(n)]
    lo, hi = s.ci_t(d)
    slo, shi = sp.t.interval(0.95, n - 1, loc=np.mean(d), scale=sp.sem(d))
    worst_ci = max(worst_ci, abs(lo - slo), abs(hi - shi))
check(worst_ci < 1e-9, "ci_t = scipy.stats.t.interval(0.95, n-1, mean, sem) (max |diff| %.1e, n 2-20)" % worst_ci)

# 3. the bootstrap: seeded, close to scipy's percentile bootstrap
d = [rng.gauss(1.0, 0.5) for _ in range(12)]
b1, b2 = s.ci_bootstrap(d), s.ci_bootstrap(d)
check(b1 == b2, "ci_bootstrap reproducible with its fixed seed %s" % (b1,))
ref = sp.bootstrap((np.array(d),), np.mean, confidence_level=0.95, n_resamples=20000, method="percentile",
                   random_state=np.random.default_rng(1)).confidence_interval
w = ref.high - ref.low
check(abs(b1[0] - ref.low) < 0.1 * w and abs(b1[1] - ref.high) < 0.1 * w,
      "ci_bootstrap [%.4f, %.4f] within 10 %% of the width of scipy.stats.bootstrap's [%.4f, %.4f]" %
      (b1[0], b1[1], ref.low, ref.high))

# 4. coverage: 95 % intervals hold the true mean in 95 % of seeded samples
# (400 samples: binomial 99.9 % bounds 0.913-0.979)
rng = random.Random(11)
cov_t = cov_b = 0
for i in range(400):
    d = [rng.gauss(2.0, 1.0) for _ in range(8)]
    lo, hi = s.ci_t(d)
    cov_t += lo < 2.0 < hi
    lo, hi = s.ci_bootstrap(d, resamples=400, seed=i)
    cov_b += lo < 2.0 < hi
check(0.913 <= cov_t / 400 <= 0.979, "t interval coverage %.3f of 400 samples (n 8; 0.95 expected)" % (cov_t / 400))
# the percentile bootstrap undercovers at n = 8 (known: ~0.90-0.92), never as far as a 80 % interval
check(0.86 <= cov_b / 400 <= 0.97, "bootstrap coverage %.3f of 400 samples (n 8; percentile undercovers slightly)" %
      (cov_b / 400))

# 5. compare(): the paired t test, not "difference > SD of the differences"
rng = random.Random(3)
base = [rng.gauss(30.0, 2.0) for _ in range(20)]
z = [rng.gauss(0.0, 1.0) for _ in range(20)]
z = [(v - s.mean(z)) / s.spread(z) for v in z]         # exactly mean 0, sd 1
a = [x + 0.6 + v for x, v in zip(base, z)]              # effect size d_z = 0.6 at n = 20: t = 2.68
c = s.compare(a, base)
p = sp.ttest_rel(a, base).pvalue
check(c["verdict"] == "A beats B" and p < 0.05 and abs(c["diff"]) < c["spread"],
      "compare: d_z %.2f < 1 at n 20 is 'A beats B' (scipy ttest_rel p %.4f)" % (c["diff"] / c["spread"], p))
agree = 0
for i in range(200):
    r = random.Random(100 + i)
    x = [r.gauss(0, 1) for _ in range(6)]
    y = [v + r.gauss(0.5, 1.0) for v in x]
    c = s.compare(y, x)
    res = sp.ttest_rel(y, x)
    sig = res.pvalue < 0.05
    agree += (c["verdict"] != "tie") == sig
check(agree == 200, "compare's verdict = scipy ttest_rel at 5 %% on %d of 200 random pairs (n 6)" % agree)
agree = 0
for i in range(200):
    r = random.Random(500 + i)
    x = [r.gauss(0, 1) for _ in range(6)]
    y = [r.gauss(1.0, 2.0) for _ in range(9)]
    c = s.compare(y, x, paired=False)
    sig = sp.ttest_ind(y, x, equal_var=False).pvalue < 0.05
    agree += (c["verdict"] != "tie") == sig
check(agree == 200, "unpaired compare = scipy ttest_ind (Welch) at 5 %% on %d of 200 random samples" % agree)
check(s.compare([1, 2, 3, 4], [0, 1, 2, 3])["verdict"] == "too few seeds", "compare: 4 pairs are too few")
lo_is_better = s.compare([0.10, 0.11, 0.12, 0.10, 0.11], [0.15, 0.16, 0.17, 0.15, 0.17], higher_is_better=False)
check(lo_is_better["verdict"] == "A beats B" and lo_is_better["lo"] > 0, "compare: lower-is-better orientation")


# 6. judge(): gains constructed so the interval is known.  g = c + e * z,
# z = (-2, -1, 0, 1, 2): mean c, sd e * 1.5811, half-width t_{.975,4} * sd / sqrt(5) = 1.9630 e.
def pair(c, e, base=10.0, hib=True):
    z = (-2.0, -1.0, 0.0, 1.0, 2.0)
    b = [base + 0.1 * i for i in range(5)]
    a = [x + (c + e * k if hib else -(c + e * k)) for x, k in zip(b, z)]
    return a, b


H = 1.9630  # half-width per unit e (above)
lo, hi = s.ci_t([0.5 + 0.1 * k for k in (-2, -1, 0, 1, 2)])
check(abs(hi - lo - 2 * H * 0.1) < 1e-3, "half-width of the constructed gains %.4f (1.9630 e expected)" % ((hi - lo) / 2))
cases = [  # claim, gain c, e, margin, expected verdict
    ("better", 0.5, 0.1, 0.25, "agree"),          # [0.30, 0.70]
    ("better", 0.1, 0.01, 0.25, "agree"),         # [0.08, 0.12]: better, by less than m (still shown better)
    ("better", 0.0, 0.05, 0.25, "disagree"),      # [-0.10, 0.10] < m: no gain worth the name
    ("better", -0.5, 0.1, 0.25, "disagree"),      # A worse
    ("better", 0.1, 0.1, 0.25, "inconclusive"),   # [-0.10, 0.30] spans 0 and m
    ("not worse", -0.1, 0.05, 0.25, "agree"),     # [-0.20, 0.00] above -m
    ("not worse", -0.6, 0.1, 0.25, "disagree"),   # [-0.80, -0.40] below -m
    ("not worse", -0.2, 0.1, 0.25, "inconclusive"),  # [-0.40, 0.00] spans -m
    ("equal", 0.05, 0.05, 0.25, "equivalent"),    # [-0.05, 0.15] inside +-m
    ("equal", 0.6, 0.1, 0.25, "disagree"),        # [0.40, 0.80] beyond +m
    ("equal", -0.6, 0.1, 0.25, "disagree"),       # beyond -m
    ("equal", 0.2, 0.1, 0.25, "inconclusive"),    # [0.00, 0.40] crosses +m
]
for claim, c, e, m, want in cases:
    for hib in (True, False):
        a, b = pair(c, e, hib=hib)
        j = s.judge(a, b, claim, "psnr_db" if hib else "flip", margin=m)
        check(j["verdict"] == want and abs(j["gain"] - c) < 1e-9,
              "judge %-9s gain %+.2f CI [%+.3f, %+.3f] m %.2f (%s) -> %s" % (
                  claim, c, j["lo"], j["hi"], m, "higher better" if hib else "lower better", j["verdict"]))
a, b = pair(0.5, 0.1)
check(s.judge(a[:4], b[:4], "better", "psnr_db")["verdict"] == "inconclusive", "judge: 4 pairs inconclusive")
# relative margin: 3 % of B's mean FLIP
a, b = pair(0.001, 0.0005, base=0.1, hib=False)
j = s.judge(a, b, "equal", "flip")
check(abs(j["margin"] - 0.03 * s.mean(b)) < 1e-12 and j["verdict"] == "equivalent",
      "judge: FLIP margin 3 %% of B's mean (%.5f), a 0.001 difference equivalent" % j["margin"])
j2 = s.judge(a, b, "equal", "flip", method="bootstrap")
check(j2["verdict"] == "equivalent" and j2["lo"] > j["lo"] - 1e-12 and j2["hi"] < j["hi"] + 1e-12,
      "judge with the bootstrap interval (narrower than t at n 5): equivalent")
j = s.judge([1.0] * 5, [0.5] * 5, "better", "psnr_db")
check(j["verdict"] == "agree" and "in effect one pair" in j["why"], "judge names identical pairs: %s" % j["why"])
check(all(k in s.MARGINS for k in s.HIGHER_IS_BETTER) and all(k in s.HIGHER_IS_BETTER for k in s.MARGINS),
      "every metric has a margin and a direction")
try:
    s.judge(a, b, "equal", "nosuch")
    check(False, "unknown metric refused")
except ValueError as ex:
    check("no equivalence margin" in str(ex), "unknown metric refused: %s" % ex)

# 7. judge_all(): a claim on several metrics holds only in all of them, is refuted by any one
A, D, I, E = ({"verdict": v} for v in ("agree", "disagree", "inconclusive", "equivalent"))
for parts, want in (((A, A), "agree"), ((A, I), "inconclusive"), ((I, A), "inconclusive"), ((A, D), "disagree"),
                    ((I, D), "disagree"), ((E, E), "equivalent"), ((E, I), "inconclusive"), ((A,), "agree")):
    got = s.judge_all(list(parts))["verdict"]
    check(got == want, "judge_all %s -> %s" % ("+".join(p["verdict"] for p in parts), got))
# RMSE: an error magnitude, lower better, margin 3 % of B's mean
a, b = pair(0.5, 0.05, base=10.0, hib=False)
j = s.judge(a, b, "better", "rmse")
check(j["verdict"] == "agree" and abs(j["margin"] - 0.3 * s.mean(b) / 10.0) < 1e-9,
      "judge rmse: lower is better, margin 3 %% of B's mean (%.4f)" % j["margin"])

# 8. ci_proportion(): Wilson's score interval against scipy.stats.binomtest(...).proportion_ci("wilson"),
# and its coverage on seeded Bernoulli samples at a proportion near the edge (where the normal interval fails)
worst_w = 0.0
for n in (1, 2, 5, 15, 40):
    for k in range(n + 1):
        lo, hi = s.ci_proportion(k, n)
        ref = sp.binomtest(k, n).proportion_ci(confidence_level=0.95, method="wilson")
        worst_w = max(worst_w, abs(lo - ref.low), abs(hi - ref.high))
check(worst_w < 1e-12, "ci_proportion = scipy's Wilson interval (max |diff| %.1e over n 1-40, every k)" % worst_w)
rng = random.Random(7)
cover = 0
for _ in range(2000):
    k = sum(1 for _ in range(15) if rng.random() < 0.2)
    lo, hi = s.ci_proportion(k, 15)
    cover += lo <= 0.2 <= hi
check(0.93 <= cover / 2000.0 <= 0.99, "ci_proportion covers p = 0.2 at n 15 in %.1f %% of 2000 samples" % (
    100.0 * cover / 2000))
check(all(math.isnan(x) for x in s.ci_proportion(0, 0) + s.ci_proportion(3, 2)), "ci_proportion refuses n 0, k > n")

print("test_tdc_stats: %s" % ("all passed" if not fails else "%d FAILED" % fails))
sys.exit(1 if fails else 0)
