#!/usr/bin/env python3
"""Writes studio.hdr, the 256×128 environment of env.toml: a photo studio
seen from the hair — a warm softbox up on the camera's left, a cool rim light
behind the hair, a dim fill on the right, grey walls over a dark floor.
Radiance RGBE, flat scanlines. Equirectangular as plait reads it: u = 0.5
looks along -z (away from the default camera), u = 0.75 along +x, the top
row is +y. Run from this folder: python3 make_studio_hdr.py"""
import math

W, H = 256, 128


def direction(u, v):
    phi, theta = 2 * math.pi * (u - 0.5), math.pi * v
    return (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))


def light(d, centre, half_width_deg, colour):
    """A soft-edged disc of light around `centre` (a unit vector)."""
    c = sum(a * b for a, b in zip(d, centre))
    angle = math.degrees(math.acos(max(-1.0, min(1.0, c))))
    edge = max(0.0, min(1.0, (half_width_deg - angle) / 3.0 + 0.5))
    return tuple(edge * x for x in colour)


def unit(x, y, z):
    n = math.sqrt(x * x + y * y + z * z)
    return (x / n, y / n, z / n)


SOFTBOX = unit(-0.6, 0.55, 0.6)   # camera-left, above, in front of the hair
RIM = unit(0.1, 0.35, -1.0)       # behind the hair, seen from the camera
FILL = unit(1.0, 0.1, 0.2)        # camera-right


def radiance(d):
    y = d[1]
    if y >= 0:
        wall = (0.10 + 0.06 * y, 0.095 + 0.05 * y, 0.09 + 0.05 * y)
    else:
        wall = (0.035, 0.03, 0.028)
    parts = [
        wall,
        light(d, SOFTBOX, 14.0, (9.0, 7.8, 6.2)),
        light(d, RIM, 8.0, (2.5, 4.0, 7.0)),
        light(d, FILL, 30.0, (0.35, 0.4, 0.5)),
    ]
    return tuple(sum(p[i] for p in parts) for i in range(3))


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return bytes((0, 0, 0, 0))
    e = math.frexp(m)[1]
    scale = 256.0 / (2.0 ** e)
    r, g, b = (min(255, int(x * scale)) for x in c)
    return bytes((r, g, b, e + 128))


def main():
    out = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
    out += f"-Y {H} +X {W}\n".encode()
    for row in range(H):
        for col in range(W):
            px = bytearray(rgbe(radiance(direction((col + 0.5) / W, (row + 0.5) / H))))
            # (1, 1, 1, e) and a leading (2, 2, …) are run-length markers in
            # Radiance's formats: nudge such a texel by one step.
            if px[:3] == b"\x01\x01\x01" or (col == 0 and px[:2] == b"\x02\x02"):
                px[2] += 1
            out += px
    with open("studio.hdr", "wb") as f:
        f.write(out)


if __name__ == "__main__":
    main()
