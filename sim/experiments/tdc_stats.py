"""tdc_stats.py - the statistics every experiment claim goes through.

A tdc figure is the mean over the seeds (or contents) of a run.  A claim
compares two conditions A and B measured on the same seeds/contents
(paired), so the quantity judged is the per-seed difference, oriented so
that positive means "A is better" (A - B for PSNR/SSIM, B - A for error
metrics such as FLIP):

    * its 95 % confidence interval: Student's t on the paired differences
      (ci_t), or a seeded percentile bootstrap (ci_bootstrap) when the
      differences are far from normal;
    * an equivalence margin m per metric (MARGINS): a difference whose
      interval lies inside (-m, +m) is practically zero.

judge() turns the interval and the margin into the verdict of a claim
(TOST-style: the interval against the margin, never a bare p-value):

    paper says           agree / equivalent          disagree                       inconclusive
    "A better than B"    lo > 0                      hi < m (at most a negligible   otherwise
                                                     gain, or A worse)
    "A not worse"        lo > -m                     hi < -m (worse by more than    otherwise
                                                     the margin)
    "A equals B"         -m < lo and hi < m          lo >= m or hi <= -m            otherwise
                         (verdict "equivalent")

With fewer than MIN_SEEDS pairs the verdict is "inconclusive".  A 95 %
interval inside the margin is the two one-sided tests at alpha = 0.025 each
(conservative against the usual 0.05).  docs/experiments.md.
"""
import math
import random
import statistics

MIN_SEEDS = 5
LEVEL = 0.95
BOOT_SEED = 20240615       # the bootstrap's fixed seed: the same data give the same interval
BOOT_RESAMPLES = 4000

# Equivalence margins, per metric column: (kind, value).  "abs" is in the
# metric's own unit; "rel" is a fraction of B's mean (error magnitudes,
# whose scale differs by orders between contents).  Why these values:
#  jod      0.1 JOD: 1 JOD is 75 % of observers preferring one condition, so
#           0.1 JOD is 52.7 % (Phi(0.1 * 0.674)): a coin toss (issue 28).
#  psnr_db  0.25 dB: a 2.9 % change of the RMS error (10^(0.25/20)).
#  flip, terr, flicker, rmse: 3 % of B's mean error - the same
#           relative change of an error's size as 0.25 dB, and a third of
#           the ~10 % contrast increment the eye needs to tell two supra-
#           threshold contrasts apart (Legge & Foley 1980, Fig. 3's dipper
#           at suprathreshold pedestals), so a difference inside it is not
#           one an observer of the error would see.
#  ssim     0.002: SSIM's scale is compressed near 1; 0.002 is ~3 % of the
#           1 - SSIM of our runs (0.05-0.1).
#  saving_pct  2 percentage points of renderer time: the seed-to-seed
#           timing spread on the shared machine (trm-render, 1-3 points).
#  ratio    5 % of B: cost ratios ("3.5x") reported to one decimal.
MARGINS = {
    "jod": ("abs", 0.1),
    "psnr_db": ("abs", 0.25),
    "ssim": ("abs", 0.002),
    "flip": ("rel", 0.03),
    "terr": ("rel", 0.03),
    "flicker": ("rel", 0.03),
    "rmse": ("rel", 0.03),
    # the simulator's former judge, kept as labelled legacy columns (docs/eye.md)
    "legacy_terr": ("rel", 0.03),
    "legacy_flicker": ("rel", 0.03),
    "saving_pct": ("abs", 2.0),
    "ratio": ("rel", 0.05),
}
HIGHER_IS_BETTER = {"jod": True, "psnr_db": True, "ssim": True, "flip": False, "terr": False, "flicker": False, "rmse": False,
                    "legacy_terr": False, "legacy_flicker": False, "saving_pct": True, "ratio": True}
CLAIMS = ("better", "not worse", "equal")


def mean(v):
    return sum(v) / len(v) if v else float("nan")


def spread(v):
    """Sample standard deviation (n - 1); 0 for one value, nan for none."""
    if not v:
        return float("nan")
    if len(v) == 1:
        return 0.0
    m = mean(v)
    return math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1))


def summary(v):
    v = [float(x) for x in v]
    return {"n": len(v), "mean": mean(v), "spread": spread(v)}


# --- Student's t ------------------------------------------------------------
def _betacf(a, b, x):
    """Continued fraction of the regularised incomplete beta (modified Lentz;
    converges for x < (a + 1) / (a + b + 2))."""
    tiny, qab, qap, qam = 1e-300, a + b, a + 1.0, a - 1.0
    c, d = 1.0, 1.0 - qab * x / qap
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 400):
        m2 = 2 * m
        aa = m * (b - m) * x / ((qam + m2) * (a + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        h *= d * c
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        de = d * c
        h *= de
        if abs(de - 1.0) < 1e-15:
            break
    return h


def betainc(a, b, x):
    """Regularised incomplete beta I_x(a, b)."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    lbt = math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log(1.0 - x)
    if x < (a + 1.0) / (a + b + 2.0):
        return math.exp(lbt) * _betacf(a, b, x) / a
    return 1.0 - math.exp(lbt) * _betacf(b, a, 1.0 - x) / b


def t_cdf(t, df):
    """P(T <= t) for Student's t with df degrees of freedom."""
    if t * t < df:  # near 0: 1 - x would be rounded away, use the complement's form
        half = 0.5 * betainc(0.5, df / 2.0, t * t / (df + t * t))
        return 0.5 + half if t > 0 else 0.5 - half
    tail = 0.5 * betainc(df / 2.0, 0.5, df / (df + t * t))
    return 1.0 - tail if t > 0 else tail


def t_ppf(p, df):
    """The p-quantile of Student's t (bisection on t_cdf to 1e-13 relative)."""
    if not 0.0 < p < 1.0:
        raise ValueError("t_ppf: p = %r outside (0, 1)" % p)
    lo, hi = -1.0, 1.0
    while t_cdf(lo, df) > p:
        lo *= 2.0
    while t_cdf(hi, df) < p:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if t_cdf(mid, df) < p:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-13 * max(1.0, abs(mid)):
            break
    return 0.5 * (lo + hi)


# --- intervals of the mean of paired differences ------------------------------
def ci_t(d, level=LEVEL):
    """(lo, hi) of the mean of d: mean +- t_{(1+level)/2, n-1} * sd / sqrt(n)."""
    n = len(d)
    if n < 2:
        return float("nan"), float("nan")
    m, s = mean(d), spread(d)
    h = t_ppf(0.5 + level / 2.0, n - 1) * s / math.sqrt(n)
    return m - h, m + h


def ci_bootstrap(d, level=LEVEL, resamples=BOOT_RESAMPLES, seed=BOOT_SEED):
    """(lo, hi) of the mean of d: percentile bootstrap, seeded (reproducible)."""
    n = len(d)
    if n < 2:
        return float("nan"), float("nan")
    rng = random.Random(seed)
    ms = sorted(sum(d[rng.randrange(n)] for _ in range(n)) / n for _ in range(resamples))
    a = (1.0 - level) / 2.0
    return ms[int(math.floor(a * (resamples - 1)))], ms[int(math.ceil((1.0 - a) * (resamples - 1)))]


def ci_proportion(k, n, level=LEVEL):
    """(lo, hi) of a proportion k / n: Wilson's score interval, which keeps its coverage for small n and
    for k near 0 or n, where the normal approximation does not (for "most contents" counts)."""
    if n < 1 or not 0 <= k <= n:
        return float("nan"), float("nan")
    z = statistics.NormalDist().inv_cdf(0.5 + level / 2.0)
    p = float(k) / n
    c = (p + z * z / (2.0 * n)) / (1.0 + z * z / n)
    h = z / (1.0 + z * z / n) * math.sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n))
    return max(0.0, c - h), min(1.0, c + h)


def margin_of(metric, ref_mean=None):
    """The equivalence margin of metric (absolute), given B's mean for relative margins."""
    if metric not in MARGINS:
        raise ValueError("no equivalence margin for metric '%s' (tdc_stats.MARGINS: %s)" % (metric, ", ".join(MARGINS)))
    kind, v = MARGINS[metric]
    return v if kind == "abs" else v * abs(ref_mean)


def gains(a, b, higher_is_better=True):
    """Per-pair gains of A over B (positive: A better)."""
    a = [float(x) for x in a]
    b = [float(x) for x in b]
    if len(a) != len(b):
        raise ValueError("paired comparison of %d and %d values" % (len(a), len(b)))
    return [(x - y) if higher_is_better else (y - x) for x, y in zip(a, b)]


def judge(a, b, claim, metric, higher_is_better=None, margin=None, method="t"):
    """The verdict on the paper's claim that A is 'better' than / 'not worse'
    than / 'equal' to B, from paired samples a and b (per seed, same order).

    metric names the margin (MARGINS) and the direction (HIGHER_IS_BETTER);
    margin overrides the table (absolute, the metric's unit).  Returns a
    dict: verdict (agree / disagree / equivalent / inconclusive), gain
    (mean of A's per-pair gain over B), lo, hi (its 95 % interval), margin,
    n, method, and why (one line: the interval against the margin)."""
    if claim not in CLAIMS:
        raise ValueError("claim '%s' (one of %s)" % (claim, ", ".join(CLAIMS)))
    hib = HIGHER_IS_BETTER.get(metric, True) if higher_is_better is None else higher_is_better
    g = gains(a, b, hib)
    n = len(g)
    m = margin if margin is not None else margin_of(metric, mean([float(x) for x in b]) if b else float("nan"))
    lo, hi = (ci_bootstrap(g) if method == "bootstrap" else ci_t(g)) if n >= 2 else (float("nan"), float("nan"))
    out = {"gain": mean(g), "lo": lo, "hi": hi, "margin": m, "n": n, "method": method, "claim": claim}
    inside = -m < lo and hi < m
    if n < MIN_SEEDS:
        v = "inconclusive"
        why = "%d pairs (fewer than %d)" % (n, MIN_SEEDS)
    elif claim == "better":
        v = "agree" if lo > 0 else ("disagree" if hi < m else "inconclusive")
        why = {"agree": "A better: interval above 0" + ("; smaller than the margin" if hi < m else ""),
               "disagree": "A not better by the margin: interval below +m",
               "inconclusive": "interval spans 0 and +m"}[v]
    elif claim == "not worse":
        v = "agree" if lo > -m else ("disagree" if hi < -m else "inconclusive")
        why = {"agree": "A not worse: interval above -m", "disagree": "A worse by more than the margin",
               "inconclusive": "interval spans -m"}[v]
    else:
        v = "equivalent" if inside else ("disagree" if lo >= m or hi <= -m else "inconclusive")
        why = {"equivalent": "interval inside ±m", "disagree": "interval outside ±m: a real difference",
               "inconclusive": "interval crosses ±m"}[v]
    out["verdict"] = v
    if n >= 2 and max(g) == min(g) and len({float(x) for x in a}) == 1:
        why += "; the %d pairs are identical (the seed does not vary this content: in effect one pair)" % n
    out["why"] = "%s (gain of A %s, 95 %% CI [%s, %s], margin %s, n %d, %s)" % (
        why, fmt(out["gain"], 4), fmt(lo, 4), fmt(hi, 4), fmt(m, 4), n, "paired t" if method == "t" else "bootstrap")
    return out


def judge_all(results):
    """The verdict of one claim the paper makes on several metrics at once
    ("lower RMSE and higher SSIM"), from each metric's judge() result: the
    claim holds (agree, or equivalent for an 'equal' claim) only when it
    holds in every metric; it is refuted (disagree) when any metric refutes
    it; otherwise inconclusive.  Returns verdict and why (the metrics'
    verdicts in order)."""
    if not results:
        raise ValueError("judge_all: no metric results")
    vs = [j["verdict"] for j in results]
    if "disagree" in vs:
        v = "disagree"
    elif all(x == "equivalent" for x in vs):
        v = "equivalent"
    elif all(x in ("agree", "equivalent") for x in vs):
        v = "agree"
    else:
        v = "inconclusive"
    return {"verdict": v, "verdicts": vs}


def compare(a, b, higher_is_better=True, paired=None):
    """Which of A and B is better, with no margin: 'A beats B' when the 95 %
    interval of A's paired gain is above 0, 'B beats A' when below, else
    'tie' (the interval holds 0); 'too few seeds' under MIN_SEEDS pairs.
    Unpaired samples (lengths differ, or paired=False) use Welch's interval.
    Returns verdict, diff (mean A - mean B), spread (sd of the paired
    differences, or sqrt(sa^2/na + sb^2/nb) * sqrt(n) unpaired), lo, hi
    (of A's gain) and n.  A claim's verdict goes through judge()."""
    a = [float(x) for x in a]
    b = [float(x) for x in b]
    if paired is None:
        paired = len(a) == len(b)
    n = min(len(a), len(b))
    d = mean(a) - mean(b)
    sign = 1.0 if higher_is_better else -1.0
    if paired:
        g = gains(a, b, higher_is_better)
        s = spread([x - y for x, y in zip(a, b)])
        lo, hi = ci_t(g)
    else:
        se2 = (spread(a) ** 2 / len(a) if len(a) > 1 else 0.0) + (spread(b) ** 2 / len(b) if len(b) > 1 else 0.0)
        se = math.sqrt(se2)
        s = se * math.sqrt(n)
        # Welch-Satterthwaite degrees of freedom
        num = se2 * se2
        den = sum((spread(v) ** 2 / len(v)) ** 2 / (len(v) - 1) for v in (a, b) if len(v) > 1)
        df = num / den if den > 0 else max(1, n - 1)
        h = t_ppf(0.5 + LEVEL / 2.0, df) * se if se > 0 else 0.0
        lo, hi = sign * d - h, sign * d + h
    if n < MIN_SEEDS:
        verdict = "too few seeds"
    elif lo > 0:
        verdict = "A beats B"
    elif hi < 0:
        verdict = "B beats A"
    else:
        verdict = "tie"
    return {"verdict": verdict, "diff": d, "spread": s, "lo": lo, "hi": hi, "n": n}


def beats(a, b, higher_is_better=True):
    """True only when A beats B (the 95 % interval of the paired gain above 0)."""
    return compare(a, b, higher_is_better)["verdict"] == "A beats B"


def fmt(x, digits=3):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return ""
    if isinstance(x, str):
        return x
    return "%.*f" % (digits, x)


def fmt_ms(s, digits=3):
    """'mean +- spread' of a summary()."""
    return "%s ± %s" % (fmt(s["mean"], digits), fmt(s["spread"], digits))


def fmt_ci(j, digits=4):
    """'[lo, hi]' of a judge() or compare() result."""
    return "[%s, %s]" % (fmt(j["lo"], digits), fmt(j["hi"], digits))
