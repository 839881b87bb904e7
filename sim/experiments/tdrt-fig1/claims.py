"""TDRT §2 / Fig. 1: jittered 1-spp frames fused by the eye, per refresh rate (contents: 5 edge angles)."""
SWEEP = "fig1"
Q_F1 = ("TDRT §2 / Fig. 1: 'Four images, each rendered with one sample per pixel (SPP) from the standard 4× MSAA "
        "pattern, are shown after each other in succession. The higher the display rate, the more we see the combined, "
        "antialiased effect of all four images.'")


def claims(exp):
    rows = exp.rows(SWEEP)
    rates = sorted({r["refresh"] for r in rows}, key=int)
    for col in ("flip", "psnr_db"):
        for hz in rates:
            exp.judge("TDRT Fig. 1", Q_F1, "%s Hz: 4 jittered 1-spp frames better than one centred sample (%s)" % (hz, col),
                      "antialiased", exp.values(rows, col, mode="jitter1", refresh=hz),
                      exp.values(rows, col, mode="full", refresh=hz), "better", col, "jitter1", "1 spp",
                      run="%s/%s refresh=%s" % (exp.group, SWEEP, hz))
        for lo in rates[:-1]:
            hi = rates[-1]
            exp.judge("TDRT Fig. 1", Q_F1, "jittered frames closer to antialiased at %s Hz than at %s Hz (%s)" % (hi, lo, col),
                      "the higher the rate, the more antialiased", exp.values(rows, col, mode="jitter1", refresh=hi),
                      exp.values(rows, col, mode="jitter1", refresh=lo), "better", col, "%s Hz" % hi, "%s Hz" % lo,
                      run="%s/%s" % (exp.group, SWEEP))
