#!/usr/bin/env python3
"""Render a scene folder written by `plait export mitsuba` with Mitsuba 3.

    render.py DIR OUT.exr [--spp N] [--max-depth D] [--seed S] [--variant V]
                          [--coverage COV.exr] [--coverage-spp N]
                          [--expect-version X.Y.Z]

OUT.exr: linear radiance (RGB, 32-bit float), the background (plait.json's
radiance) added where camera rays miss: rgb + (1 - alpha) * background, with
Mitsuba's emitters hidden from camera rays so the ambient that lights the scene
need not be the background seen. --max-depth 2 is single scattering (one
scattering event between camera and light, with shadow rays).

COV.exr (RGB, three equal channels): per pixel, the fraction of camera rays (jittered over the pixel's
square, as the box filter integrates) whose first hit is hair, i.e. a curve
shape; head and ground are meshes.

Needs Mitsuba (scripts/ensure-mitsuba.sh; run this with its venv's python and
DRJIT_LIBLLVM_PATH set). Exit 2 with Mitsuba's message on any failure.
"""

import argparse
import json
import os
import sys


def fail(message):
    print(f"error: {message}", file=sys.stderr)
    sys.exit(2)


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene_dir")
    p.add_argument("out")
    p.add_argument("--spp", type=int, default=64)
    p.add_argument("--max-depth", type=int, default=16)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--variant", default="llvm_ad_rgb")
    p.add_argument("--coverage", metavar="COV.exr")
    p.add_argument("--coverage-spp", type=int, default=64)
    p.add_argument("--expect-version", metavar="X.Y.Z",
                   help="fail unless Mitsuba is this version (plait's cache keys on it)")
    a = p.parse_args()
    if a.spp < 1 or a.coverage_spp < 1:
        p.error("--spp and --coverage-spp must be at least 1")
    if a.max_depth < 1 and a.max_depth != -1:
        p.error("--max-depth must be at least 1 (or -1: unbounded)")
    for path in (a.out, a.coverage):
        if path is not None and not path.endswith(".exr"):
            p.error(f"{path}: the output is OpenEXR; name it `….exr`")
    return a


def write_exr(mi, np, array, path):
    """Write float32 channels atomically: a reader never sees half a file."""
    tmp = path + ".part.exr"
    mi.Bitmap(np.ascontiguousarray(array, dtype=np.float32)).write(tmp)
    os.replace(tmp, path)


def hair_coverage(mi, dr, np, scene, n, seed):
    sensor = scene.sensors()[0]
    w, h = sensor.film().crop_size()
    idx = dr.arange(mi.UInt32, w * h * n)
    pix = idx // n
    rng = mi.PCG32(size=w * h * n, initstate=seed)
    u = (mi.Float(pix % w) + rng.next_float32()) / w
    v = (mi.Float(pix // w) + rng.next_float32()) / h
    ray, _ = sensor.sample_ray(0.0, 0.0, mi.Point2f(u, v), mi.Point2f(0.5, 0.5))
    si = scene.ray_intersect(ray)
    hit = si.is_valid() & ~si.shape.is_mesh()
    return np.array(mi.Float(dr.select(hit, 1.0, 0.0))).reshape(h, w, n).mean(axis=2)


def main():
    a = parse_args()
    try:
        import drjit as dr
        import mitsuba as mi
        import numpy as np
    except ImportError as e:
        fail(f"{e}: install Mitsuba with `bash scripts/ensure-mitsuba.sh` and run this with its python")
    if a.expect_version and mi.__version__ != a.expect_version:
        fail(f"Mitsuba {mi.__version__} is installed, plait expects {a.expect_version}: "
             "run `bash scripts/ensure-mitsuba.sh`")
    try:
        with open(os.path.join(a.scene_dir, "plait.json")) as f:
            side = json.load(f)
        mi.set_variant(a.variant)
        scene = mi.load_file(
            os.path.join(a.scene_dir, "scene.xml"),
            spp=str(a.spp),
            max_depth=str(a.max_depth),
            seed=str(a.seed),
        )
        img = np.array(mi.render(scene, seed=a.seed))
        alpha = img[..., 3:4]
        rgb = img[..., :3] + (1.0 - alpha) * np.asarray(side["background"], dtype=np.float32)
        if not np.isfinite(rgb).all():
            fail(f"{a.scene_dir}: Mitsuba's image has {int((~np.isfinite(rgb)).sum())} NaN or Inf values")
        write_exr(mi, np, rgb, a.out)
        if a.coverage:
            cov = hair_coverage(mi, dr, np, scene, a.coverage_spp, a.seed)
            # RGB, each channel the coverage: any EXR reader takes it.
            write_exr(mi, np, np.repeat(cov[..., None], 3, axis=2), a.coverage)
    except (RuntimeError, OSError, ValueError, KeyError) as e:
        fail(f"{a.scene_dir}: mitsuba: {e}")


if __name__ == "__main__":
    main()
