#!/usr/bin/env python3
"""Writes scenes/sky.hdr: a small procedural sky for the environment light (book 5.3).

    python3 tools/make_sky.py [OUT.hdr] [WIDTH]

An equirectangular (lat-long) map in zraka's convention (environment.hpp): row 0 is the zenith,
column u = phi / 2 pi with phi measured from -z towards +x. The sky is a made-up gradient (deep
blue at the zenith, pale at the horizon, a glow around the sun), a sun disk of radius 1.5 degrees
that holds most of the power, and a dim ground below the horizon. Nothing is downloaded; the
file is a flat (not run-length encoded) Radiance RGBE image, which stb_image reads.
"""
import math
import struct
import sys

SUN_ELEVATION = math.radians(35)
SUN_PHI = math.radians(60)
SUN_RADIUS = math.radians(1.5)
SUN_RADIANCE = (2600.0, 2400.0, 2100.0)


def radiance(theta, phi):
    d = (math.sin(phi) * math.sin(theta), math.cos(theta), -math.cos(phi) * math.sin(theta))
    st = math.pi / 2 - SUN_ELEVATION
    s = (math.sin(SUN_PHI) * math.sin(st), math.cos(st), -math.cos(SUN_PHI) * math.sin(st))
    cos_sun = max(-1.0, min(1.0, sum(a * b for a, b in zip(d, s))))
    angle = math.acos(cos_sun)
    if angle < SUN_RADIUS:
        return SUN_RADIANCE
    up = d[1]
    if up < 0:  # the ground: dim, a little lighter towards the horizon
        g = 0.12 + 0.08 * math.exp(8 * up)
        return (g * 1.1, g, g * 0.85)
    t = 1 - up  # 0 at the zenith, 1 at the horizon
    sky = (0.15 + 0.55 * t ** 3, 0.3 + 0.5 * t ** 3, 0.9 + 0.2 * t ** 3)
    glow = 1.5 * math.exp(-angle / 0.15) + 0.3 * math.exp(-angle / 0.6)
    return tuple(c + glow * w for c, w in zip(sky, (1.0, 0.85, 0.6)))


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return b"\0\0\0\0"
    mant, e = math.frexp(m)  # m = mant * 2^e, mant in [0.5, 1)
    f = mant * 256.0 / m
    return bytes([min(255, int(c[0] * f)), min(255, int(c[1] * f)), min(255, int(c[2] * f)), e + 128])


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/sky.hdr"
    w = int(sys.argv[2]) if len(sys.argv) > 2 else 256
    h = w // 2
    data = bytearray(f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n".encode())
    for j in range(h):
        for i in range(w):
            # The mean over 2 x 2 points of the texel, so that the small sun is not aliased away.
            acc = [0.0, 0.0, 0.0]
            for a in (0.25, 0.75):
                for b in (0.25, 0.75):
                    L = radiance(math.pi * (j + a) / h, 2 * math.pi * (i + b) / w)
                    acc = [x + y / 4 for x, y in zip(acc, L)]
            data += rgbe(acc)
    with open(out, "wb") as f:
        f.write(data)
    print(f"wrote {out}: {w} x {h}, {len(data)} bytes")


if __name__ == "__main__":
    main()
