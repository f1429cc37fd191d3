//! The environment as one linear RGB equirectangular image, and the mapping
//! between its texels and directions (the same in
//! `shaders/passes/environment_cube.wgsl`).
//!
//! Direction of (u, v) ∈ [0, 1]²: φ = 2π(u − ½), θ = πv,
//! d = (sin θ sin φ, cos θ, −sin θ cos φ): the centre looks along −z, the top
//! row is +y, u grows towards +x.

use std::f32::consts::PI;

use glam::Vec3;

use super::cube;

/// Widest equirectangular image kept: 512 × 256 (0.7° a texel). The sums
/// run over a 16×16×6 cube with 8 × 8 samples a texel, about one sample a
/// texel at this width; a larger image is box-filtered down.
pub const MAX_WIDTH: u32 = 512;

/// Linear RGB texels, row by row from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearImage {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<[f32; 3]>,
}

/// The environment: a linear RGB equirectangular image (see the module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct EnvironmentImage {
    pub image: LinearImage,
}

/// Direction of equirectangular coordinates (u, v) ∈ [0, 1]².
pub fn equirect_direction(u: f32, v: f32) -> Vec3 {
    let (phi, theta) = (2.0 * PI * (u - 0.5), PI * v);
    Vec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        -theta.sin() * phi.cos(),
    )
}

/// Equirectangular coordinates (u, v) ∈ [0, 1]² of a unit direction.
pub fn equirect_uv(d: Vec3) -> (f32, f32) {
    let u = 0.5 + d.x.atan2(-d.z) / (2.0 * PI);
    let v = d.y.clamp(-1.0, 1.0).acos() / PI;
    (u, v)
}

impl LinearImage {
    fn at(&self, x: u32, y: u32) -> [f32; 3] {
        self.texels[(y * self.width + x) as usize]
    }

    /// Bilinear at texel coordinates (x, y) (texel centres at +0.5); x wraps
    /// when `wrap_x`, otherwise both clamp to the edge texels.
    fn bilinear(&self, x: f32, y: f32, wrap_x: bool) -> [f32; 3] {
        let (fx, fy) = (x - 0.5, y - 0.5);
        let (x0, y0) = (fx.floor(), fy.floor());
        let (ax, ay) = (fx - x0, fy - y0);
        let (w, h) = (self.width as i64, self.height as i64);
        let col = |i: i64| -> u32 {
            if wrap_x {
                i.rem_euclid(w) as u32
            } else {
                i.clamp(0, w - 1) as u32
            }
        };
        let row = |i: i64| i.clamp(0, h - 1) as u32;
        let (x0, y0) = (x0 as i64, y0 as i64);
        let mut out = [0.0; 3];
        for (dx, dy, wgt) in [
            (0, 0, (1.0 - ax) * (1.0 - ay)),
            (1, 0, ax * (1.0 - ay)),
            (0, 1, (1.0 - ax) * ay),
            (1, 1, ax * ay),
        ] {
            let t = self.at(col(x0 + dx), row(y0 + dy));
            for c in 0..3 {
                out[c] += wgt * t[c];
            }
        }
        out
    }

    /// Area-weighted (box) resampling to `width` × `height`, one axis at a time.
    fn resampled(&self, width: u32, height: u32) -> LinearImage {
        let rows = resample_axis(self, width, true);
        resample_axis(&rows, height, false)
    }
}

/// Box-resample the x (`horizontal`) or y axis of `src` to `n` texels: each
/// output texel averages the source texels under its footprint, weighted by
/// overlap.
fn resample_axis(src: &LinearImage, n: u32, horizontal: bool) -> LinearImage {
    let (len, other) = if horizontal {
        (src.width, src.height)
    } else {
        (src.height, src.width)
    };
    if len == n {
        return src.clone();
    }
    let scale = len as f64 / n as f64;
    let (width, height) = if horizontal { (n, other) } else { (other, n) };
    let mut texels = vec![[0.0f32; 3]; (width * height) as usize];
    for o in 0..other {
        for i in 0..n {
            let (start, end) = (i as f64 * scale, (i + 1) as f64 * scale);
            let mut sum = [0.0f64; 3];
            let mut j = start.floor() as u32;
            while (j as f64) < end && j < len {
                let overlap = (end.min(j as f64 + 1.0) - start.max(j as f64)).max(0.0);
                let t = if horizontal {
                    src.at(j, o)
                } else {
                    src.at(o, j)
                };
                for c in 0..3 {
                    sum[c] += overlap * t[c] as f64;
                }
                j += 1;
            }
            let (x, y) = if horizontal { (i, o) } else { (o, i) };
            texels[(y * width + x) as usize] = sum.map(|s| (s / scale) as f32);
        }
    }
    LinearImage {
        width,
        height,
        texels,
    }
}

impl EnvironmentImage {
    /// An equirectangular image (twice as wide as high), box-filtered down
    /// to at most [`MAX_WIDTH`] wide.
    pub fn from_equirect(image: LinearImage) -> Result<EnvironmentImage, String> {
        if image.width != 2 * image.height {
            return Err(format!(
                "an equirectangular environment is twice as wide as high, got {}×{} (a cube cross: layout = \"cube_cross\")",
                image.width, image.height
            ));
        }
        let image = if image.width > MAX_WIDTH {
            image.resampled(MAX_WIDTH, MAX_WIDTH / 2)
        } else {
            image
        };
        Ok(EnvironmentImage { image })
    }

    /// Six square faces (+x, -x, +y, -y, +z, -z) of one size, resampled to
    /// an equirectangular image 4 × face wide (at most [`MAX_WIDTH`]).
    pub fn from_faces(faces: &[LinearImage]) -> Result<EnvironmentImage, String> {
        let n = faces[0].width;
        if faces.len() != 6 || faces.iter().any(|f| f.width != n || f.height != n) {
            return Err("a cube needs six square faces of one size".into());
        }
        let width = 4 * n;
        let height = 2 * n;
        let mut texels = Vec::with_capacity((width * height) as usize);
        for y in 0..height {
            for x in 0..width {
                let d = equirect_direction(
                    (x as f32 + 0.5) / width as f32,
                    (y as f32 + 0.5) / height as f32,
                );
                let (face, s, t) = cube::face_of(d);
                let f = &faces[face];
                let fx = (s + 1.0) * 0.5 * n as f32;
                let fy = (t + 1.0) * 0.5 * n as f32;
                texels.push(f.bilinear(fx, fy, false));
            }
        }
        EnvironmentImage::from_equirect(LinearImage {
            width,
            height,
            texels,
        })
    }

    pub fn width(&self) -> u32 {
        self.image.width
    }

    pub fn height(&self) -> u32 {
        self.image.height
    }

    /// The image turned by `degrees` about +y: the radiance from d is the
    /// old one from d rotated by −degrees, a shift of u by degrees / 360
    /// (as `environment_cube.wgsl` applies its `rotate` param).
    pub fn rotated(self, degrees: f32) -> EnvironmentImage {
        if degrees.rem_euclid(360.0) == 0.0 {
            return self;
        }
        let src = &self.image;
        let shift = degrees / 360.0 * src.width as f32;
        let texels = (0..src.height)
            .flat_map(|y| (0..src.width).map(move |x| (x, y)))
            .map(|(x, y)| src.bilinear(x as f32 + 0.5 + shift, y as f32 + 0.5, true))
            .collect();
        EnvironmentImage {
            image: LinearImage {
                texels,
                ..self.image
            },
        }
    }

    /// The radiance scaled by `k`.
    pub fn scaled(mut self, k: f32) -> EnvironmentImage {
        if k != 1.0 {
            for t in &mut self.image.texels {
                *t = t.map(|c| c * k);
            }
        }
        self
    }

    /// Radiance arriving from unit direction `d` (bilinear, wrapping in u).
    pub fn radiance(&self, d: Vec3) -> Vec3 {
        self.radiance_turned(d, 0.0)
    }

    /// Radiance from `d` of the image turned by `degrees` about +y, read in
    /// one bilinear lookup at u + degrees / 360 (as `environment_cube.wgsl`
    /// applies its `rotate` param).
    pub fn radiance_turned(&self, d: Vec3, degrees: f32) -> Vec3 {
        let (u, v) = equirect_uv(d);
        let x = (u + degrees / 360.0) * self.image.width as f32;
        let y = v * self.image.height as f32;
        Vec3::from(self.image.bilinear(x, y, true))
    }

    /// Texels as RGBA f32 (alpha 1), row by row: what the GPU gets as
    /// `environment_source`.
    pub fn rgba(&self) -> Vec<[f32; 4]> {
        self.image
            .texels
            .iter()
            .map(|t| [t[0], t[1], t[2], 1.0])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direction_and_uv_are_inverse() {
        for (u, v) in [(0.5, 0.5), (0.1, 0.3), (0.9, 0.8), (0.25, 0.5)] {
            let d = equirect_direction(u, v);
            assert!((d.length() - 1.0).abs() < 1e-5);
            let (u2, v2) = equirect_uv(d);
            assert!(
                (u - u2).abs() < 1e-5 && (v - v2).abs() < 1e-5,
                "{u},{v} → {u2},{v2}"
            );
        }
        assert!(equirect_direction(0.5, 0.5).abs_diff_eq(Vec3::NEG_Z, 1e-6));
        assert!(equirect_direction(0.75, 0.5).abs_diff_eq(Vec3::X, 1e-6));
        assert!(equirect_direction(0.3, 0.0).abs_diff_eq(Vec3::Y, 1e-6));
    }

    #[test]
    fn box_resampling_keeps_the_mean() {
        let texels = (0..64 * 32).map(|i| [(i % 7) as f32, 1.0, 0.0]).collect();
        let img = LinearImage {
            width: 64,
            height: 32,
            texels,
        };
        let small = img.resampled(10, 5);
        let mean = |i: &LinearImage| {
            i.texels.iter().map(|t| t[0] as f64).sum::<f64>() / i.texels.len() as f64
        };
        assert!((mean(&img) - mean(&small)).abs() < 1e-4);
        assert!(small.texels.iter().all(|t| (t[1] - 1.0).abs() < 1e-5));
    }

    #[test]
    fn rotation_turns_about_y() {
        // A bright texel straight ahead (-z) moves to +x after rotate = -90:
        // the radiance from d is the old one from d rotated by +90°.
        let mut texels = vec![[0.0f32; 3]; 64 * 32];
        texels[16 * 64 + 32] = [100.0, 0.0, 0.0];
        texels[15 * 64 + 32] = [100.0, 0.0, 0.0];
        let env = EnvironmentImage::from_equirect(LinearImage {
            width: 64,
            height: 32,
            texels,
        })
        .expect("2:1");
        assert!(env.radiance(Vec3::NEG_Z).x > 10.0);
        let turned = env.rotated(-90.0);
        assert!(
            turned.radiance(Vec3::X).x > 10.0,
            "{}",
            turned.radiance(Vec3::X)
        );
        assert!(turned.radiance(Vec3::NEG_Z).x < 1.0);
    }
}
