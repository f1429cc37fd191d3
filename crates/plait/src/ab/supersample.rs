//! The supersampled reference of `plait ab --supersample N`: an image
//! rendered N × N times larger, filtered down by averaging each N × N block.
//! Colour is averaged in linear light (sRGB decoded, averaged, encoded), as
//! the pixel's area would integrate it; alpha is averaged as is.

/// `image` (width and height multiples of `k`) averaged over k × k blocks;
/// `k` ≤ 1 returns it unchanged.
pub fn box_filter(image: &image::RgbaImage, k: u32) -> image::RgbaImage {
    if k <= 1 {
        return image.clone();
    }
    let (w, h) = (image.width() / k, image.height() / k);
    let to_linear: Vec<f32> = (0..=255u8)
        .map(|v| srgb_to_linear(v as f32 / 255.0))
        .collect();
    let n = (k * k) as f32;
    image::RgbaImage::from_fn(w, h, |x, y| {
        let mut sum = [0.0f32; 4];
        for dy in 0..k {
            for dx in 0..k {
                let p = image.get_pixel(x * k + dx, y * k + dy).0;
                for c in 0..3 {
                    sum[c] += to_linear[p[c] as usize];
                }
                sum[3] += p[3] as f32 / 255.0;
            }
        }
        let encode = |v: f32, srgb: bool| {
            let v = if srgb { linear_to_srgb(v / n) } else { v / n };
            (v.clamp(0.0, 1.0) * 255.0).round() as u8
        };
        image::Rgba([
            encode(sum[0], true),
            encode(sum[1], true),
            encode(sum[2], true),
            encode(sum[3], false),
        ])
    })
}

/// A linear radiance image averaged over k × k blocks (every channel as
/// is: it is already linear); `k` ≤ 1 returns it unchanged.
pub fn box_filter_linear(image: &image::Rgba32FImage, k: u32) -> image::Rgba32FImage {
    if k <= 1 {
        return image.clone();
    }
    let n = (k * k) as f32;
    image::Rgba32FImage::from_fn(image.width() / k, image.height() / k, |x, y| {
        let mut sum = [0.0f32; 4];
        for dy in 0..k {
            for dx in 0..k {
                let p = image.get_pixel(x * k + dx, y * k + dy).0;
                for c in 0..4 {
                    sum[c] += p[c];
                }
            }
        }
        image::Rgba(sum.map(|v| v / n))
    })
}

fn srgb_to_linear(v: f32) -> f32 {
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

fn linear_to_srgb(v: f32) -> f32 {
    if v <= 0.003_130_8 {
        v * 12.92
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn averages_blocks_in_linear_light() {
        // A 2 × 2 block of black and white: half the light, sRGB 188, not 128.
        let image = image::RgbaImage::from_fn(4, 2, |x, _| {
            if x % 2 == 0 {
                image::Rgba([0, 0, 0, 255])
            } else {
                image::Rgba([255, 255, 255, 255])
            }
        });
        let small = box_filter(&image, 2);
        assert_eq!(small.dimensions(), (2, 1));
        assert_eq!(small.get_pixel(0, 0).0, [188, 188, 188, 255]);
        assert_eq!(box_filter(&image, 1), image);
    }
}
