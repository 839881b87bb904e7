"""Figures and tables of the papers with no experiment here, each with the reason (no sweep: rows only).

"not reproducible": nothing here can run it.  Unclassed "inconclusive":
could be run, not built yet (the work left is named)."""

ROWS = [
    ("TRM §7.1 Fig. 13", "§7.1: 'frames compressed with JPEG XS bpp=7 and encoded with TRM with a reduction factor of "
     "0.5 required only about 4.5 bpp'", "JPEG XS bandwidth with TRM", "≈ 4.5 bpp at r = 0.5 (XS bpp = 7)",
     "not reproducible", "JPEG XS (ISO/IEC 21122) has no encoder in Debian 12 and the standard's reference software "
     "is not freely licensed; the lossless column needs the same sequences, which the paper does not publish"),
]


def claims(exp):
    for paper, quote, claim, pv, cls, why in ROWS:
        exp.claim(paper, claim, pv, "-", "inconclusive", why, run="(not run)", quote=quote, cls=cls)
