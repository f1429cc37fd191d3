//! Temporal stability: how much a technique's frame-to-frame change departs
//! from the reference's own frame-to-frame change over an animated sequence.
//!
//! Real motion changes every frame, the reference's included, so a raw
//! frame difference counts motion as flicker. The measure here subtracts the
//! reference's change first: for frames t−1, t of a variant (I) and of the
//! reference (R),
//!
//! ```text
//! flicker(t) = mean over pixels and R, G, B of |(I_t − I_{t−1}) − (R_t − R_{t−1})|
//! ```
//!
//! (values in 0..1), and the same over visibility probe samples for the
//! self-shadowing (V against the exact visibility). It is zero for a static
//! scene, zero for the reference against itself, and grows with changes the
//! reference does not make: popping shadows, crawling strands (Sintorn &
//! Assarsson 2009 Fig. 4 argues occupancy maps flicker less than deep
//! opacity maps on moving stray strands).

use image::RgbaImage;
use serde::Serialize;

use crate::{CompareError, check};

/// `flicker(t)` of an image sequence: one value per transition t−1 → t.
pub fn image_flicker(
    variant: &[RgbaImage],
    reference: &[RgbaImage],
) -> Result<Vec<f64>, CompareError> {
    if variant.len() != reference.len() {
        return Err(CompareError::FrameCount {
            variant: variant.len(),
            reference: reference.len(),
        });
    }
    let mut out = Vec::new();
    for t in 1..variant.len() {
        let (i0, i1, r0, r1) = (
            &variant[t - 1],
            &variant[t],
            &reference[t - 1],
            &reference[t],
        );
        for other in [i1, r0, r1] {
            check(i0, other)?;
        }
        let mut sum = 0.0f64;
        for (((a0, a1), b0), b1) in i0
            .pixels()
            .zip(i1.pixels())
            .zip(r0.pixels())
            .zip(r1.pixels())
        {
            for c in 0..3 {
                let di = a1.0[c] as f64 - a0.0[c] as f64;
                let dr = b1.0[c] as f64 - b0.0[c] as f64;
                sum += (di - dr).abs() / 255.0;
            }
        }
        out.push(sum / (i0.width() as f64 * i0.height() as f64 * 3.0));
    }
    Ok(out)
}

/// `flicker(t)` of probed visibility sequences (each frame the same probe
/// samples): mean |(V_t − V_{t−1}) − (E_t − E_{t−1})| over the samples.
pub fn visibility_flicker(variant: &[Vec<f32>], reference: &[Vec<f32>]) -> Vec<f64> {
    (1..variant.len().min(reference.len()))
        .map(|t| {
            let samples = variant[t]
                .len()
                .min(variant[t - 1].len())
                .min(reference[t].len())
                .min(reference[t - 1].len());
            if samples == 0 {
                return 0.0;
            }
            let sum: f64 = (0..samples)
                .map(|k| {
                    let dv = variant[t][k] as f64 - variant[t - 1][k] as f64;
                    let de = reference[t][k] as f64 - reference[t - 1][k] as f64;
                    (dv - de).abs()
                })
                .sum();
            sum / samples as f64
        })
        .collect()
}

/// Mean |I_t − I_{t−1}| over pixels and R, G, B per transition: how much the
/// sequence moves at all (the scale the flicker is read against).
pub fn frame_change(frames: &[RgbaImage]) -> Result<Vec<f64>, CompareError> {
    let still: Vec<RgbaImage> = frames
        .iter()
        .map(|f| RgbaImage::from_pixel(f.width(), f.height(), image::Rgba([0, 0, 0, 255])))
        .collect();
    image_flicker(frames, &still)
}

/// A variant's temporal stability over one animated sequence.
#[derive(Clone, Debug, Serialize, serde::Deserialize, PartialEq)]
pub struct Temporal {
    pub frames: usize,
    pub fps: f64,
    /// `flicker(t)` of the image per transition (t = 1 … frames − 1).
    pub image_flicker: Vec<f64>,
    pub image_flicker_mean: f64,
    pub image_flicker_max: f64,
    /// The variant's own frame-to-frame change (motion plus flicker).
    pub image_change_mean: f64,
    /// `flicker(t)` of the probed visibility, when the variant has a
    /// self-shadowing provider and the reference one too.
    pub visibility_flicker: Option<Vec<f64>>,
    pub visibility_flicker_mean: Option<f64>,
    pub visibility_flicker_max: Option<f64>,
}

impl Temporal {
    pub fn new(
        fps: f64,
        image_flicker: Vec<f64>,
        image_change: &[f64],
        visibility_flicker: Option<Vec<f64>>,
    ) -> Self {
        let mean = |v: &[f64]| {
            if v.is_empty() {
                0.0
            } else {
                v.iter().sum::<f64>() / v.len() as f64
            }
        };
        let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        Temporal {
            frames: image_flicker.len() + 1,
            fps,
            image_flicker_mean: mean(&image_flicker),
            image_flicker_max: max(&image_flicker),
            image_change_mean: mean(image_change),
            visibility_flicker_mean: visibility_flicker.as_deref().map(mean),
            visibility_flicker_max: visibility_flicker.as_deref().map(max),
            image_flicker,
            visibility_flicker,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solid(v: u8) -> RgbaImage {
        RgbaImage::from_pixel(4, 3, image::Rgba([v, v, v, 255]))
    }

    /// A square moving right one pixel a frame.
    fn moving(t: u32) -> RgbaImage {
        let mut img = solid(0);
        img.put_pixel(t % 4, 1, image::Rgba([255, 255, 255, 255]));
        img
    }

    #[test]
    fn a_static_scene_and_real_motion_are_not_flicker() {
        let still: Vec<_> = (0..5).map(|_| solid(90)).collect();
        assert_eq!(image_flicker(&still, &still).unwrap(), [0.0; 4]);
        let motion: Vec<_> = (0..4).map(moving).collect();
        assert_eq!(image_flicker(&motion, &motion).unwrap(), [0.0; 3]);
        // The motion itself is a change, just not flicker.
        assert!(frame_change(&motion).unwrap().iter().all(|&c| c > 0.0));
        // A constant error (a darker image every frame) does not flicker either.
        let darker: Vec<_> = (0..5).map(|_| solid(60)).collect();
        assert_eq!(image_flicker(&darker, &still).unwrap(), [0.0; 4]);
    }

    #[test]
    fn a_flickering_variant_is_positive_by_the_size_of_its_flicker() {
        let still: Vec<_> = (0..5).map(|_| solid(90)).collect();
        let flicker: Vec<_> = (0..5)
            .map(|t| solid(if t % 2 == 0 { 90 } else { 141 }))
            .collect();
        let f = image_flicker(&flicker, &still).unwrap();
        for x in &f {
            assert!((x - 51.0 / 255.0).abs() < 1e-12, "{f:?}");
        }
        let t = Temporal::new(30.0, f, &frame_change(&flicker).unwrap(), None);
        assert_eq!(t.frames, 5);
        assert!((t.image_flicker_mean - 0.2).abs() < 1e-12);
    }

    #[test]
    fn visibility_flicker_subtracts_the_exact_change() {
        let exact = vec![vec![1.0, 0.5], vec![0.8, 0.5], vec![0.6, 0.5]];
        assert_eq!(visibility_flicker(&exact, &exact), [0.0, 0.0]);
        let popping = vec![vec![1.0, 0.5], vec![0.8, 0.9], vec![0.6, 0.5]];
        let f = visibility_flicker(&popping, &exact);
        assert!(
            (f[0] - 0.2).abs() < 1e-6 && (f[1] - 0.2).abs() < 1e-6,
            "{f:?}"
        );
    }

    #[test]
    fn sequences_of_different_lengths_or_sizes_are_errors() {
        assert!(image_flicker(&[solid(1)], &[solid(1), solid(2)]).is_err());
        let small = RgbaImage::new(2, 2);
        assert!(image_flicker(&[solid(1), small.clone()], &[solid(1), small]).is_err());
    }
}
