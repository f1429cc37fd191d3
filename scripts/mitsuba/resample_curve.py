#!/usr/bin/env python3
"""plait given the curve Mitsuba renders: the export's B-spline, sampled finer.

    resample_curve.py DIR SCENE.toml OUT K

DIR is SCENE.toml's export (`plait export mitsuba`). Writes OUT.usda: every
strand of DIR/hair_0.txt (the interpolating B-spline through plait's points,
write.rs) sampled K times per segment, as linear BasisCurves with widths
twice the spline's radius, the hair group's colour (plait.json) and opacity
1; and OUT.toml: SCENE.toml with its `[hair.procedural]` table replaced by
`[hair] file = "OUT.usda"`. plait rendering OUT.toml draws (nearly) the
curve Mitsuba draws for SCENE.toml, so plait ÷ Mitsuba on it has no
interpolation term left (issue 47: scripts/mitsuba/tangent_check.sh).
One hair group only (the check's scenes have one).
"""
import json
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import direct_probe  # noqa: E402


def sampled(path, k):
    t = np.arange(k) / k
    for c in direct_probe.strands(path):
        segs = np.stack([c[j:j + 4] for j in range(len(c) - 3)])
        q = np.einsum("tk,skc->stc", direct_probe.BASIS(t), segs).reshape(-1, 4)
        yield np.concatenate([q, direct_probe.BASIS(np.array([1.0])) @ segs[-1]])


def usda(strands, colour):
    p = np.concatenate([s[:, :3] for s in strands])
    w = np.concatenate([2.0 * s[:, 3] for s in strands])
    n = len(p)
    col = "({}, {}, {})".format(*map(float, colour))
    vertex = ' (\n        interpolation = "vertex"\n    )\n'
    return (
        '#usda 1.0\n(\n    metersPerUnit = 1.0\n    upAxis = "Y"\n)\n'
        'def BasisCurves "Strands"\n{\n    uniform token type = "linear"\n    uniform token wrap = "nonperiodic"\n'
        f'    int[] curveVertexCounts = [{", ".join(str(len(s)) for s in strands)}]\n'
        '    point3f[] points = [' + ", ".join(f"({float(a)!r}, {float(b)!r}, {float(c)!r})" for a, b, c in p) + ']\n'
        '    float[] widths = [' + ", ".join(repr(float(x)) for x in w) + ']' + vertex
        + '    color3f[] primvars:displayColor = [' + ", ".join([col] * n) + ']' + vertex
        + '    float[] primvars:displayOpacity = [' + ", ".join(["1.0"] * n) + ']' + vertex + '}\n'
    )


def main():
    src, scene, out, k = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    groups = json.load(open(os.path.join(src, "plait.json")))["hair_groups"]
    if len(groups) != 1:
        sys.exit(f"error: {src}: {len(groups)} hair groups; resample_curve.py takes one")
    strands = list(sampled(os.path.join(src, "hair_0.txt"), k))
    with open(out + ".usda", "w") as f:
        f.write(usda(strands, groups[0]["color"]))
    text, n = re.subn(r"\[hair\.procedural\].*?\n\n",
                      f'[hair]\nfile = "{os.path.basename(out)}.usda"\n\n', open(scene).read(), flags=re.S)
    if n != 1:
        sys.exit(f"error: {scene}: no [hair.procedural] table followed by a blank line")
    with open(out + ".toml", "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()
