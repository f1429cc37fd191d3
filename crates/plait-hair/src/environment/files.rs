//! Reading environment files: HDR (`.hdr`), OpenEXR (`.exr`) and LDR images
//! (PNG, JPEG: sRGB, decoded to linear), checked texel by texel, and cutting
//! a cube cross into its faces.

use std::path::Path;

use super::image::LinearImage;

/// An image file as linear RGB. Rejects what cannot be lit with: NaN,
/// infinite or negative radiance (the message names the first such texel).
pub(crate) fn read_linear(path: &Path) -> Result<LinearImage, String> {
    let reader = image::ImageReader::open(path)
        .map_err(|e| format!("cannot read the environment image: {e}"))?
        .with_guessed_format()
        .map_err(|e| format!("cannot read the environment image: {e}"))?;
    if reader.format().is_none() {
        return Err(
            "not an image plait can read (Radiance .hdr, OpenEXR .exr, PNG or JPEG)".into(),
        );
    }
    let decoded = reader
        .decode()
        .map_err(|e| format!("not a readable image: {e}"))?;
    let float = matches!(
        decoded,
        image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_)
    );
    let rgb = decoded.to_rgb32f();
    let (width, height) = rgb.dimensions();
    if width == 0 || height == 0 {
        return Err("the image is empty".into());
    }
    let mut texels: Vec<[f32; 3]> = rgb.pixels().map(|p| p.0).collect();
    for (i, t) in texels.iter().enumerate() {
        let what = if t.iter().any(|c| c.is_nan()) {
            "NaN"
        } else if t.iter().any(|c| c.is_infinite()) {
            "infinite radiance"
        } else if t.iter().any(|c| *c < 0.0) {
            "negative radiance"
        } else {
            continue;
        };
        let (x, y) = (i as u32 % width, i as u32 / width);
        return Err(format!(
            "{what} in texel ({x}, {y}) of {width}×{height}: an environment needs finite radiance ≥ 0"
        ));
    }
    if !float {
        // 8- and 16-bit images store sRGB-encoded values.
        for t in &mut texels {
            for c in t.iter_mut() {
                *c = srgb_to_linear(*c);
            }
        }
    }
    Ok(LinearImage {
        width,
        height,
        texels,
    })
}

fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The six faces (+x, -x, +y, -y, +z, -z) of a horizontal (4 × 3 faces) or
/// vertical (3 × 4) cube cross.
pub(crate) fn split_cross(cross: &LinearImage) -> Result<Vec<LinearImage>, String> {
    let (w, h) = (cross.width, cross.height);
    // (column, row, turned 180°) of each face.
    let cells: [(u32, u32, bool); 6] = if w * 3 == h * 4 && w % 4 == 0 {
        [
            (2, 1, false),
            (0, 1, false),
            (1, 0, false),
            (1, 2, false),
            (1, 1, false),
            (3, 1, false),
        ]
    } else if w * 4 == h * 3 && w % 3 == 0 {
        [
            (2, 1, false),
            (0, 1, false),
            (1, 0, false),
            (1, 2, false),
            (1, 1, false),
            (1, 3, true),
        ]
    } else {
        return Err(format!(
            "a cube cross must be 4:3 (horizontal: 4 × 3 square faces) or 3:4 (vertical), got {w}×{h}"
        ));
    };
    let n = if w * 3 == h * 4 { w / 4 } else { w / 3 };
    Ok(cells
        .iter()
        .map(|&(col, row, turned)| {
            let mut texels = Vec::with_capacity((n * n) as usize);
            for y in 0..n {
                for x in 0..n {
                    let (fx, fy) = if turned {
                        (n - 1 - x, n - 1 - y)
                    } else {
                        (x, y)
                    };
                    texels.push(cross.texels[((row * n + fy) * w + col * n + fx) as usize]);
                }
            }
            LinearImage {
                width: n,
                height: n,
                texels,
            }
        })
        .collect())
}

/// Six face images must be square and of one size: (face index, message).
pub(crate) fn check_faces(faces: &[LinearImage]) -> Result<(), (usize, String)> {
    let n = faces[0].width;
    for (i, f) in faces.iter().enumerate() {
        if f.width != f.height || f.width != n {
            return Err((
                i,
                format!(
                    "cube faces must be square and all {n}×{n} (the +x face's size), got {}×{}",
                    f.width, f.height
                ),
            ));
        }
    }
    Ok(())
}
