#!/usr/bin/env python3
"""On which side of the mirror direction Mitsuba 3's hair BSDF puts the R
lobe, through a real curve (issue 42).

    tilt_side.py        (Mitsuba's venv python: scripts/ensure-mitsuba.sh)

One straight `bsplinecurve` strand along +x whose control points are
written root first (x = -3, -1, 1, 3: the order plait's export writes a
strand, root to tip). Rays from eye directions at θo (in the plane of the
strand and the light, 30° round the fibre from the light's azimuth) hit
the strand at 33 offsets across its width; the hit's own shading frame and
the `hair` BSDF (σ_a 10⁴: only R survives) give f·cos towards a directional
light at θi. θ is signed towards the last control point (the tip). The
printed shift is θo + θi at the peak over θo (parabolic refinement), and
its move from the untilted lobe's (scale_tilt 0: d'Eon's M_p and Fresnel
make even that peak sit off the mirror direction): < 0 towards the root.

Mitsuba 3.9.1 moves the peak by +9.8° at scale_tilt +4 and -13.3° at -4: a positive scale_tilt puts R on the
tip's side of a curve written root first, so plait's export hands Mitsuba
-α (crates/plait/src/mitsuba/write.rs) for a cuticle whose scales point to
the tip (R towards the root, Marschner et al. 2003).
"""
import os
import tempfile

import drjit as dr
import mitsuba as mi
import numpy as np

mi.set_variant("llvm_ad_rgb")
tmp = tempfile.mkdtemp()
path = os.path.join(tmp, "strand.txt")
with open(path, "w") as f:
    f.write("-3 0 0 0.05\n-1 0 0 0.05\n1 0 0 0.05\n3 0 0 0.05\n")
scene = mi.load_dict({"type": "scene", "c": {"type": "bsplinecurve", "filename": path}})
THETA_I = 30.0
AZIMUTH = np.radians(30.0)


def direction(theta, phi):
    return np.array([np.sin(theta), np.cos(theta) * np.cos(phi), np.cos(theta) * np.sin(phi)])


def r_lobe(tilt, thetas):
    """Mean f·cos over the strand's width, per eye angle in `thetas`."""
    bsdf = mi.load_dict({"type": "hair", "scale_tilt": tilt, "sigma_a": mi.ScalarColor3f(1e4, 1e4, 1e4)})
    to_light = direction(np.radians(THETA_I), 0.0)
    offsets = np.linspace(-0.049, 0.049, 33)
    origins, dirs = [], []
    for theta in thetas:
        to_eye = direction(theta, AZIMUTH)
        # Offsets across the strand: perpendicular to the strand and the eye.
        side = np.cross(to_eye, [1.0, 0.0, 0.0])
        side /= np.linalg.norm(side)
        origins += [5.0 * to_eye + o * side for o in offsets]
        dirs += [-to_eye] * len(offsets)
    origins, dirs = np.array(origins), np.array(dirs)
    ray = mi.Ray3f(mi.Point3f(*map(mi.Float, origins.T)), mi.Vector3f(*map(mi.Float, dirs.T)))
    si = scene.ray_intersect(ray)
    assert np.all(np.array(si.is_valid())), "a ray missed the strand"
    assert np.allclose(np.array(si.sh_frame.t)[0], 1.0, atol=1e-3), "the frame's axis is not +x"
    light = mi.Vector3f(*[mi.Float(np.full(len(origins), c)) for c in to_light])
    value = np.array(bsdf.eval(mi.BSDFContext(), si, si.to_local(light))[0])
    return value.reshape(len(thetas), len(offsets)).mean(axis=1)


def peak_shift(tilt):
    thetas = np.radians(np.linspace(-60.0, 20.0, 321))
    values = r_lobe(tilt, thetas)
    j = int(np.argmax(values))
    a, b, c = values[j - 1], values[j], values[j + 1]
    frac = 0.5 * (a - c) / (a - 2 * b + c)
    step = thetas[1] - thetas[0]
    return np.degrees(thetas[j] + frac * step) + THETA_I


print(f"mitsuba {mi.__version__}: bsplinecurve along +x written root (x = -3) to tip (x = +3); "
      f"light at theta_i {THETA_I} deg towards the tip; R alone (sigma_a 1e4)")
base = peak_shift(0.0)
print(f"scale_tilt +0.0: R peak at theta_o + theta_i = {base:+.2f} deg (the untilted lobe's own asymmetry)")
for tilt in (-4.0, 4.0):
    s = peak_shift(tilt)
    side = "tip" if s > base else "root"
    print(f"scale_tilt {tilt:+.1f}: R peak at theta_o + theta_i = {s:+.2f} deg, {s - base:+.2f} from the untilted lobe: "
          f"towards the {side}")
