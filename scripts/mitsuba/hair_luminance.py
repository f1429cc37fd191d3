"""Mean hair luminance and hair RMSE of a `plait ab` run's variants against
its path-traced reference (issue 43's multiple-scattering claim).

Usage: <mitsuba venv python> scripts/mitsuba/hair_luminance.py REPORT_DIR SCENE...
(the run swept techniques.multiple_scattering=none,karis,dual_scattering on
pipelines/occupancy.toml). Hair pixels: those where karis or dual_scattering
changes the `none` image (both add light on every lit or shadowed strand).
Luminance with Rec. 709 weights, linear radiance (the .exr files).
"""
import glob
import os
import sys

import mitsuba as mi
import numpy as np

mi.set_variant('scalar_rgb')
METHODS = ['none', 'karis', 'dual_scattering']


def load(path):
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


def lum(a):
    return a @ np.array([0.2126, 0.7152, 0.0722])


def main():
    os.chdir(sys.argv[1])
    for scene in sys.argv[2:]:
        ref = load(f'{scene}-reference.exr')
        v = {m: load(glob.glob(f'{scene}-*@{m}.exr')[0]) for m in METHODS}
        mask = (np.abs(lum(v['dual_scattering']) - lum(v['none'])) > 1e-5) | (
            np.abs(lum(v['karis']) - lum(v['none'])) > 1e-5)
        r = lum(ref)[mask].mean()
        cells = ' '.join(
            f"{m}: luminance ×{lum(x)[mask].mean() / r:.3f} RMSE {np.sqrt(((x - ref)[mask] ** 2).mean()):.4f};"
            for m, x in v.items())
        print(f'{scene}: {int(mask.sum())} hair pixels, path-traced mean luminance {r:.5f}; {cells}')


main()
