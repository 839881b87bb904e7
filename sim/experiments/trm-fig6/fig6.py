"""TRM §4.2, Fig. 6: the retinal image of a moving square after TRM, with D and U in gamma-compressed codes
(TRM's choice, and tdc's: firmware/tdc_trm.h, ref/ref_trm.h) or in linear light, read out in linear
luminance and in Stevens brightness (L^(1/3), the paper's "cubic root ... good predictor of brightness").

One dimension, TRM's equations as ref/ref_trm.h writes them (r = 1/2, D a Gaussian of sigma 2.5 full-res
pixels at the reduced sample centres 2k + 1/2 with taps within 3 sigma and clamp-to-edge, U linear
interpolation between those centres): under pursuit the eye sees the pair's mean in linear light,
P = (clamp(beta_t) + alpha_t+1) / 2 with beta_t = 2 I - lin(U D I) (moving pixels: no residual, TRM §4.2),
alpha_t+1 = lin(U D I) rendered one pixel further (the reduced grid's other phase, as at an odd number of
pixels per frame).  The square's edges are area-sampled at sub-pixel offsets (the contents paired by the
claims)."""
import math

GAMMA = 2.2          # the paper: sRGB's ~2.2 (§4.2); the Vive's measured 2.25 changes nothing here
SIGMA = 2.5          # D's sigma in full-res pixels (the firmware's default, firmware/tdc_trm.h)
N = 96               # pixels of the 1-D frame
LEFT, WIDTH = 36, 24  # the square


def square(phase, lo, hi):
    """Gamma codes in [0, 1] of the square [LEFT + phase, LEFT + WIDTH + phase), area-sampled."""
    a, b = LEFT + phase, LEFT + WIDTH + phase
    out = []
    for i in range(N):
        cover = max(0.0, min(i + 1, b) - max(i, a))
        # area sampling in linear light, then encoded (what a renderer's resolve gives)
        lin = cover * hi ** GAMMA + (1 - cover) * lo ** GAMMA
        out.append(lin ** (1 / GAMMA))
    return out


def down(v, shift):
    """D: reduced samples at full-res centres 2k + 1/2 + shift (Gaussian, taps within 3 sigma, clamp-to-edge)."""
    out = []
    for k in range(N // 2):
        c = 2 * k + 0.5 + shift
        s = w = 0.0
        for i in range(int(math.floor(c - 3 * SIGMA)), int(math.ceil(c + 3 * SIGMA)) + 1):
            if abs(i - c) > 3 * SIGMA:
                continue
            g = math.exp(-0.5 * ((i - c) / SIGMA) ** 2)
            s += g * v[min(max(i, 0), N - 1)]
            w += g
        out.append(s / w)
    return out


def up(red, shift):
    """U: linear interpolation of the reduced samples (centres 2k + 1/2 + shift) at every full-res pixel."""
    out = []
    for i in range(N):
        u = (i - 0.5 - shift) / 2.0
        k0 = int(math.floor(u))
        f = u - k0
        a = red[min(max(k0, 0), len(red) - 1)]
        b = red[min(max(k0 + 1, 0), len(red) - 1)]
        out.append(a + f * (b - a))
    return out


def perceived(codes, space):
    """P in linear light: the pair's mean, D/U in 'gamma' codes or in 'linear' light."""
    lin = [c ** GAMMA for c in codes]
    src = codes if space == "gamma" else lin
    to_lin = (lambda x: max(0.0, x) ** GAMMA) if space == "gamma" else (lambda x: x)
    a_t = [to_lin(x) for x in up(down(src, 0), 0)]      # the low-pass of frame t (beta's compensation)
    a_t1 = [to_lin(x) for x in up(down(src, 1), 1)]     # frame t+1's reduced frame, on the retina
    beta = [min(1.0, max(0.0, 2 * i - a)) for i, a in zip(lin, a_t)]
    return lin, [(b + a) / 2 for b, a in zip(beta, a_t1)]


def artefacts(phase, lo, hi, space, readout):
    """(overshoot, undershoot): the largest excursion of the perceived signal above / below the original's,
    in linear luminance ('luminance', peak = 1) or Stevens brightness L^(1/3) ('brightness')."""
    lin, p = perceived(square(phase, lo, hi), space)
    f = (lambda x: x) if readout == "luminance" else (lambda x: max(0.0, x) ** (1 / 3.0))
    d = [f(q) - f(i) for q, i in zip(p, lin)]
    return max(0.0, max(d)), max(0.0, -min(d))
