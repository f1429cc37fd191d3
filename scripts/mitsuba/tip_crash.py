#!/usr/bin/env python3
"""Minimal reproducer of a Mitsuba 3.9.1 crash plait's export works around
(crates/plait/src/mitsuba/write.rs, `terminator`).

    tip_crash.py [--variant llvm_ad_rgb]

A `bsplinecurve` file of 6,000 one-segment strands, the last one in view of
a camera looking at its tip from the side. A hit near the end of the file's
last segment makes `bsplinecurve`'s global parameter v = (segment + u) /
segments round to 1.0 in f32, and its partials() then reads the segment
index at floor(v * segments) = segments, one past the end. Each case runs in
its own process (a segfault ends it):

  no terminator, Dr.Jit debug mode: "out-of-bounds read from position 6000
      in an array of size 6000"
  no terminator:                    the read goes past the buffer: what
      lies there decides whether it segfaults (here 1 run in 2 or so; the
      built-in scene at 512 spp, every time) or shades with garbage
  a radius-0 segment appended:      no out-of-bounds read, renders

Needs Mitsuba's python (scripts/ensure-mitsuba.sh) and DRJIT_LIBLLVM_PATH.
"""

import os
import subprocess
import sys
import tempfile

CASE = r"""
import sys, drjit as dr, mitsuba as mi, numpy as np
path, variant, debug = sys.argv[1], sys.argv[2], sys.argv[3] == "1"
mi.set_variant(variant)
if debug:
    dr.set_flag(dr.JitFlag.Debug, True)
scene = mi.load_dict({
    "type": "scene",
    "integrator": {"type": "path", "max_depth": 4},
    "sensor": {"type": "perspective", "fov": 3,
               "to_world": mi.ScalarTransform4f().look_at(origin=[0, 4, 3], target=[0, 0, 1], up=[0, 1, 0]),
               "film": {"type": "hdrfilm", "width": 16, "height": 16}},
    "light": {"type": "constant"},
    "hair": {"type": "bsplinecurve", "filename": path,
             "bsdf": {"type": "hair", "sigma_a": {"type": "rgb", "value": [5, 5, 5]}}},
})
img = np.array(mi.render(scene, spp=16))[..., 0]
print(f"rendered: mean {img.mean():.6f}, hair in {(img < 0.9).mean():.4f} of the pixels")
"""


def strand(x, r=0.05):
    # Four control points: one segment, from z = 0 to z = 1 (its tip).
    return "\n".join(f"{x} 0 {z} {r}" for z in (-1, 0, 1, 2))


def main():
    variant = sys.argv[sys.argv.index("--variant") + 1] if "--variant" in sys.argv else "llvm_ad_rgb"
    with tempfile.TemporaryDirectory() as tmp:
        strands = [strand(100 + i) for i in range(5999)] + [strand(0)]
        bare = os.path.join(tmp, "bare.txt")
        fixed = os.path.join(tmp, "terminated.txt")
        open(bare, "w").write("\n\n".join(strands) + "\n")
        open(fixed, "w").write("\n\n".join(strands + ["\n".join(["0 0 1 0"] * 4)]) + "\n")
        for name, path, debug in [("no terminator, debug mode", bare, "1"),
                                  ("no terminator, debug mode off", bare, "0"),
                                  ("radius-0 segment appended, debug mode", fixed, "1"),
                                  ("radius-0 segment appended, debug mode off", fixed, "0")]:
            r = subprocess.run([sys.executable, "-c", CASE, path, variant, debug],
                               capture_output=True, text=True)
            said = [l for l in (r.stdout + r.stderr).splitlines()
                    if "out-of-bounds read" in l or l.startswith("rendered")]
            status = f"exit {r.returncode}" if r.returncode >= 0 else f"killed by signal {-r.returncode}"
            print(f"{name}: {status}; " + "; ".join(said))


if __name__ == "__main__":
    main()
