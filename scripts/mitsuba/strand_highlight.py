#!/usr/bin/env python3
"""Where along one straight strand the highlights sit (issue 42).

    strand_highlight.py IMAGE.exr...   (Mitsuba's venv python, for its EXR reader)

The scene is scripts/mitsuba/one_strand.toml: one strand along +x, root at
x = -2 (its first point), tip at x = +2, at z = 0; the camera at (0, 0, 4)
with a 45° vertical field of view; a directional light in the strand's
normal plane (θi = 0). A pixel column at world x sees the eye at
θo = asin(-x / |(x, 0, -4)|), θ signed towards the tip, so a lobe peaking
at θo + θi = s lights the strand at x = -4 tan s: a lobe towards the root
(s < 0) shines on the tip's half of the image, one towards the tip on the
root's half. Per image: the strand's brightness per column (summed over the
rows it covers) smoothed by a 21-column box (a path-traced strand of ~1 px
is noisy column by column), and its largest value as column, world x and
θo + θi, with the columns where it stays above 90 % of that.
"""
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
DISTANCE, FOV_Y = 4.0, 45.0


def profile(path):
    image = np.array(mi.Bitmap(path))[..., :3].astype(np.float64)
    lum = image @ np.array([0.2126, 0.7152, 0.0722])
    rows = lum.sum(axis=1)
    centre = int(np.argmax(rows))
    band = lum[max(0, centre - 3):centre + 4].sum(axis=0)
    return band, image.shape[1], image.shape[0]


def world_x(column, width, height):
    half_h = DISTANCE * np.tan(np.radians(FOV_Y / 2))
    half_w = half_h * width / height
    return ((column + 0.5) / width * 2 - 1) * half_w


def main():
    for path in sys.argv[1:]:
        band, width, height = profile(path)
        smooth = np.convolve(band, np.ones(21) / 21, mode="same")
        c = int(np.argmax(smooth))
        x = world_x(c, width, height)
        shift = np.degrees(np.arcsin(-x / np.hypot(x, DISTANCE)))
        high = np.nonzero(smooth >= 0.9 * smooth[c])[0]
        said = [f"peak at column {c} (x {x:+.2f}, θo+θi {shift:+.1f}°), above 90 % over columns "
                f"{high.min()}–{high.max()} (x {world_x(high.min(), width, height):+.2f} to "
                f"{world_x(high.max(), width, height):+.2f})"]
        print(f"{path}: " + "; ".join(said))


if __name__ == "__main__":
    main()
