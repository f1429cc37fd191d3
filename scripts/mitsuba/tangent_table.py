#!/usr/bin/env python3
"""The table of scripts/mitsuba/tangent_check.sh (issue 47's residual).

    tangent_table.py DIR

Per colour and segment count, over the hair mask (Mitsuba's hair coverage
>= 0.9; rows split into thirds of the mask's rows), mean linear luminance
(Rec. 709) ratios:
  plait / Mitsuba d2          plait shadow_opaque=1 ÷ Mitsuba max depth 2
  plait / BSDF@plait tangent  plait unshadowed ÷ Mitsuba's hair BSDF at the
                              same hits, averaged over h, about plait's own
                              shading tangent (direct_probe.py)
  BSDF@plait / BSDF@spline    the same BSDF about plait's tangent ÷ about the
                              B-spline's (Mitsuba's) tangent
  h-average / hit h           that BSDF about the B-spline's tangent averaged
                              over h ÷ at the h of each camera ray's hit
                              (Mitsuba's own unshadowed single scattering)
  shadow plait / Mitsuba      plait shadow_opaque=1 ÷ plait unshadowed, over
                              Mitsuba d2 ÷ Mitsuba unshadowed
  Catmull-Rom / B-spline      Mitsuba d2 with the strands as Catmull-Rom
                              pieces (catmull_rom.py) ÷ as the B-spline
  plait on B-spline x4 / Mitsuba  plait shadow_opaque=1 on the export's
                              B-spline sampled 4 times a segment
                              (resample_curve.py) ÷ Mitsuba d2
The four factors multiply to about the first column (ratios of means over a
region do not multiply exactly).
"""
import os
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
Y = np.array([0.2126, 0.7152, 0.0722])


def lum(d, n):
    return np.array(mi.Bitmap(os.path.join(d, n)), dtype=np.float64)[..., :3] @ Y


def cells(m, num, den):
    ys = np.nonzero(m)[0]
    b = np.quantile(ys, [0, 1 / 3, 2 / 3, 1])
    yy = np.arange(m.shape[0])[:, None]
    thirds = [num[m & (yy >= b[i]) & (yy <= b[i + 1])].mean() / den[m & (yy >= b[i]) & (yy <= b[i + 1])].mean()
              for i in range(3)]
    return f"{num[m].mean() / den[m].mean():.3f} ({' / '.join(f'{t:.3f}' for t in thirds)})"


def main():
    d = sys.argv[1]
    print("colour segments | plait / Mitsuba d2 | plait / BSDF@plait tangent | BSDF@plait / BSDF@spline"
          " | h-average / hit h | shadow plait / Mitsuba | Catmull-Rom / B-spline | plait on B-spline x4 / Mitsuba   (mean (top / mid / bottom third))")
    for segments in (24, 96):
        for c in ("blond", "dark_brown", "black"):
            n = f"{c}_{segments}"
            m = np.array(mi.Bitmap(os.path.join(d, f"{n}_mask.exr")), dtype=np.float64)
            m = (m if m.ndim == 2 else m[..., 0]) >= 0.9
            pl, mt = lum(d, f"{n}_plait.exr"), lum(d, f"{n}_mitsuba_d2.exr")
            pu = lum(d, f"{n}_plait_unshadowed.exr")
            pt = lum(d, f"{n}_probe_plait_tangent_unshadowed.exr")
            sp = lum(d, f"{n}_probe_haverage_unshadowed.exr")
            hit = lum(d, f"{n}_probe_unshadowed.exr")
            # The shadow factor as a ratio of region means, like the others.
            sh = cells(m, pl * hit, pu * mt)
            print(f"{c} {segments} ({m.sum()} px) | {cells(m, pl, mt)} | {cells(m, pu, pt)} | {cells(m, pt, sp)}"
                  f" | {cells(m, sp, hit)} | {sh} | {cells(m, lum(d, f'{n}_cr_mitsuba_d2.exr'), mt)}"
                  f" | {cells(m, lum(d, f'{n}_x4_plait.exr'), mt)}")


if __name__ == "__main__":
    main()
