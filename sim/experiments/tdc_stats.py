"""tdc_stats.py - the statistics every experiment claim goes through.

A figure of tdc is the mean over the seeds (or contents) of a run, with its
spread: the sample standard deviation over those seeds.  "A beats B" is
written only when

    * each side has at least MIN_SEEDS values (5), and
    * the difference of the means exceeds the spread of that difference:
      the standard deviation of the per-seed differences when the seeds are
      paired (same seeds on both sides: the usual case, content noise
      cancels), else spread_A + spread_B (unpaired, conservative).

Otherwise the comparison is "tie" (difference within the spread) or
"too few seeds".  docs/experiments.md.
"""
import math

MIN_SEEDS = 5


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


def compare(a, b, higher_is_better=True, paired=None):
    """Compare samples a and b (lists of floats, per seed).

    paired: lists of equal length in the same seed order (default: paired
    when the lengths are equal).  Returns a dict: verdict ('A beats B',
    'B beats A', 'tie', 'too few seeds'), diff (mean A - mean B), spread
    (of that difference) and n."""
    a = [float(x) for x in a]
    b = [float(x) for x in b]
    if paired is None:
        paired = len(a) == len(b)
    n = min(len(a), len(b))
    d = mean(a) - mean(b)
    if paired:
        if len(a) != len(b):
            raise ValueError("paired comparison of %d and %d values" % (len(a), len(b)))
        s = spread([x - y for x, y in zip(a, b)])
    else:
        s = spread(a) + spread(b)
    if n < MIN_SEEDS:
        verdict = "too few seeds"
    elif abs(d) <= s or d == 0.0:
        verdict = "tie"
    else:
        better_a = d > 0 if higher_is_better else d < 0
        verdict = "A beats B" if better_a else "B beats A"
    return {"verdict": verdict, "diff": d, "spread": s, "n": n}


def beats(a, b, higher_is_better=True):
    """True only when A beats B beyond the spread (compare())."""
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
