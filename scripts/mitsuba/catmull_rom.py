#!/usr/bin/env python3
"""Rewrite an exported scene folder's hair curves as Catmull-Rom segments.

    catmull_rom.py SRC_DIR DST_DIR

`plait export mitsuba` writes each strand as the interpolating cubic
B-spline through plait's points (write.rs). plait draws the polyline; it
used to shade it about its vertex tangents as central differences of the
points (one-sided at the ends), interpolated along each segment — the knot
tangents of the Catmull-Rom spline through the same points, not the
B-spline's (now it shades about the B-spline's directions at the points,
bent inside a segment: direct_probe.plait_tangents). This copies SRC_DIR to DST_DIR with every segment of
hair_K.txt written as its own 4-control-point `bsplinecurve` piece that
traces the Catmull-Rom cubic exactly (the pieces meet with the same position,
tangent and radius), so Mitsuba shades about plait's former tangents at the points
(issue 47's top/bottom residual: scripts/mitsuba/tangent_check.sh). Segment
order, and so Mitsuba's prim_index, is kept. Radii follow the same spline,
clamped at 0.
"""
import os
import shutil
import sys

import numpy as np

# Catmull-Rom (P0..P3, the segment from P1 to P2) to uniform cubic B-spline
# control points of the same cubic: B = inv(M_bspline) · M_catmull_rom · P.
M_CR = 0.5 * np.array([[0, 2, 0, 0], [-1, 0, 1, 0], [2, -5, 4, -1], [-1, 3, -3, 1]], dtype=np.float64)
M_BS = np.array([[1, 4, 1, 0], [-3, 0, 3, 0], [3, -6, 3, 0], [-1, 3, -3, 1]], dtype=np.float64) / 6
TO_BS = np.linalg.solve(M_BS, M_CR)


def strands(path):
    out, cur = [], []
    for line in open(path):
        f = line.split()
        if not f:
            if cur:
                out.append(np.array(cur))
            cur = []
        else:
            cur.append([float(x) for x in f[:4]])
    if cur:
        out.append(np.array(cur))
    return out


def pieces(c):
    """The B-spline control points of `c` (n + 2 rows for n points) → the
    points, then one 4 x 4 piece per segment."""
    p = (c[:-2] + 4 * c[1:-1] + c[2:]) / 6
    ext = np.concatenate([2 * p[:1] - p[1:2], p, 2 * p[-1:] - p[-2:-1]])
    for j in range(len(p) - 1):
        b = TO_BS @ ext[j:j + 4]
        b[:, 3] = np.maximum(b[:, 3], 0.0)
        yield b


def main():
    src, dst = sys.argv[1], sys.argv[2]
    shutil.copytree(src, dst, dirs_exist_ok=True)
    for name in os.listdir(src):
        if name.startswith("hair_") and name.endswith(".txt"):
            lines = []
            for c in strands(os.path.join(src, name)):
                for b in pieces(c):
                    lines += [" ".join(repr(float(x)) for x in row) for row in b] + [""]
            with open(os.path.join(dst, name), "w") as f:
                f.write("\n".join(lines))
    print(f"wrote {dst}: Catmull-Rom pieces")


if __name__ == "__main__":
    main()
