#!/usr/bin/env python3
"""tdc_retina_flicker.py DUMP [HZ]: per stream of a tdc-sim --dump, the mean
luminance, the amplitude of the HZ component (default refresh / 2) of the
field-mean luminance and the mean per-pixel amplitude at HZ, from
S/retina.y4m (docs/eye.md).  Full-field flicker shows in both amplitudes;
flicker that alternates between neighbouring pixels only in the second."""
import json
import math
import struct
import sys


def frames(path, w, h, scale):
    b = open(path, "rb").read()
    hl = b.index(b"\n") + 1
    n = (len(b) - hl) // (6 + 2 * w * h)
    fl = 6 + 2 * w * h
    return [[v * scale / 65535.0 for v in struct.unpack("<%dH" % (w * h), b[hl + k * fl + 6:hl + (k + 1) * fl])]
            for k in range(n)]


def amplitude(x, hz, fps):
    re = sum(v * math.cos(2 * math.pi * hz * k / fps) for k, v in enumerate(x))
    im = sum(v * math.sin(2 * math.pi * hz * k / fps) for k, v in enumerate(x))
    return 2.0 * math.hypot(re, im) / len(x)


def main():
    d = sys.argv[1]
    j = json.load(open(d + "/dump.json"))
    hz = float(sys.argv[2]) if len(sys.argv) > 2 else j["refresh_hz"] / 2.0
    w, h, fps, scale = j["width"], j["height"], j["fps"], j["linear"]["full_scale_cdm2"]
    print("| stream | mean cd/m^2 | %g Hz amplitude of the field mean | mean per-pixel %g Hz amplitude |" % (hz, hz))
    print("| --- | ---: | ---: | ---: |")
    for s in j["streams"]:
        f = frames("%s/%s/retina.y4m" % (d, s), w, h, scale)
        mean = [sum(x) / len(x) for x in f]
        px = [amplitude([fr[i] for fr in f], hz, fps) for i in range(0, w * h, 37)]
        print("| %s | %.2f | %.2f | %.2f |" % (s, sum(mean) / len(mean), amplitude(mean, hz, fps), sum(px) / len(px)))


if __name__ == "__main__":
    main()
