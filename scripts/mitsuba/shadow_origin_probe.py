#!/usr/bin/env python3
"""Where a fibre's shadow ray starts, inside Mitsuba's own scene (issue 48).

    shadow_origin_probe.py DIR [--spp N] [--seed S]

DIR is a scene folder of `plait export mitsuba`. At max depth 2 plait's path
tracer read ~0.93 of Mitsuba's mean hair light over fully covered pixels.
plait starts a fibre's shadow ray at the camera ray's closest approach to
the segment's axis (inside the fibre) and skips the hit segment and its two
neighbours; Mitsuba starts it on the tube's surface. This probe keeps
Mitsuba's geometry, BSDF and hit and changes only the shadow ray's origin,
so geometry cannot differ. Per camera hit on hair, the directional light's
single scattering (BSDF × irradiance, as Mitsuba's max depth 2 adds it)
with the shadow ray from:
  surface  Mitsuba's own (scene.sample_emitter_direction, tested)
  surface_skip  the surface point, the hit segment and its neighbours on the
           same strand skipped (whether Mitsuba's tube shadows itself)
  axis_skip  plait's: the camera ray's closest approach to the curve's
           centreline, the same segments skipped
  none     nothing casts shadows
Printed: each one's mean luminance over pixels every camera ray of which
meets hair (the test's mask), and its ratio to `surface`.
Measured (issue 48's groom, 160x120, 16 spp, seeds 0-2): axis_skip ÷
surface 0.996-0.998 on blond (0.979 in one 8-spp run), 0.996-1.010 on
black; surface_skip 1.000
(Mitsuba's tube does not shadow its own hit).
Run with the Mitsuba venv's python (scripts/ensure-mitsuba.sh).
"""
import argparse
import os
import sys

import drjit as dr
import mitsuba as mi
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def strands(path):
    """Control points (x y z radius) per strand, as direct_probe.strands."""
    out, cur = [], []
    for line in open(path):
        f = line.split()
        if not f:
            out.append(np.array(cur))
            cur = []
        else:
            cur.append([float(x) for x in f[:4]])
    out.append(np.array(cur))
    return [c for c in out if len(c) >= 4 and c[:, 3].any()]


def segments(path):
    """Per bsplinecurve segment: its four control points and its strand."""
    seg, owner = [], []
    for s, c in enumerate(strands(path)):
        for j in range(len(c) - 3):
            seg.append(c[j:j + 4])
            owner.append(s)
    return np.stack(seg), np.array(owner)


def basis(t):
    return np.stack([(1 - t) ** 3, 3 * t**3 - 6 * t**2 + 4, -3 * t**3 + 3 * t**2 + 3 * t + 1, t**3], -1) / 6


def dbasis(t):
    return np.stack([-(1 - t) ** 2, 3 * t**2 - 4 * t, -3 * t**2 + 2 * t + 1, t**2], -1) / 2


def vec(a):
    return mi.Vector3f(*[mi.Float(np.ascontiguousarray(a[:, i])) for i in range(3)])


def visible(scene, origin, d, own, owner, nseg, rounds=6):
    """Whether the ray from `origin` along `d` escapes, hits of the same
    strand's segments own-1..own+1 passed through (own < 0: none skipped)."""
    o = origin
    open_ = np.ones(len(own), dtype=bool)
    for _ in range(rounds):
        si = scene.ray_intersect(mi.Ray3f(o, d), mi.RayFlags.Minimal, False)
        hit = np.array(si.is_valid())
        mesh = np.array(si.shape.is_mesh()) & hit
        k = np.minimum(np.array(si.prim_index).astype(np.int64), nseg - 1)
        same = hit & ~mesh & (own >= 0) & (owner[k] == owner[np.maximum(own, 0)]) & (np.abs(k - own) <= 1)
        open_ &= ~(hit & ~same)
        if not same.any():
            break
        # Past the skipped hit (a hair's width is ~1e-3 here).
        t = np.where(same, np.array(si.t) + 1e-5, 0.0)
        o = o + d * mi.Float(t)
        keep = same
        if not keep.any():
            break
    return open_


def main():
    p = argparse.ArgumentParser()
    p.add_argument("scene_dir")
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--save", metavar="PREFIX", help="also write PREFIX_{variant}.npy (luminance, h×w) and PREFIX_coverage.npy")
    a = p.parse_args()
    mi.set_variant("llvm_ad_rgb")
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
    hair = np.array(si.is_valid() & ~si.shape.is_mesh())
    seg, owner = segments(os.path.join(a.scene_dir, "hair_0.txt"))
    nseg = len(seg)
    k = np.minimum(np.array(si.prim_index).astype(np.int64), nseg - 1)
    tl = np.clip(np.array(si.uv.y) * nseg - k, 0.0, 1.0)
    centre = np.einsum("nk,nkc->nc", basis(tl), seg[k][..., :3])
    tan = np.einsum("nk,nkc->nc", dbasis(tl), seg[k][..., :3])
    tan /= np.maximum(np.linalg.norm(tan, axis=1), 1e-30)[:, None]
    # The camera ray's closest approach to the centreline's tangent line.
    o = np.array(ray.o).reshape(-1, 3) if np.array(ray.o).shape[0] != 3 else np.array(ray.o).T
    d = np.array(ray.d).reshape(-1, 3) if np.array(ray.d).shape[0] != 3 else np.array(ray.d).T
    wv = o - centre
    dt = np.sum(d * tan, 1)
    t_axis = (dt * np.sum(tan * wv, 1) - np.sum(d * wv, 1)) / np.maximum(1 - dt * dt, 1e-8)
    axis_point = o + t_axis[:, None] * d
    ds, em = scene.sample_emitter_direction(si, mi.Point2f(0.5, 0.5), False)
    bsdf = si.bsdf(ray)
    val = bsdf.eval(mi.BSDFContext(), si, si.to_local(ds.d)) * em
    val = np.array(val)
    val = val.T if val.shape[0] == 3 and val.shape[-1] != 3 else val
    lum = (val @ np.array([0.2126, 0.7152, 0.0722])) * hair
    ds_vis, _ = scene.sample_emitter_direction(si, mi.Point2f(0.5, 0.5), True)
    surface_open = np.array(ds_vis.pdf) > 0
    own = np.where(hair, k, -1)
    sp = si.spawn_ray(ds.d)
    skip_surface = visible(scene, sp.o, ds.d, own, owner, nseg)
    skip_axis = visible(scene, vec(axis_point), ds.d, own, owner, nseg)
    cov = hair.reshape(h, w, n).mean(axis=2)
    full = (cov >= 1.0).ravel()
    if a.save:
        np.save(f"{a.save}_coverage.npy", cov)
    print(f"{a.scene_dir}: {full.sum()} fully covered pixels, {n} spp")
    means = {}
    for name, open_ in (("surface", surface_open), ("surface_skip", skip_surface),
                        ("axis_skip", skip_axis), ("none", np.ones_like(hair))):
        img = (lum * open_).reshape(h, w, n).mean(axis=2).ravel()
        means[name] = img[full].mean()
        if a.save:
            np.save(f"{a.save}_{name}.npy", img.reshape(h, w))
        print(f"  {name:13s} mean {means[name]:.5f}  ÷ surface {means[name] / means['surface']:.4f}")


if __name__ == "__main__":
    main()
