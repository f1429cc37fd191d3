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
  OUT_PREFIX_haverage_shadowed.exr, OUT_PREFIX_haverage_unshadowed.exr
                             at each hair hit the BSDF averaged over the
                             fibre's width (h uniform in [−1, 1]) about the
                             curve's tangent: what plait's shading point
                             computes (shaders/lib/chiang.wgsl)
  OUT_PREFIX_plait_tangent_shadowed.exr, …_plait_tangent_unshadowed.exr
                             the same about plait's shading tangent
                             (plait_tangents: the spline's directions at the
                             points, bent as a Hermite piece); the difference
                             to haverage was issue 47's top/bottom residual
                             while plait interpolated central differences
                             linearly (scripts/mitsuba/tangent_check.sh)
  OUT_PREFIX_coverage.exr    the fraction of each pixel's rays whose first
                             hit is a fibre (as render.py --coverage)
Why the fibre images: at a `linearcurve` hit Mitsuba 3.9.1 leaves dp_du zero
and builds the shading frame from the normal alone, while its hair BSDF takes
local y as the fibre's axis, so each fibre was shaded about an axis that
depends on its normal, not on the strand (scripts/mitsuba/frame_probe.py).
plait now exports `bsplinecurve` (dp_du around the curve: local y is the
curve's tangent); the fibre images rebuild the frame from the curve's own
tangent (si.prim_index and uv into hair_0.txt's control points): y = the
tangent, z = the normal made perpendicular to it. They should now equal
Mitsuba's own, and the printed angle be ~0. Also printed: how far the
B-spline strays from plait's polyline between points, in fibre radii.
Run with the Mitsuba venv's python (scripts/ensure-mitsuba.sh).
"""
import argparse
import json
import os

import drjit as dr
import mitsuba as mi
import numpy as np


def strands(path):
    """Control points (x y z radius) of each strand; blank lines separate them."""
    out, cur = [], []
    for line in open(path):
        f = line.split()
        if not f:
            out.append(np.array(cur))
            cur = []
        else:
            cur.append([float(x) for x in f[:4]])
    out.append(np.array(cur))
    # The export ends each file with a segment of radius 0 (write.rs,
    # `terminator`: a Mitsuba 3.9.1 workaround), no strand of plait's.
    return [c for c in out if len(c) >= 4 and c[:, 3].any()]


def bspline(path):
    """Per segment (bsplinecurve's prim_index order): its four control points
    (segments x 4 x 4). Segment j of a strand uses C[j..j+4]."""
    return np.concatenate([np.stack([c[j:j + 4] for j in range(len(c) - 3)]) for c in strands(path)])


def polyline_tangents(path):
    """Per segment (bspline()'s order): plait's unit vertex tangents at its two
    ends (crates/plait-hair/src/strands.rs: central differences of the points,
    one-sided at a strand's ends; segments x 2 x 3). The points are where the
    B-spline passes at its knots, (C[i] + 4 C[i+1] + C[i+2]) / 6."""
    out = []
    for c in strands(path):
        p = (c[:-2, :3] + 4 * c[1:-1, :3] + c[2:, :3]) / 6
        t = np.concatenate([p[1:2] - p[:1], p[2:] - p[:-2], p[-1:] - p[-2:-1]])
        t /= np.maximum(np.linalg.norm(t, axis=1), 1e-30)[:, None]
        out.append(np.stack([t[:-1], t[1:]], axis=1))
    return np.concatenate(out)


def plait_tangents(path, k, tl):
    """plait's shading tangent at tl along segment k (bspline()'s order; rows
    of k and tl): the unit tangents at the points are the interpolating
    spline's derivative directions there, (C[i+2] − C[i]) / 2
    (crates/plait-hair/src/curve.rs), and inside a segment they bend as the
    cubic Hermite piece whose end derivatives are those tangents times the
    chord's length (shaders/lib/strand_curve.wgsl). polyline_tangents is
    what plait shaded about before: its ends interpolated linearly."""
    rows = []
    for c in strands(path):
        c = c[:, :3]
        p = (c[:-2] + 4 * c[1:-1] + c[2:]) / 6
        t = (c[2:] - c[:-2]) / 2
        t /= np.maximum(np.linalg.norm(t, axis=1), 1e-30)[:, None]
        rows.append(np.stack([p[:-1], p[1:], t[:-1], t[1:]], axis=1))
    p0, p1, t0, t1 = np.moveaxis(np.concatenate(rows)[k], 1, 0)
    chord = p1 - p0
    chord /= np.maximum(np.linalg.norm(chord, axis=1), 1e-30)[:, None]
    u = tl[:, None]
    v = 6 * u * (1 - u) * chord + (1 - u) * (1 - 3 * u) * t0 + u * (3 * u - 2) * t1
    return v / np.maximum(np.linalg.norm(v, axis=1), 1e-30)[:, None]


BASIS = lambda t: np.stack([(1 - t) ** 3, 3 * t**3 - 6 * t**2 + 4, -3 * t**3 + 3 * t**2 + 3 * t + 1, t**3], -1) / 6
DBASIS = lambda t: np.stack([-(1 - t) ** 2, 3 * t**2 - 4 * t, -3 * t**2 + 2 * t + 1, t**2], -1) / 2


def polyline_error(seg):
    """Distance from the B-spline to plait's polyline (the chord between the
    points the curve passes through at its knots), in the curve's radius."""
    t = np.linspace(0.0, 1.0, 17)
    q = np.einsum("tk,skc->stc", BASIS(t), seg)
    a, b = q[:, :1, :3], q[:, -1:, :3]
    ab = b - a
    u = np.clip(np.sum((q[..., :3] - a) * ab, -1) / np.maximum(np.sum(ab * ab, -1), 1e-30), 0, 1)
    d = np.linalg.norm(q[..., :3] - (a + u[..., None] * ab), axis=-1)
    return (d / q[..., 3]).ravel()


def image(mi, np, val, valid, w, h, n, bg):
    rgb = np.array(dr.select(valid, val, mi.Color3f(0.0)))
    rgb = (rgb if rgb.shape[-1] == 3 else rgb.T).reshape(h, w, n, 3).mean(axis=2)
    miss = 1.0 - np.array(mi.Float(dr.select(valid, 1.0, 0.0))).reshape(h, w, n).mean(axis=2)
    return rgb + miss[..., None] * bg


def h_average(bsdf, ctx, t, to_eye, to_light, si, samples=32):
    """The hair BSDF at each hit averaged over the fibre's width, as plait's
    shading point is (shaders/lib/chiang.wgsl: h = sin γ uniform in [−1, 1]):
    the eye and the light keep their angles to the tangent t and their
    relative azimuth φ about it; Mitsuba's hair frame has the tangent as
    local y and h = sin of the eye's azimuth from local z."""
    sin_e, sin_l = dr.dot(to_eye, t), dr.dot(to_light, t)
    e_perp = dr.normalize(to_eye - t * sin_e)
    l_perp = dr.normalize(to_light - t * sin_l)
    phi = dr.atan2(dr.dot(dr.cross(e_perp, l_perp), t), dr.dot(e_perp, l_perp))
    cos_e, cos_l = dr.safe_sqrt(1 - sin_e * sin_e), dr.safe_sqrt(1 - sin_l * sin_l)
    local = mi.SurfaceInteraction3f(si)
    local.sh_frame = mi.Frame3f(mi.Vector3f(1, 0, 0), mi.Vector3f(0, 1, 0), mi.Vector3f(0, 0, 1))
    acc = mi.Color3f(0.0)
    for k in range(samples):
        g = float(np.arcsin((k + 0.5) / samples * 2.0 - 1.0))
        local.wi = mi.Vector3f(cos_e * np.sin(g), sin_e, cos_e * np.cos(g))
        wo = mi.Vector3f(cos_l * dr.sin(g + phi), sin_l, cos_l * dr.cos(g + phi))
        acc += bsdf.eval(ctx, local, wo)
    return acc / samples


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
    # The curve's tangent at each hair hit (others keep Mitsuba's frame).
    seg = bspline(os.path.join(a.scene_dir, "hair_0.txt"))
    err = polyline_error(seg)
    print(f"{a.scene_dir}: B-spline to plait's polyline, in fibre radii: median {np.median(err):.4f}, "
          f"99th percentile {np.percentile(err, 99):.4f}, max {err.max():.4f} ({len(seg)} segments)")
    k = np.minimum(np.array(si.prim_index), len(seg) - 1)
    tl = np.clip(np.array(si.uv.y) * len(seg) - k, 0.0, 1.0)
    tan = np.einsum("nk,nkc->nc", DBASIS(tl), seg[k][..., :3])
    tan /= np.maximum(np.linalg.norm(tan, axis=1), 1e-30)[:, None]
    t = mi.Vector3f(*[mi.Float(tan[:, i]) for i in range(3)])
    # plait's shading tangent at the same place (plait_tangents).
    ptan = plait_tangents(os.path.join(a.scene_dir, "hair_0.txt"), k, tl)
    plait_t = mi.Vector3f(*[mi.Float(ptan[:, i]) for i in range(3)])
    nrm = dr.normalize(si.n - t * dr.dot(si.n, t))
    fibre = mi.SurfaceInteraction3f(si)
    fibre.sh_frame = dr.select(hair, mi.Frame3f(dr.cross(t, nrm), t, nrm), si.sh_frame)
    fibre.wi = fibre.sh_frame.to_local(-ray.d)
    on = np.array(hair)
    # A fibre radius in pixels at the hits: the polyline error above in pixels.
    xfov = np.radians(float(mi.traverse(sensor)["x_fov"][0]))
    px = 2.0 * np.array(si.t)[on] * np.tan(0.5 * xfov) / w
    r_px = seg[k[on], 1, 3] / px
    print(f"{a.scene_dir}: a fibre radius is {np.median(r_px):.4f} px at the median hair hit (max {r_px.max():.4f})")
    cos = np.abs(np.array(dr.dot(si.sh_frame.t, t)))[on]
    angle = np.degrees(np.arccos(np.minimum(cos, 1.0)))
    print(f"{a.scene_dir}: {on.sum()} hair hits; angle between Mitsuba's fibre axis (local y) "
          f"and the curve's tangent: median {np.median(angle):.0f} deg, 90th percentile {np.percentile(angle, 90):.0f} deg")
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
        # plait's shading point: the same fibre's BSDF averaged over h, about
        # the curve's tangent, then about plait's shading tangent (the head and the ground as in Mitsuba's own image).
        own = bsdf.eval(ctx, si, si.to_local(ds.d))
        for tangent, prefix in ((t, "haverage_"), (plait_t, "plait_tangent_")):
            val = dr.select(hair, h_average(bsdf, ctx, tangent, -ray.d, ds.d, si), own) * em
            write(image(mi, np, val, si.is_valid(), w, h, n, bg), prefix + name)


if __name__ == "__main__":
    main()
