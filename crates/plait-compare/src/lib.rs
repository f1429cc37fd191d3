//! Image error metrics, difference heat maps and hand-drawn SVG plots for
//! plait's A/B reports (`plait ab`).
//!
//! # Conventions
//! SSIM and FLIP compare the **RGB channels of the displayed 8-bit sRGB
//! images** (after exposure and tone mapping; alpha is ignored), values
//! normalized to `0..=1` by dividing by 255: what a viewer sees in the PNG,
//! and what both metrics were designed for. RMSE, PSNR and the difference
//! map compare the **linear radiance** (the pipelines' float `radiance`, as
//! saved in the .exr files) when both images have one ([`compare_linear`],
//! [`ErrorSpace::LinearRadiance`]): a difference in light, not in how a tone
//! curve displays it. Without linear images they fall back to the displayed
//! values ([`ErrorSpace::Displayed`]); [`Metrics::error_space`] says which.
//!
//! - [`rmse`]: root mean square error over every pixel and R, G, B channel.
//! - [`psnr`]: `10·log10(1 / MSE)` dB with peak 1; `None` (infinite) for identical images.
//! - [`ssim`]: mean SSIM of Wang, Bovik, Sheikh & Simoncelli 2004 on **luma**
//!   (`Y = 0.299 R + 0.587 G + 0.114 B`, as MATLAB's `rgb2gray` used by the
//!   authors' reference code), **11×11 Gaussian window, σ = 1.5**, `K1 = 0.01`,
//!   `K2 = 0.03`, `L = 1`, over the "valid" windows (no padding, no
//!   downsampling). Images smaller than 11 pixels use a window as large as
//!   the image allows (odd size, same σ).
//! - [`flip`]: NVIDIA's LDR-ꟻLIP through the `nv-flip` crate (the reference
//!   C++ implementation), at 67 pixels per degree (the FLIP default: a 0.7 m
//!   viewing distance from a 24" 4K monitor); the mean of the error map is
//!   the single number the FLIP authors recommend.
//!
//! [`heatmap`] turns a per-pixel error into a PNG-ready image with the magma
//! color scale of FLIP and a legend bar; [`plot`] draws SVG charts; [`report`]
//! is the data model of `report.json` and its HTML rendering; [`temporal`]
//! measures flicker over animated sequences against the reference's own change.

pub mod heatmap;
pub mod linear;
pub mod plot;
pub mod report;
pub mod temporal;

use image::{Rgba32FImage, RgbaImage};

pub use linear::{mse_linear, rmse_linear};

/// Why two images could not be compared.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CompareError {
    #[error("images differ in size: {a_w}x{a_h} vs {b_w}x{b_h}")]
    SizeMismatch {
        a_w: u32,
        a_h: u32,
        b_w: u32,
        b_h: u32,
    },
    #[error("empty image")]
    Empty,
    #[error("a sequence of {variant} frames cannot be compared with one of {reference}")]
    FrameCount { variant: usize, reference: usize },
}

/// Two images of one size, not empty: what every metric compares (8-bit
/// displayed images and linear radiance alike).
pub(crate) fn check<P: image::Pixel>(
    a: &image::ImageBuffer<P, Vec<P::Subpixel>>,
    b: &image::ImageBuffer<P, Vec<P::Subpixel>>,
) -> Result<(), CompareError> {
    if a.dimensions() != b.dimensions() {
        return Err(CompareError::SizeMismatch {
            a_w: a.width(),
            a_h: a.height(),
            b_w: b.width(),
            b_h: b.height(),
        });
    }
    if a.width() == 0 || a.height() == 0 {
        return Err(CompareError::Empty);
    }
    Ok(())
}

/// Mean squared error over R, G, B (values in 0..1).
pub fn mse(a: &RgbaImage, b: &RgbaImage) -> Result<f64, CompareError> {
    check(a, b)?;
    let mut sum = 0.0f64;
    for (pa, pb) in a.pixels().zip(b.pixels()) {
        for c in 0..3 {
            let d = (pa.0[c] as f64 - pb.0[c] as f64) / 255.0;
            sum += d * d;
        }
    }
    Ok(sum / (a.width() as f64 * a.height() as f64 * 3.0))
}

/// Root mean squared error over R, G, B (values in 0..1).
pub fn rmse(a: &RgbaImage, b: &RgbaImage) -> Result<f64, CompareError> {
    Ok(mse(a, b)?.sqrt())
}

/// Peak signal-to-noise ratio in dB with peak value 1; `None` when the images
/// are identical (infinite PSNR).
pub fn psnr(a: &RgbaImage, b: &RgbaImage) -> Result<Option<f64>, CompareError> {
    let m = mse(a, b)?;
    Ok(if m == 0.0 {
        None
    } else {
        Some(-10.0 * m.log10())
    })
}

/// Luma in 0..1 (Rec. 601 weights, as MATLAB's `rgb2gray`).
pub fn luma(img: &RgbaImage) -> Vec<f64> {
    img.pixels()
        .map(|p| (0.299 * p.0[0] as f64 + 0.587 * p.0[1] as f64 + 0.114 * p.0[2] as f64) / 255.0)
        .collect()
}

/// SSIM constants (Wang et al. 2004): `K1`, `K2`, dynamic range `L`.
pub const SSIM_K1: f64 = 0.01;
pub const SSIM_K2: f64 = 0.03;
/// Gaussian window: 11×11 taps, σ = 1.5.
pub const SSIM_WINDOW: usize = 11;
pub const SSIM_SIGMA: f64 = 1.5;

/// Normalized 1-D Gaussian taps (the 2-D window is their outer product).
pub fn gaussian_taps(size: usize, sigma: f64) -> Vec<f64> {
    let c = (size as f64 - 1.0) / 2.0;
    let t: Vec<f64> = (0..size)
        .map(|i| (-((i as f64 - c).powi(2)) / (2.0 * sigma * sigma)).exp())
        .collect();
    let s: f64 = t.iter().sum();
    t.into_iter().map(|v| v / s).collect()
}

/// Mean SSIM of two luma planes (`w × h`, values 0..1); see the crate docs.
pub fn ssim_planes(x: &[f64], y: &[f64], w: usize, h: usize) -> f64 {
    let mut size = SSIM_WINDOW.min(w).min(h);
    if size.is_multiple_of(2) {
        size -= 1;
    }
    let size = size.max(1);
    let taps = gaussian_taps(size, SSIM_SIGMA);
    let c1 = (SSIM_K1 * 1.0).powi(2);
    let c2 = (SSIM_K2 * 1.0).powi(2);
    // Separable filtering, "valid" region: horizontal pass then vertical.
    let ow = w - size + 1;
    let oh = h - size + 1;
    let filter = |src: &[f64]| -> Vec<f64> {
        let mut tmp = vec![0.0; ow * h];
        for r in 0..h {
            for c in 0..ow {
                let mut s = 0.0;
                for (k, t) in taps.iter().enumerate() {
                    s += t * src[r * w + c + k];
                }
                tmp[r * ow + c] = s;
            }
        }
        let mut out = vec![0.0; ow * oh];
        for r in 0..oh {
            for c in 0..ow {
                let mut s = 0.0;
                for (k, t) in taps.iter().enumerate() {
                    s += t * tmp[(r + k) * ow + c];
                }
                out[r * ow + c] = s;
            }
        }
        out
    };
    let xx: Vec<f64> = x.iter().map(|v| v * v).collect();
    let yy: Vec<f64> = y.iter().map(|v| v * v).collect();
    let xy: Vec<f64> = x.iter().zip(y).map(|(a, b)| a * b).collect();
    let (mx, my) = (filter(x), filter(y));
    let (sxx, syy, sxy) = (filter(&xx), filter(&yy), filter(&xy));
    let mut total = 0.0;
    for i in 0..ow * oh {
        let (ux, uy) = (mx[i], my[i]);
        let vx = sxx[i] - ux * ux;
        let vy = syy[i] - uy * uy;
        let cov = sxy[i] - ux * uy;
        total +=
            ((2.0 * ux * uy + c1) * (2.0 * cov + c2)) / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
    }
    total / (ow * oh) as f64
}

/// Mean SSIM on luma (Gaussian 11×11, σ 1.5; see the crate docs). 1 for identical images.
pub fn ssim(a: &RgbaImage, b: &RgbaImage) -> Result<f64, CompareError> {
    check(a, b)?;
    Ok(ssim_planes(
        &luma(a),
        &luma(b),
        a.width() as usize,
        a.height() as usize,
    ))
}

/// FLIP's default viewing condition (pixels per degree of visual angle).
pub const FLIP_PIXELS_PER_DEGREE: f32 = 67.0;

/// The LDR-ꟻLIP error map (one value in 0..1 per pixel, row-major) and its mean.
#[derive(Clone, Debug)]
pub struct FlipResult {
    pub map: Vec<f32>,
    pub mean: f64,
}

/// LDR-ꟻLIP of `test` against `reference` (nv-flip, sRGB input, 67 ppd).
pub fn flip(reference: &RgbaImage, test: &RgbaImage) -> Result<FlipResult, CompareError> {
    check(reference, test)?;
    let rgb = |img: &RgbaImage| -> Vec<u8> {
        img.pixels()
            .flat_map(|p| [p.0[0], p.0[1], p.0[2]])
            .collect()
    };
    let (w, h) = reference.dimensions();
    let r = nv_flip::FlipImageRgb8::with_data(w, h, &rgb(reference));
    let t = nv_flip::FlipImageRgb8::with_data(w, h, &rgb(test));
    let map = nv_flip::flip(r, t, FLIP_PIXELS_PER_DEGREE);
    let values = map.to_vec();
    // A plain mean (FlipPool's equals it up to its histogram binning).
    let mean = values.iter().map(|&v| v as f64).sum::<f64>() / values.len() as f64;
    Ok(FlipResult { map: values, mean })
}

/// What RMSE, PSNR and the difference map were computed on.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorSpace {
    /// The displayed 8-bit sRGB values, 0..1.
    #[default]
    Displayed,
    /// Linear radiance before exposure and tone mapping (unbounded).
    LinearRadiance,
}

impl ErrorSpace {
    /// How a report names it.
    pub fn words(self) -> &'static str {
        match self {
            ErrorSpace::Displayed => "displayed sRGB 0..1",
            ErrorSpace::LinearRadiance => "linear radiance",
        }
    }
}

/// Every metric of one image against a reference.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Metrics {
    /// In [`Metrics::error_space`].
    pub rmse: f64,
    /// dB, peak 1 (in [`Metrics::error_space`]); `null` when the images are
    /// identical (infinite).
    pub psnr_db: Option<f64>,
    pub ssim: f64,
    /// Mean of the LDR-ꟻLIP error map.
    pub flip_mean: f64,
    /// Largest per-pixel mean |RGB difference| (in [`Metrics::error_space`]),
    /// the scale of the difference heat map.
    pub max_abs_diff: f64,
    /// What RMSE, PSNR and the difference map compare; SSIM and FLIP always
    /// compare the displayed images.
    pub error_space: ErrorSpace,
}

/// Metrics plus the per-pixel maps behind the heat maps.
#[derive(Clone, Debug)]
pub struct Comparison {
    pub metrics: Metrics,
    /// Mean |RGB difference| per pixel, row-major (in the metrics' error space).
    pub abs_diff: Vec<f32>,
    pub flip_map: Vec<f32>,
    pub width: u32,
    pub height: u32,
}

/// Compare `test` with `reference`: every metric and both per-pixel maps,
/// all on the displayed images.
pub fn compare(reference: &RgbaImage, test: &RgbaImage) -> Result<Comparison, CompareError> {
    compare_linear(reference, test, None)
}

/// [`compare`], with RMSE, PSNR and the difference map on the linear
/// radiance `linear` = (reference's, test's) when given (see the crate docs).
pub fn compare_linear(
    reference: &RgbaImage,
    test: &RgbaImage,
    linear: Option<(&Rgba32FImage, &Rgba32FImage)>,
) -> Result<Comparison, CompareError> {
    check(reference, test)?;
    let (m, abs_diff, error_space) = match linear {
        Some((r, t)) => {
            check(r, t)?;
            if r.dimensions() != reference.dimensions() {
                return Err(CompareError::SizeMismatch {
                    a_w: r.width(),
                    a_h: r.height(),
                    b_w: reference.width(),
                    b_h: reference.height(),
                });
            }
            let diff = r
                .pixels()
                .zip(t.pixels())
                .map(|(a, b)| (0..3).map(|c| (a.0[c] - b.0[c]).abs()).sum::<f32>() / 3.0);
            (
                mse_linear(r, t)?,
                diff.collect(),
                ErrorSpace::LinearRadiance,
            )
        }
        None => {
            let diff = reference.pixels().zip(test.pixels()).map(|(a, b)| {
                (0..3)
                    .map(|c| (a.0[c] as f32 - b.0[c] as f32).abs())
                    .sum::<f32>()
                    / (3.0 * 255.0)
            });
            (
                mse(reference, test)?,
                diff.collect::<Vec<f32>>(),
                ErrorSpace::Displayed,
            )
        }
    };
    let f = flip(reference, test)?;
    let metrics = Metrics {
        rmse: m.sqrt(),
        psnr_db: if m == 0.0 {
            None
        } else {
            Some(-10.0 * m.log10())
        },
        ssim: ssim(reference, test)?,
        flip_mean: f.mean,
        max_abs_diff: abs_diff.iter().fold(0.0f32, |a, &b| a.max(b)) as f64,
        error_space,
    };
    Ok(Comparison {
        metrics,
        abs_diff,
        flip_map: f.map,
        width: reference.width(),
        height: reference.height(),
    })
}

/// Median and spread of a sample.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Stats {
    pub median: f64,
    pub min: f64,
    pub max: f64,
    /// First and third quartiles (linear interpolation between order statistics).
    pub q1: f64,
    pub q3: f64,
    pub samples: Vec<f64>,
}

impl Stats {
    /// `None` for an empty sample.
    pub fn of(samples: &[f64]) -> Option<Stats> {
        if samples.is_empty() {
            return None;
        }
        let mut s = samples.to_vec();
        s.sort_by(|a, b| a.total_cmp(b));
        let q = |p: f64| {
            let pos = p * (s.len() - 1) as f64;
            let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
            s[lo] + (s[hi] - s[lo]) * (pos - lo as f64)
        };
        Some(Stats {
            median: q(0.5),
            min: s[0],
            max: s[s.len() - 1],
            q1: q(0.25),
            q3: q(0.75),
            samples: samples.to_vec(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solid(w: u32, h: u32, rgb: [u8; 3]) -> RgbaImage {
        RgbaImage::from_pixel(w, h, image::Rgba([rgb[0], rgb[1], rgb[2], 255]))
    }

    fn noise(w: u32, h: u32, seed: u32) -> RgbaImage {
        let mut s = seed.wrapping_mul(2654435761).wrapping_add(1);
        RgbaImage::from_fn(w, h, |_, _| {
            let mut next = || {
                s ^= s << 13;
                s ^= s >> 17;
                s ^= s << 5;
                (s >> 24) as u8
            };
            image::Rgba([next(), next(), next(), 255])
        })
    }

    #[test]
    fn rmse_psnr_known_values() {
        let black = solid(8, 8, [0, 0, 0]);
        let white = solid(8, 8, [255, 255, 255]);
        assert_eq!(rmse(&black, &black).unwrap(), 0.0);
        assert_eq!(psnr(&black, &black).unwrap(), None);
        assert!((rmse(&black, &white).unwrap() - 1.0).abs() < 1e-12);
        assert!(psnr(&black, &white).unwrap().unwrap().abs() < 1e-12);
        // One channel off by 51/255 = 0.2 everywhere: MSE = 0.04 / 3.
        let a = solid(4, 4, [100, 100, 100]);
        let b = solid(4, 4, [151, 100, 100]);
        let want_mse: f64 = 0.04 / 3.0;
        assert!((rmse(&a, &b).unwrap() - want_mse.sqrt()).abs() < 1e-12);
        // PSNR = 10 log10(1/MSE) = 10 log10(75) = 18.7506 dB.
        assert!((psnr(&a, &b).unwrap().unwrap() - 18.750_612_633_917).abs() < 1e-9);
        // Half the pixels black vs white: MSE 0.5, PSNR 3.0103 dB.
        let half = RgbaImage::from_fn(4, 4, |x, _| {
            if x < 2 {
                image::Rgba([255; 4])
            } else {
                image::Rgba([0, 0, 0, 255])
            }
        });
        assert!(
            (psnr(&solid(4, 4, [0, 0, 0]), &half).unwrap().unwrap() - 3.010_299_956_64).abs()
                < 1e-9
        );
    }

    #[test]
    fn alpha_is_ignored_and_sizes_checked() {
        let a = solid(3, 3, [10, 20, 30]);
        let mut b = a.clone();
        b.pixels_mut().for_each(|p| p.0[3] = 0);
        assert_eq!(rmse(&a, &b).unwrap(), 0.0);
        assert!(matches!(
            rmse(&a, &solid(2, 3, [0; 3])),
            Err(CompareError::SizeMismatch { .. })
        ));
    }

    #[test]
    fn gaussian_window_is_normalized_and_symmetric() {
        let t = gaussian_taps(11, 1.5);
        assert!((t.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        assert!((t[0] - t[10]).abs() < 1e-15);
        // Centre tap of the normalized 11-tap σ=1.5 Gaussian: 1/Σexp(-k²/4.5), k=-5..5.
        let norm: f64 = (-5..=5).map(|k: i32| (-(k * k) as f64 / 4.5).exp()).sum();
        assert!((t[5] - 1.0 / norm).abs() < 1e-12);
    }

    #[test]
    fn ssim_identical_is_one() {
        let a = noise(32, 24, 7);
        assert!((ssim(&a, &a).unwrap() - 1.0).abs() < 1e-12);
        let s = solid(16, 16, [40, 80, 120]);
        assert!((ssim(&s, &s).unwrap() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn ssim_of_constant_images_is_the_luminance_term() {
        // Constant images: σx = σy = σxy = 0, so SSIM = (2ab + C1) / (a² + b² + C1) exactly.
        let a = solid(16, 16, [51, 51, 51]); // luma 0.2
        let b = solid(16, 16, [153, 153, 153]); // luma 0.6
        let (x, y) = (0.2f64, 0.6f64);
        let c1 = 0.0001;
        let want = (2.0 * x * y + c1) / (x * x + y * y + c1);
        assert!(
            (ssim(&a, &b).unwrap() - want).abs() < 1e-9,
            "{} vs {want}",
            ssim(&a, &b).unwrap()
        );
        // Black vs white: C1 / (1 + C1).
        let k = ssim(&solid(12, 12, [0; 3]), &solid(12, 12, [255; 3])).unwrap();
        assert!((k - c1 / (1.0 + c1)).abs() < 1e-12);
    }

    /// SSIM straight from the definition: every window, weights and sums in
    /// f64, no separable filtering — an independent implementation.
    fn ssim_brute(x: &[f64], y: &[f64], w: usize, h: usize) -> f64 {
        let n = 11;
        let t = gaussian_taps(n, 1.5);
        let (c1, c2) = (0.0001, 0.0009);
        let mut total = 0.0;
        let mut count = 0;
        for r in 0..=h - n {
            for c in 0..=w - n {
                let (mut ux, mut uy) = (0.0, 0.0);
                for i in 0..n {
                    for j in 0..n {
                        let wgt = t[i] * t[j];
                        ux += wgt * x[(r + i) * w + c + j];
                        uy += wgt * y[(r + i) * w + c + j];
                    }
                }
                let (mut vx, mut vy, mut cov) = (0.0, 0.0, 0.0);
                for i in 0..n {
                    for j in 0..n {
                        let wgt = t[i] * t[j];
                        let dx = x[(r + i) * w + c + j] - ux;
                        let dy = y[(r + i) * w + c + j] - uy;
                        vx += wgt * dx * dx;
                        vy += wgt * dy * dy;
                        cov += wgt * dx * dy;
                    }
                }
                total += ((2.0 * ux * uy + c1) * (2.0 * cov + c2))
                    / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
                count += 1;
            }
        }
        total / count as f64
    }

    #[test]
    fn ssim_matches_a_direct_implementation() {
        let a = noise(24, 20, 1);
        let b = noise(24, 20, 2);
        let (la, lb) = (luma(&a), luma(&b));
        let fast = ssim(&a, &b).unwrap();
        let slow = ssim_brute(&la, &lb, 24, 20);
        assert!((fast - slow).abs() < 1e-9, "{fast} vs {slow}");
        // Uncorrelated noise is far from 1; symmetric in its arguments.
        assert!(fast < 0.2);
        assert!((ssim(&b, &a).unwrap() - fast).abs() < 1e-12);
    }

    #[test]
    fn ssim_of_inverted_image_follows_the_closed_form() {
        // y = 1 - x: μy = 1 - μx, σy = σx, σxy = -σx², so each window's
        // structure term is (C2 - 2σ²)/(C2 + 2σ²) < 0 for a textured image:
        // SSIM must be negative, and agree with the direct implementation.
        let a = noise(16, 16, 5);
        let b = RgbaImage::from_fn(16, 16, |x, y| {
            let p = a.get_pixel(x, y).0;
            image::Rgba([255 - p[0], 255 - p[1], 255 - p[2], 255])
        });
        let s = ssim(&a, &b).unwrap();
        assert!(s < 0.0, "{s}");
        assert!((s - ssim_brute(&luma(&a), &luma(&b), 16, 16)).abs() < 1e-9);
    }

    #[test]
    fn small_images_use_a_smaller_window() {
        let a = noise(5, 4, 3);
        assert!((ssim(&a, &a).unwrap() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn flip_identical_is_zero_and_black_white_is_large() {
        let a = noise(32, 32, 9);
        let f = flip(&a, &a).unwrap();
        assert_eq!(f.map.len(), 32 * 32);
        assert!(f.mean.abs() < 1e-6, "{}", f.mean);
        let k = flip(&solid(32, 32, [0; 3]), &solid(32, 32, [255; 3])).unwrap();
        // FLIP's color pipeline maps the largest perceptual difference
        // (black vs white is close to it) near 1.
        assert!(k.mean > 0.9 && k.mean <= 1.0, "{}", k.mean);
        let small = flip(&solid(32, 32, [100; 3]), &solid(32, 32, [104; 3])).unwrap();
        assert!(small.mean > 0.0 && small.mean < k.mean);
    }

    #[test]
    fn compare_collects_everything() {
        let a = noise(16, 12, 4);
        let c = compare(&a, &a).unwrap();
        assert_eq!(c.metrics.rmse, 0.0);
        assert_eq!(c.metrics.psnr_db, None);
        assert!((c.metrics.ssim - 1.0).abs() < 1e-12);
        assert_eq!(c.metrics.max_abs_diff, 0.0);
        assert_eq!(c.abs_diff.len(), 16 * 12);
    }

    #[test]
    fn stats_quartiles() {
        let s = Stats::of(&[5.0, 1.0, 3.0, 2.0, 4.0]).unwrap();
        assert_eq!(
            (s.min, s.q1, s.median, s.q3, s.max),
            (1.0, 2.0, 3.0, 4.0, 5.0)
        );
        let e = Stats::of(&[1.0, 2.0]).unwrap();
        assert_eq!(e.median, 1.5);
        assert!(Stats::of(&[]).is_none());
    }
}
