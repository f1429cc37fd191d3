#!/usr/bin/env python3
"""A `plait ab` report against a path-traced reference, split by light and
by band of the hair (issue 42: why `chiang` is farther from the path tracer
than Marschner and Kajiya-Kay). The shading page's figure `chiang-bands`
(scripts/mitsuba/chiang_bands.sh) prints its table with this.

    ab_bands.py MASK.exr THRESHOLD AB_DIR [DEPTH2_DIR]   (Mitsuba's venv python)

The hair mask is MASK.exr's first channel >= THRESHOLD, split into thirds
of its rows (top, middle, bottom): plait's own `--show camera_alpha` (the
`camera_alpha` texture's first channel, hair in front of the opaque depth
— used with 2.3, so that exp(-2.3) = 0.1 of the light behind passes if it
is an optical depth; the threshold is a choice, say it with the numbers),
or render.py --coverage on the export of the same scene with 0.9. Per
variant of AB_DIR (its SCENE-reference.exr and SCENE-VARIANT.exr, linear
radiance):
  - mean hair luminance ÷ the reference's, over the mask and per third;
  - RMSE over the whole image (as the report's), over the hair mask, and
    over the hair mask after scaling the variant by the one factor that
    fits the reference best there (least squares): what is left when the
    overall brightness is taken out;
  - with DEPTH2_DIR (the same variants against the path tracer at maximum
    depth 2): mean hair luminance ÷ that reference's.
One row per variant, the last Markdown table printed.
"""
import glob
import os
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
LUM = np.array([0.2126, 0.7152, 0.0722])


def read(path):
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


def variants(ab):
    """The reference image and {variant: image path} of one ab directory."""
    refs = glob.glob(os.path.join(ab, "*-reference.exr"))
    if len(refs) != 1:
        sys.exit(f"ab_bands.py: {ab}: expected one *-reference.exr, found {len(refs)}")
    scene = os.path.basename(refs[0])[: -len("-reference.exr")]
    paths = {}
    for path in sorted(glob.glob(os.path.join(ab, f"{scene}-*.exr"))):
        name = os.path.basename(path)[len(scene) + 1: -len(".exr")]
        if name != "reference":
            paths[name] = path
    return read(refs[0]), paths


def thirds_of(mask):
    ys = np.nonzero(mask.any(axis=1))[0]
    cuts = np.linspace(ys.min(), ys.max() + 1, 4).astype(int)
    rows = np.arange(mask.shape[0])[:, None]
    return cuts, [mask & (rows >= a) & (rows < b) for a, b in zip(cuts[:-1], cuts[1:])]


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    mask = read(sys.argv[1])[..., 0] >= float(sys.argv[2])
    cuts, thirds = thirds_of(mask)
    ref, paths = variants(sys.argv[3])
    depth2 = variants(sys.argv[4]) if len(sys.argv) == 5 else None
    ref_l = ref @ LUM
    print(f"hair mask: {mask.sum()} px ({os.path.basename(sys.argv[1])} >= {sys.argv[2]}), "
          f"thirds of rows {cuts.tolist()}; the reference's mean hair luminance "
          f"{ref_l[mask].mean():.4f} (" + ", ".join(f"{ref_l[t].mean():.4f}" for t in thirds) + ")\n")
    head = "| variant | hair ÷ path tracer | top | middle | bottom | RMSE image | RMSE hair | RMSE hair, scaled | factor |"
    print(head + (" hair ÷ depth 2 |" if depth2 else ""))
    print("|---|" + "---:|" * (head.count("|") - 2 + (1 if depth2 else 0)))
    for name, path in paths.items():
        img = read(path)
        lum = img @ LUM
        cells = [lum[mask].mean() / ref_l[mask].mean()]
        cells += [lum[t].mean() / ref_l[t].mean() for t in thirds]
        k = (img[mask] * ref[mask]).sum() / (img[mask] ** 2).sum()
        row = "| " + name + " | " + " | ".join(f"{c:.3f}" for c in cells)
        row += f" | {np.sqrt(((img - ref) ** 2).mean()):.4f}"
        row += f" | {np.sqrt(((img[mask] - ref[mask]) ** 2).mean()):.4f}"
        row += f" | {np.sqrt(((k * img[mask] - ref[mask]) ** 2).mean()):.4f} | {k:.2f} |"
        if depth2:
            ref2, paths2 = depth2
            if name not in paths2:
                sys.exit(f"ab_bands.py: {sys.argv[4]} has no variant `{name}`")
            lum2 = read(paths2[name]) @ LUM
            row += f" {lum2[mask].mean() / (ref2 @ LUM)[mask].mean():.3f} |"
        print(row)


if __name__ == "__main__":
    main()
