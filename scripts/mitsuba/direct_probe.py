#!/usr/bin/env python3
"""Single scattering by hand, to split a plait ÷ Mitsuba difference (issue 47).

    direct_probe.py DIR OUT_PREFIX [--spp N] [--seed S]

DIR is a scene folder of `plait export mitsuba`. Per pixel (box filter:
positions jittered uniformly over the pixel's square, as plait's coverage
integrates), the first camera hit's BSDF times the directional emitter:
  OUT_PREFIX_shadowed.exr    shadow rays tested (any fibre, the head or the
                             ground blocks: Mitsuba's max depth 2; this image
                             equals render.py --max-depth 2 within its noise)
  OUT_PREFIX_unshadowed.exr  nothing casts shadows
  OUT_PREFIX_fibre_shadowed.exr, OUT_PREFIX_fibre_unshadowed.exr
                             the same with the hair BSDF given the strand's
                             own axis (see below)
  OUT_PREFIX_coverage.exr    the fraction of each pixel's rays whose first
                             hit is a fibre (as render.py --coverage)
Why the fibre images: at a `linearcurve` hit this Mitsuba (3.x, as installed
by scripts/ensure-mitsuba.sh) leaves dp_du zero and builds the shading frame
from the normal alone (Frame3f(n): sh_frame.s equals it exactly), while its
hair BSDF takes local y as the fibre's axis (scripts/mitsuba/fibre_probe.py).
So Mitsuba shades each fibre about an axis that depends on its normal, not
on the strand. The fibre images rebuild the frame from the strand's segment
(si.prim_index into hair_0.txt's segments): y = the segment's direction,
z = the normal made perpendicular to it.
Run with the Mitsuba venv's python (scripts/ensure-mitsuba.sh).
"""
import argparse
import json
import os

import drjit as dr
import mitsuba as mi
import numpy as np


def segments(path):
    """Directions of every consecutive point pair of every strand, in the
    order of linearcurve's prim_index (blank lines separate strands)."""
    strands, cur = [], []
    for line in open(path):
        f = line.split()
        if not f:
            strands.append(cur)
            cur = []
        else:
            cur.append([float(x) for x in f[:3]])
    strands.append(cur)
    dirs = [np.diff(np.array(s), axis=0) for s in strands if len(s) > 1]
    d = np.concatenate(dirs)
    return d / np.linalg.norm(d, axis=1)[:, None]


def image(mi, np, val, valid, w, h, n, bg):
    rgb = np.array(dr.select(valid, val, mi.Color3f(0.0)))
    rgb = (rgb if rgb.shape[-1] == 3 else rgb.T).reshape(h, w, n, 3).mean(axis=2)
    miss = 1.0 - np.array(mi.Float(dr.select(valid, 1.0, 0.0))).reshape(h, w, n).mean(axis=2)
    return rgb + miss[..., None] * bg


def main():
    p = argparse.ArgumentParser()
    p.add_argument("scene_dir")
    p.add_argument("prefix")
    p.add_argument("--spp", type=int, default=32)
    p.add_argument("--seed", type=int, default=0)
    a = p.parse_args()
    mi.set_variant("llvm_ad_rgb")
    side = json.load(open(os.path.join(a.scene_dir, "plait.json")))
    bg = np.asarray(side["background"], dtype=np.float64)
    scene = mi.load_file(os.path.join(a.scene_dir, "scene.xml"), spp="1", max_depth="2")
    sensor = scene.sensors()[0]
    w, h = sensor.film().crop_size()
    n = a.spp
    pix = dr.arange(mi.UInt32, w * h * n) // n
    rng = mi.PCG32(size=w * h * n, initstate=a.seed)
    u = (mi.Float(pix % w) + rng.next_float32()) / w
    v = (mi.Float(pix // w) + rng.next_float32()) / h
    ray, _ = sensor.sample_ray(0.0, 0.0, mi.Point2f(u, v), mi.Point2f(0.5, 0.5))
    si = scene.ray_intersect(ray, mi.RayFlags.All, True)
    hair = si.is_valid() & ~si.shape.is_mesh()
    cov = np.array(mi.Float(dr.select(hair, 1.0, 0.0))).reshape(h, w, n).mean(axis=2)
    write = lambda rgb, name: mi.Bitmap(np.ascontiguousarray(rgb, dtype=np.float32)).write(f"{a.prefix}_{name}.exr")
    write(np.repeat(cov[..., None], 3, axis=2), "coverage")
    # The strand's axis at each hair hit (others keep Mitsuba's frame).
    dirs = segments(os.path.join(a.scene_dir, "hair_0.txt"))
    k = np.minimum(np.array(si.prim_index), len(dirs) - 1)
    t = mi.Vector3f(*[mi.Float(dirs[k, i]) for i in range(3)])
    nrm = dr.normalize(si.n - t * dr.dot(si.n, t))
    fibre = mi.SurfaceInteraction3f(si)
    fibre.sh_frame = dr.select(hair, mi.Frame3f(dr.cross(t, nrm), t, nrm), si.sh_frame)
    fibre.wi = fibre.sh_frame.to_local(-ray.d)
    on = np.array(hair)
    cos = np.abs(np.array(dr.dot(si.sh_frame.t, t)))[on]
    angle = np.degrees(np.arccos(np.minimum(cos, 1.0)))
    print(f"{a.scene_dir}: {on.sum()} hair hits; angle between Mitsuba's fibre axis (local y) "
          f"and the strand: median {np.median(angle):.0f} deg, 90th percentile {np.percentile(angle, 90):.0f} deg")
    ctx = mi.BSDFContext()
    bsdf = si.bsdf(ray)
    sample = mi.Point2f(rng.next_float32(), rng.next_float32())
    for vis in (True, False):
        ds, em = scene.sample_emitter_direction(si, sample, vis)
        name = "shadowed" if vis else "unshadowed"
        val = bsdf.eval(ctx, si, si.to_local(ds.d)) * em
        write(image(mi, np, val, si.is_valid(), w, h, n, bg), name)
        val = bsdf.eval(ctx, fibre, fibre.sh_frame.to_local(ds.d)) * em
        write(image(mi, np, val, si.is_valid(), w, h, n, bg), "fibre_" + name)


if __name__ == "__main__":
    main()
