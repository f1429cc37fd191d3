#!/usr/bin/env python3
"""Where plait's hair light differs from Mitsuba's, by how lit a pixel is (issue 48).

    shadow_bins.py COVERAGE.exr MITSUBA_A.exr MITSUBA_B.exr PLAIT.exr...

COVERAGE is render.py's --coverage of the scene (pixels where every camera
ray meets hair are the ones compared); MITSUBA_A and MITSUBA_B are two
Mitsuba renders of it with different seeds (e.g. render.py --spp 1024
--max-depth 2 --seed 0 and --seed 5); PLAIT are plait renders (each a seed).
Printed: each plait render's mean luminance over the compared pixels as a
ratio to the mean of A and B; then the mean of the plait renders against A
in bins of B's luminance (fifths, the top one split at 95 %). Binning by B
and comparing with A keeps the bins free of A's noise (binning by the image
compared would make its dark bins read low by selection).
Measured (black groom, tests/scenes/ms_black.toml, 160x120, max depth 2,
plait 32 spp seeds 0-5, Mitsuba 1024 spp seeds 0 and 5): 1.008 / 1.028 /
1.033 / 1.031 / 1.055 / 1.042; bins from the darkest 1.123, 1.090, 0.996,
1.010, 1.014, 1.011 (tests/path_traced_gpu.rs' docs).
Run with the Mitsuba venv's python (scripts/ensure-mitsuba.sh).
"""
import sys

import mitsuba as mi
import numpy as np

REC709 = np.array([0.2126, 0.7152, 0.0722])


def luminance(path):
    return np.array(mi.Bitmap(path)).astype(np.float64)[..., :3] @ REC709


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    mi.set_variant("scalar_rgb")
    cov, a_path, b_path, *plait_paths = sys.argv[1:]
    full = np.array(mi.Bitmap(cov))[..., 0] >= 1.0
    a, b = luminance(a_path), luminance(b_path)
    both = 0.5 * (a + b)
    print(f"{full.sum()} fully covered pixels; Mitsuba B / A {b[full].mean() / a[full].mean():.4f}")
    plait = []
    for p in plait_paths:
        img = luminance(p)
        plait.append(img)
        print(f"{p}: plait / Mitsuba {img[full].mean() / both[full].mean():.4f}")
    mean = sum(plait) / len(plait)
    edges = np.quantile(b[full], [0.0, 0.2, 0.4, 0.6, 0.8, 0.95, 1.0])
    for lo, hi in zip(edges[:-1], edges[1:]):
        s = full & (b >= lo) & (b <= hi)
        print(f"  Mitsuba B in [{lo:.4f}, {hi:.4f}]: {s.sum()} pixels, plait / Mitsuba A {mean[s].mean() / a[s].mean():.4f}")


if __name__ == "__main__":
    main()
