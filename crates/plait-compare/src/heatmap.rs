//! Per-pixel error as a color image: FLIP's magma scale plus a legend bar.

use image::{Rgb, RgbImage};

/// The magma color scale (256 entries, from FLIP's reference implementation).
pub fn magma() -> Vec<[u8; 3]> {
    let lut = nv_flip::magma_lut().to_vec();
    lut.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
}

/// Height in pixels of the legend strip under the map.
pub const LEGEND_HEIGHT: u32 = 14;

/// `values` (row-major `width × height`) mapped 0 → darkest, `scale` →
/// brightest (clamped), with a legend bar along the bottom: a gap, then the
/// color scale from 0 (left) to `scale` (right). The numbers of the legend
/// are written next to the image in the report (and in `report.json`).
pub fn heatmap(values: &[f32], width: u32, height: u32, scale: f32) -> RgbImage {
    let lut = magma();
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let color = |v: f32| {
        let t = (v / scale).clamp(0.0, 1.0);
        Rgb(lut[(t * 255.0).round() as usize])
    };
    let mut img = RgbImage::from_pixel(width, height + LEGEND_HEIGHT, Rgb([255, 255, 255]));
    for y in 0..height {
        for x in 0..width {
            img.put_pixel(x, y, color(values[(y * width + x) as usize]));
        }
    }
    for y in height + 4..height + LEGEND_HEIGHT {
        for x in 0..width {
            let t = if width > 1 {
                x as f32 / (width - 1) as f32
            } else {
                0.0
            };
            img.put_pixel(x, y, Rgb(lut[(t * 255.0).round() as usize]));
        }
    }
    img
}

/// A "nice" upper bound for a heat map scale: 1, 2 or 5 × 10^k ≥ `max`.
pub fn nice_scale(max: f64) -> f64 {
    if max <= 0.0 || !max.is_finite() {
        return 1.0;
    }
    let p = 10f64.powf(max.log10().floor());
    for m in [1.0, 2.0, 5.0, 10.0] {
        if m * p >= max * (1.0 - 1e-9) {
            return m * p;
        }
    }
    10.0 * p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heatmap_maps_ends_of_the_scale() {
        let lut = magma();
        assert_eq!(lut.len(), 256);
        let img = heatmap(&[0.0, 0.5, 1.0, 7.0], 4, 1, 1.0);
        assert_eq!(img.dimensions(), (4, 1 + LEGEND_HEIGHT));
        assert_eq!(img.get_pixel(0, 0).0, lut[0]);
        assert_eq!(img.get_pixel(2, 0).0, lut[255]);
        assert_eq!(img.get_pixel(3, 0).0, lut[255]); // clamped
        // magma goes dark to bright
        let lum = |c: [u8; 3]| c.iter().map(|&v| v as u32).sum::<u32>();
        assert!(lum(lut[0]) < lum(lut[128]) && lum(lut[128]) < lum(lut[255]));
        // legend: left end is the scale's start, right end its end
        assert_eq!(img.get_pixel(0, LEGEND_HEIGHT).0, lut[0]);
        assert_eq!(img.get_pixel(3, LEGEND_HEIGHT).0, lut[255]);
    }

    #[test]
    fn nice_scales() {
        assert_eq!(nice_scale(0.0), 1.0);
        assert!((nice_scale(0.03) - 0.05).abs() < 1e-12);
        assert!((nice_scale(0.2) - 0.2).abs() < 1e-12);
        assert!((nice_scale(0.7) - 1.0).abs() < 1e-12);
        assert!((nice_scale(0.0012) - 0.002).abs() < 1e-12);
    }
}
