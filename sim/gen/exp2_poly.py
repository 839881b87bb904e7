#!/usr/bin/python3
"""Generate the Q30 coefficients of the quintic 2^-g, g in [0,1), used by
tdc_exp_neg_q16() in firmware/tdc_math.c.  Chebyshev fit (near-minimax),
printed as C initialisers.  Run: /usr/bin/python3 sim/gen/exp2_poly.py"""
import numpy as np
g = np.linspace(0.0, 1.0, 200001)
f = 2.0 ** (-g)
p = np.polynomial.chebyshev.Chebyshev.fit(g, f, 5).convert(kind=np.polynomial.Polynomial)
c = [int(round(x * (1 << 30))) for x in p.coef]
# force exact end point 2^-0 = 1 so exp(0) is exactly 1.0
c[0] = 1 << 30
print("max fit error %.3g" % np.max(np.abs(np.polyval([x / (1 << 30) for x in c][::-1], g) - f)))
print("static const int32_t k_exp2_poly_q30[6] = {" + ", ".join(str(x) for x in c) + "};")
