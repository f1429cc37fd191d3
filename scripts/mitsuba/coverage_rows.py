#!/usr/bin/env python3
"""plait's hair coverage against Mitsuba's, by bands of 10 image rows.

    coverage_rows.py PLAIT.exr MITSUBA_COVERAGE.exr

plait writes no alpha, so its coverage is read from a render of the scene
with the head and the ground removed, the light's intensity 0, no ambient
and a white background (`background.color = [1, 1, 1]`): every pixel is
then the background seen through the hair, 1 − α (any exact transparency
technique, e.g. --set techniques.transparency=linked_list
--set techniques.self_shadow=none). MITSUBA_COVERAGE.exr is render.py
--coverage on the export of the same scene (the fraction of camera rays
whose first hit is a fibre). Printed per band: Σα plait ÷ Σ Mitsuba, and
over the pixels Mitsuba covers at least 0.9 (the hair mask of compare.py),
the mean α of each.
"""
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
pl = 1 - np.array(mi.Bitmap(sys.argv[1]), dtype=np.float64)[..., 0]
mt = np.array(mi.Bitmap(sys.argv[2]), dtype=np.float64)[..., 0]
print(f"Σα plait {pl.sum():.1f} px, Mitsuba {mt.sum():.1f} px, ratio {pl.sum() / mt.sum():.3f}")
rows = np.arange(pl.shape[0])[:, None] * np.ones((1, pl.shape[1]))
for y0 in range(0, pl.shape[0], 10):
    band = (rows >= y0) & (rows < y0 + 10)
    mask = band & (mt >= 0.9)
    if mt[band].sum() == 0:
        continue
    line = f"rows {y0:3}-{y0 + 9:3}: Σα ratio {pl[band].sum() / mt[band].sum():.3f}"
    if mask.any():
        line += f"; mask {mask.sum():4} px, mean α plait {pl[mask].mean():.3f} Mitsuba {mt[mask].mean():.3f}"
    print(line)
