#!/usr/bin/env python3
"""How far plait's shading tangent is from the curves through its points.

    tangent_angles.py DIR

DIR is an export of `plait export mitsuba`. Per segment, at 0, ¼ and ½ of
the way along it: the angle between plait's tangent — as it was (its vertex
tangents, central differences of the points, interpolated linearly and
normalized; direct_probe.polyline_tangents) and as it is (the spline's
directions at the points bent as a Hermite piece; direct_probe.
plait_tangents) — and the tangent of the export's
interpolating B-spline, and of the Catmull-Rom spline (catmull_rom.py)
through the same points; and how far a segment turns (the angle between its
two vertex tangents). Median and 90th percentile over all segments.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import catmull_rom  # noqa: E402
import direct_probe  # noqa: E402


def angles(a, b):
    return np.degrees(np.arccos(np.clip((a * b).sum(1), -1.0, 1.0)))


def unit(v):
    return v / np.maximum(np.linalg.norm(v, axis=1), 1e-30)[:, None]


def main():
    path = os.path.join(sys.argv[1], "hair_0.txt")
    ends = direct_probe.polyline_tangents(path)
    curves = {
        "B-spline": direct_probe.bspline(path),
        "Catmull-Rom": np.array([b for c in direct_probe.strands(path) for b in catmull_rom.pieces(c)]),
    }
    turn = angles(ends[:, 0], ends[:, 1])
    print(f"{sys.argv[1]}: {len(ends)} segments; a segment turns by median {np.median(turn):.1f}°, "
          f"90th percentile {np.percentile(turn, 90):.1f}°")
    k = np.arange(len(ends))
    for t in (0.0, 0.25, 0.5):
        shaded = {
            "linear (before)": unit(ends[:, 0] * (1 - t) + ends[:, 1] * t),
            "curve (now)": direct_probe.plait_tangents(path, k, np.full(len(k), t)),
        }
        for label, plait in shaded.items():
            cells = []
            for name, seg in curves.items():
                tan = unit(np.einsum("nk,nkc->nc", direct_probe.DBASIS(np.full(len(seg), t)), seg[..., :3]))
                a = angles(tan, plait)
                cells.append(f"{name} median {np.median(a):.2f}°, 90th percentile {np.percentile(a, 90):.2f}°, max {a.max():.2f}°")
            print(f"  at {t:.2f} along: plait's {label} tangent to the " + "; to the ".join(cells))


if __name__ == "__main__":
    main()
