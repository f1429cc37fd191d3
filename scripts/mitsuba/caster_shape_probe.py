#!/usr/bin/env python3
"""Shadows cast by plait's polyline or by the export's B-spline, inside Mitsuba (issue 48).

    caster_shape_probe.py DIR [SEED] [SPP]

DIR is a scene folder of `plait export mitsuba` (its bsplinecurve runs
through plait's points and bends between them; plait's capsules are the
polyline itself). Writes DIR/hair_lin.txt (plait's points: the B-spline at
its knots, (C[j] + 4 C[j+1] + C[j+2]) / 6) and DIR/scene_lin.xml (the same
scene with a linearcurve through them). Camera hits, the BSDF and the light
are Mitsuba's own B-spline scene's; only the shadow rays' casters change
(the hit segment and its neighbours skipped in both, as
shadow_origin_probe.py's `visible`). Printed: the mean hair light over fully
covered pixels with either casters, their ratio, and the part of hair hits
whose shadow ray is open. The bins printed after it are by the B-spline
image itself, so they carry its noise (for a rough look only).
Measured (black groom, tests/scenes/ms_black.toml at 160x120): polyline ÷
B-spline 0.996 / 1.005 / 1.026 (16 spp, seeds 0-2), 1.017 / 0.987 (64 spp,
seeds 3-4); shadow rays open 0.2-1.0 % more often with the polyline.
Run with the Mitsuba venv's python (scripts/ensure-mitsuba.sh).
"""
import os
import sys

import drjit as dr
import mitsuba as mi
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
mi.set_variant("llvm_ad_rgb")
import shadow_origin_probe as P  # noqa: E402

d = sys.argv[1]
# plait's own points: the B-spline at its knots, (C[j] + 4 C[j+1] + C[j+2]) / 6.
lines = []
for c in P.strands(d + '/hair_0.txt'):
    pts = (c[:-2] + 4 * c[1:-1] + c[2:]) / 6
    lines.append('\n'.join(' '.join(f'{v:.9g}' for v in p) for p in pts))
open(d + '/hair_lin.txt', 'w').write('\n\n'.join(lines) + '\n')
xml = open(d + '/scene.xml').read().replace('type="bsplinecurve"', 'type="linearcurve"').replace('hair_0.txt', 'hair_lin.txt')
open(d + '/scene_lin.xml', 'w').write(xml)
seed = int(sys.argv[2]) if len(sys.argv) > 2 else 0
scene = mi.load_file(d + '/scene.xml', spp='1', max_depth='2')
lin = mi.load_file(d + '/scene_lin.xml', spp='1', max_depth='2')
sensor = scene.sensors()[0]
w, h = sensor.film().crop_size()
n = int(sys.argv[3]) if len(sys.argv) > 3 else 16
pix = dr.arange(mi.UInt32, w * h * n) // n
rng = mi.PCG32(size=w * h * n, initstate=seed)
u = (mi.Float(pix % w) + rng.next_float32()) / w
v = (mi.Float(pix // w) + rng.next_float32()) / h
ray, _ = sensor.sample_ray(0.0, 0.0, mi.Point2f(u, v), mi.Point2f(0.5, 0.5))
si = scene.ray_intersect(ray, mi.RayFlags.All, True)
hair = np.array(si.is_valid() & ~si.shape.is_mesh())
seg, owner = P.segments(d + '/hair_0.txt')
nseg = len(seg)
k = np.minimum(np.array(si.prim_index).astype(np.int64), nseg - 1)
ds, em = scene.sample_emitter_direction(si, mi.Point2f(0.5, 0.5), False)
val = np.array(si.bsdf(ray).eval(mi.BSDFContext(), si, si.to_local(ds.d)) * em)
val = val.T if val.shape[0] == 3 and val.shape[-1] != 3 else val
lum = (val @ np.array([0.2126, 0.7152, 0.0722])) * hair
own = np.where(hair, k, -1)
sp = si.spawn_ray(ds.d)
bs = P.visible(scene, sp.o, ds.d, own, owner, nseg)
li = P.visible(lin, sp.o, ds.d, own, owner, nseg)
cov = hair.reshape(h, w, n).mean(axis=2)
full = (cov >= 1.0).ravel()
ib = (lum * bs).reshape(h, w, n).mean(axis=2).ravel()
il = (lum * li).reshape(h, w, n).mean(axis=2).ravel()
print(f'seed {seed}: {full.sum()} px; B-spline casters {ib[full].mean():.5f}, polyline casters {il[full].mean():.5f}, ratio {il[full].mean() / ib[full].mean():.4f}; shadow rays open {bs[hair].mean():.4f} vs {li[hair].mean():.4f}')
q = np.quantile(ib[full], [0, .2, .4, .6, .8, 1])
for lo, hi in zip(q[:-1], q[1:]):
    s = full & (ib >= lo) & (ib <= hi)
    print(f'  B-spline-shadowed in [{lo:.4f},{hi:.4f}]: polyline/B-spline {il[s].mean() / ib[s].mean():.4f}')
