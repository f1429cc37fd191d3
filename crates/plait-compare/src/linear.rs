//! Errors of linear radiance images (the pipelines' float `radiance`, as
//! saved in .exr files): values as stored, unbounded, never clipped or
//! encoded, so a difference in light is measured as light.

use image::Rgba32FImage;

use crate::CompareError;

/// Mean squared error over R, G, B of two linear radiance images (values
/// as stored, unbounded: no clipping, no encoding).
pub fn mse_linear(a: &Rgba32FImage, b: &Rgba32FImage) -> Result<f64, CompareError> {
    crate::check(a, b)?;
    let mut sum = 0.0f64;
    for (pa, pb) in a.pixels().zip(b.pixels()) {
        for c in 0..3 {
            let d = pa.0[c] as f64 - pb.0[c] as f64;
            sum += d * d;
        }
    }
    Ok(sum / (a.width() as f64 * a.height() as f64 * 3.0))
}

/// Root mean squared error over R, G, B of two linear radiance images.
pub fn rmse_linear(a: &Rgba32FImage, b: &Rgba32FImage) -> Result<f64, CompareError> {
    Ok(mse_linear(a, b)?.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ErrorSpace, compare, compare_linear};
    use image::RgbaImage;

    fn flat(w: u32, h: u32, v: [f32; 3]) -> Rgba32FImage {
        Rgba32FImage::from_pixel(w, h, image::Rgba([v[0], v[1], v[2], 1.0]))
    }

    #[test]
    fn linear_rmse_is_unbounded_and_unencoded() {
        // 2 and 5 differ by 3 in every channel: both would display as 255.
        let (a, b) = (flat(4, 3, [2.0; 3]), flat(4, 3, [5.0; 3]));
        assert_eq!(rmse_linear(&a, &b).unwrap(), 3.0);
        assert_eq!(rmse_linear(&a, &a).unwrap(), 0.0);
        // One channel of one pixel of 12: mse = 1 / 36 (×1 channel of 36).
        let mut c = flat(4, 3, [0.0; 3]);
        c.put_pixel(1, 1, image::Rgba([1.0, 0.0, 0.0, 1.0]));
        let want = (1.0f64 / 36.0).sqrt();
        assert!((rmse_linear(&c, &flat(4, 3, [0.0; 3])).unwrap() - want).abs() < 1e-12);
        assert!(matches!(
            rmse_linear(&a, &flat(3, 3, [0.0; 3])),
            Err(CompareError::SizeMismatch { .. })
        ));
    }

    #[test]
    fn compare_linear_takes_rmse_from_radiance_and_ssim_flip_from_the_display() {
        let shown = RgbaImage::from_pixel(16, 16, image::Rgba([255, 255, 255, 255]));
        let (a, b) = (flat(16, 16, [2.0; 3]), flat(16, 16, [5.0; 3]));
        let c = compare_linear(&shown, &shown, Some((&a, &b))).unwrap();
        assert_eq!(c.metrics.error_space, ErrorSpace::LinearRadiance);
        assert_eq!(c.metrics.rmse, 3.0);
        assert_eq!(c.metrics.max_abs_diff, 3.0);
        assert!(c.abs_diff.iter().all(|&d| d == 3.0));
        // The displayed images are equal: SSIM 1, ꟻLIP 0.
        assert!((c.metrics.ssim - 1.0).abs() < 1e-12);
        assert_eq!(c.metrics.flip_mean, 0.0);
        let d = compare(&shown, &shown).unwrap();
        assert_eq!(d.metrics.error_space, ErrorSpace::Displayed);
        assert_eq!(d.metrics.rmse, 0.0);
    }
}
