#!/usr/bin/env python3
"""The shading frame Mitsuba builds at curve hits (issues 42, 47).

    frame_probe.py        (Mitsuba's venv python: scripts/ensure-mitsuba.sh)

One straight strand along x, radius 0.05, seen from +z at seven points
across its width, as `linearcurve` (two points) and as `bsplinecurve` (four
collinear control points, the curve from x = -1 to 1). Prints dp_du, the
normal and the frame's axes: Mitsuba's `hair` BSDF takes sh_frame.t (local
y) as the fibre's axis, so it should be (±1, 0, 0). Mitsuba 3.9.1 gives
linearcurve dp_du = 0 and a frame from the normal alone (t perpendicular to
the strand), bsplinecurve dp_du around the curve and t = the strand.
"""
import os
import tempfile

import drjit as dr
import mitsuba as mi
import numpy as np

mi.set_variant("llvm_ad_rgb")
print("mitsuba", mi.__version__)
tmp = tempfile.mkdtemp()
files = {
    "linearcurve": "-1 0 0 0.05\n1 0 0 0.05\n",
    "bsplinecurve": "-3 0 0 0.05\n-1 0 0 0.05\n1 0 0 0.05\n3 0 0 0.05\n",
}
n = 7
o = mi.Point3f(mi.Float(np.linspace(-0.5, 0.5, n)), mi.Float(np.linspace(-0.04, 0.04, n)), mi.Float([5.0] * n))
ray = mi.Ray3f(o, mi.Vector3f(0, 0, -1))
for typ, text in files.items():
    path = os.path.join(tmp, typ + ".txt")
    open(path, "w").write(text)
    si = mi.load_dict({"type": "scene", "c": {"type": typ, "filename": path}}).ray_intersect(ray)
    show = lambda v: np.array(v).T.round(3).tolist()
    print(typ, "hits", np.array(si.is_valid()).tolist())
    print("  dp_du           ", show(si.dp_du))
    print("  n               ", show(si.n))
    print("  sh_frame.s      ", show(si.sh_frame.s))
    print("  sh_frame.t (axis)", show(si.sh_frame.t))
    print("  |t . strand| min", float(np.abs(np.array(si.sh_frame.t)[0]).min().round(4)))
