//! The CPU twin of the default display transform (`tone_mapping/agx`,
//! `techniques/tone_mapping/agx/tone_map.wgsl`): a path-traced reference's
//! radiance is shown through the same exposure and operator as the GPU
//! variants' (2^exposure, AgX, sRGB encoding by an rgba8unorm-srgb target),
//! so SSIM and ꟻLIP compare like with like. The constants are the WGSL's,
//! and a test compares this with the GPU pass's output pixel by pixel.

use glam::{Mat3, Vec3};

// Column-major like the WGSL (mat3x3 built from columns).
const SRGB_TO_REC2020: [[f32; 3]; 3] = [
    [0.6274, 0.0691, 0.0164],
    [0.3293, 0.9195, 0.0880],
    [0.0433, 0.0113, 0.8956],
];
const REC2020_TO_SRGB: [[f32; 3]; 3] = [
    [1.6605, -0.1246, -0.0182],
    [-0.5876, 1.1329, -0.1006],
    [-0.0728, -0.0083, 1.1187],
];
const AGX_INSET: [[f32; 3]; 3] = [
    [0.856_627_15, 0.137_318_97, 0.111_898_21],
    [0.095_121_24, 0.761_242, 0.076_799_42],
    [0.048_251_606, 0.101_439_04, 0.811_302_37],
];
const AGX_OUTSET: [[f32; 3]; 3] = [
    [1.127_100_6, -0.141_329_76, -0.141_329_76],
    [-0.110_606_64, 1.157_823_7, -0.110_606_64],
    [-0.016_493_939, -0.016_493_939, 1.251_936_4],
];
const AGX_MIN_EV: f32 = -12.47393;
const AGX_MAX_EV: f32 = 4.026069;

fn mat(cols: [[f32; 3]; 3]) -> Mat3 {
    Mat3::from_cols(cols[0].into(), cols[1].into(), cols[2].into())
}

fn contrast(x: Vec3) -> Vec3 {
    let x2 = x * x;
    let x4 = x2 * x2;
    15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x
        - Vec3::splat(0.00232)
}

/// AgX of an exposed linear sRGB radiance: the display's linear value, 0…1.
pub fn agx(c: Vec3) -> Vec3 {
    let v = mat(AGX_INSET) * (mat(SRGB_TO_REC2020) * c);
    let v = v.max(Vec3::splat(1e-10)).to_array().map(f32::log2);
    let v = ((Vec3::from(v) - Vec3::splat(AGX_MIN_EV)) / (AGX_MAX_EV - AGX_MIN_EV))
        .clamp(Vec3::ZERO, Vec3::ONE);
    let v = mat(AGX_OUTSET) * contrast(v);
    let v = Vec3::from(v.max(Vec3::ZERO).to_array().map(|x| x.powf(2.2)));
    (mat(REC2020_TO_SRGB) * v).clamp(Vec3::ZERO, Vec3::ONE)
}

/// The sRGB encoding an rgba8unorm-srgb target applies (IEC 61966-2-1),
/// rounded to 8 bits.
pub fn srgb_u8(linear: f32) -> u8 {
    let l = linear.clamp(0.0, 1.0);
    let s = if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

/// A linear radiance image as the default display shows it at `exposure`
/// stops: 2^exposure, AgX, sRGB; alpha 255 as the display pass writes.
pub fn display(radiance: &image::Rgba32FImage, exposure: f32) -> image::RgbaImage {
    let scale = exposure.exp2();
    image::RgbaImage::from_fn(radiance.width(), radiance.height(), |x, y| {
        let p = radiance.get_pixel(x, y).0;
        let d = agx(Vec3::new(p[0], p[1], p[2]) * scale);
        image::Rgba([srgb_u8(d.x), srgb_u8(d.y), srgb_u8(d.z), 255])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Fixed points of the operator: black maps near 0, middle grey to the
    /// sigmoid's middle, huge values clamp to 1 — and the result is monotonic.
    #[test]
    fn agx_is_monotonic_and_bounded() {
        let mut last = -1.0;
        for i in 0..200 {
            let x = 1e-4 * 1.1f32.powi(i);
            let y = agx(Vec3::splat(x)).x;
            assert!((0.0..=1.0).contains(&y), "{x} → {y}");
            assert!(y >= last - 1e-6, "not monotonic at {x}: {last} then {y}");
            last = y;
        }
        assert!(agx(Vec3::ZERO).x < 0.01);
        assert_eq!(srgb_u8(1.0), 255);
        assert_eq!(srgb_u8(0.0), 0);
        assert_eq!(srgb_u8(0.214_041_14), 128);
    }
}
