#!/usr/bin/env python3
"""A `plait ab` report against a path-traced reference, split by light and
by band of the hair (issue 42: why `chiang` is farther from the path tracer
than Marschner and Kajiya-Kay).

    ab_bands.py MASK.exr THRESHOLD AB_DIR...   (Mitsuba's venv python)

The hair mask is MASK.exr's first channel >= THRESHOLD, split into thirds
of its rows (top, middle, bottom): render.py --coverage on the export of
the same scene with 0.9, or plait's own `--show camera_alpha` (the
`camera_alpha` texture's first channel, hair in front of the opaque depth
— used here with 2.3, so that exp(-2.3) = 0.1 of the light behind passes if
it is an optical depth; the threshold is a choice, say it with the
numbers). Per
AB_DIR (its SCENE-reference.exr and SCENE-VARIANT.exr, linear radiance)
and variant:
  - mean hair luminance ÷ the reference's, over the mask and per third;
  - RMSE over the whole image (as the report's), over the hair mask, and
    over the hair mask after scaling the variant by the one factor that
    fits the reference best there (least squares): what is left when the
    overall brightness is taken out.
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


def main():
    cov = read(sys.argv[1])[..., 0]
    threshold = float(sys.argv[2])
    mask = cov >= threshold
    ys = np.nonzero(mask.any(axis=1))[0]
    cuts = np.linspace(ys.min(), ys.max() + 1, 4).astype(int)
    thirds = [mask & (np.arange(cov.shape[0])[:, None] >= a) & (np.arange(cov.shape[0])[:, None] < b)
              for a, b in zip(cuts[:-1], cuts[1:])]
    print(f"hair mask: {mask.sum()} px ({os.path.basename(sys.argv[1])} >= {threshold}), thirds of rows {cuts.tolist()}")
    print("| run | variant | hair ÷ ref | top | middle | bottom | RMSE image | RMSE hair | RMSE hair, scaled (factor) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for ab in sys.argv[3:]:
        ref_path = glob.glob(os.path.join(ab, "*-reference.exr"))[0]
        scene = os.path.basename(ref_path)[: -len("-reference.exr")]
        ref = read(ref_path)
        ref_l = ref @ LUM
        print(f"| {os.path.basename(ab.rstrip('/'))} | reference | mean hair luminance {ref_l[mask].mean():.4f} | "
              + " | ".join(f"{ref_l[t].mean():.4f}" for t in thirds) + " | | | |")
        for path in sorted(glob.glob(os.path.join(ab, f"{scene}-*.exr"))):
            name = os.path.basename(path)[len(scene) + 1: -len(".exr")]
            if name == "reference":
                continue
            img = read(path)
            lum = img @ LUM
            ratio = lum[mask].mean() / ref_l[mask].mean()
            bands = [lum[t].mean() / ref_l[t].mean() for t in thirds]
            rmse = np.sqrt(((img - ref) ** 2).mean())
            hair = np.sqrt(((img[mask] - ref[mask]) ** 2).mean())
            k = (img[mask] * ref[mask]).sum() / (img[mask] ** 2).sum()
            scaled = np.sqrt(((k * img[mask] - ref[mask]) ** 2).mean())
            print(f"| {os.path.basename(ab.rstrip('/'))} | {name} | {ratio:.3f} | "
                  + " | ".join(f"{b:.3f}" for b in bands)
                  + f" | {rmse:.4f} | {hair:.4f} | {scaled:.4f} ({k:.2f}) |")


if __name__ == "__main__":
    main()
