//! Kajiya-Kay irradiance maps (Xing et al. 2012 §3) on the CPU: the
//! reference the GPU kernels (`shaders/passes/irradiance_maps.wgsl`,
//! `sh_irradiance_maps.wgsl`) and the brute-force lighting
//! (`techniques/lighting/environment_reference/lighting.wgsl`) are checked against.
//!
//! Each texel i of the environment cube is a directional light of radiance
//! Lᵢ over solid angle dωᵢ. For a strand of unit tangent t seen at angle θ′
//! between t and the eye:
//!
//! - diffuse D(t) = 1/π² Σ sin θᵢ Lᵢ dωᵢ (eq. 5), θᵢ the angle between t and
//!   the texel's direction;
//! - specular S(t, θ′) = 1/π² Σ cos^p(θ̄ᵢ − θ′) Lᵢ dωᵢ (eq. 7), θ̄ᵢ = π − θᵢ,
//!   negative cosines clamped to 0.
//!
//! The 1/π² (the integral of sin θ over the sphere) makes a uniform
//! environment of radiance 1 give D = 1, so `frame.ambient` and an
//! environment of that radiance light the diffuse term alike. The shading
//! multiplies in kd, ks and the hair colour (the paper leaves Kd out of the
//! map for the same reason, §3). The maps store D over t (one map) and S over
//! t for θ′ = mπ/M, m = 0…M (eq. 8); a lookup interpolates the two maps
//! around θ′.

use std::f32::consts::PI;

use glam::Vec3;

use super::cube::{self, EnvironmentCube};

/// 1 / ∫ sin θ dω = 1/π².
pub const NORMALIZATION: f32 = 1.0 / (PI * PI);

/// Kajiya-Kay diffuse response sin θ (eq. 4) of cos θ = t · l.
pub fn diffuse_response(cos_tl: f32) -> f32 {
    (1.0 - cos_tl * cos_tl).max(0.0).sqrt()
}

/// Kajiya-Kay specular response cos^p(π − θ − θ′) (eq. 6), clamped at 0.
pub fn specular_response(cos_tl: f32, theta_eye: f32, exponent: f32) -> f32 {
    let theta = cos_tl.clamp(-1.0, 1.0).acos();
    (PI - theta - theta_eye).cos().max(0.0).powf(exponent)
}

/// The brute-force sums for one tangent (Xing et al. 2012 Fig. 3a, 3c):
/// (D(t), S(t, θ′)) over every texel of `cube`.
pub fn brute_force(cube: &EnvironmentCube, t: Vec3, theta_eye: f32, exponent: f32) -> (Vec3, Vec3) {
    let (mut d, mut s) = (Vec3::ZERO, Vec3::ZERO);
    for i in 0..cube.radiance.len() {
        let l = cube.direction(i);
        let weight = cube.radiance[i] * cube.solid_angle[i];
        let c = t.dot(l);
        d += diffuse_response(c) * weight;
        s += specular_response(c, theta_eye, exponent) * weight;
    }
    (d * NORMALIZATION, s * NORMALIZATION)
}

/// One diffuse and M + 1 specular maps of n × n × 6 texels, in one atlas
/// 6n wide and (M + 2)·n high: map k (0 diffuse, 1 + m specular at θ′ =
/// mπ/M) holds face f's texel (x, y) at (f·n + x, k·n + y), as the GPU
/// texture `irradiance_maps` does.
#[derive(Debug, Clone, PartialEq)]
pub struct IrradianceMaps {
    pub size: u32,
    /// M: the specular maps are at θ′ = mπ/M, m = 0…M.
    pub intervals: u32,
    pub texels: Vec<Vec3>,
}

impl IrradianceMaps {
    /// Maps filled by `value(map, tangent)` at every texel centre.
    pub fn from_fn(size: u32, intervals: u32, mut value: impl FnMut(u32, Vec3) -> Vec3) -> Self {
        let (w, h) = (6 * size, (intervals + 2) * size);
        let mut texels = Vec::with_capacity((w * h) as usize);
        for ay in 0..h {
            for ax in 0..w {
                let (map, y) = (ay / size, ay % size);
                let (face, x) = ((ax / size) as usize, ax % size);
                texels.push(value(map, cube::texel_direction(face, size, x, y)));
            }
        }
        IrradianceMaps {
            size,
            intervals,
            texels,
        }
    }

    /// The maps summed directly over the cube's texels (§3, eq. 5 and 8).
    pub fn direct(cube: &EnvironmentCube, size: u32, intervals: u32, exponent: f32) -> Self {
        Self::from_fn(size, intervals, |map, t| {
            let (d, s) = brute_force(cube, t, theta_of_map(map, intervals), exponent);
            if map == 0 { d } else { s }
        })
    }

    /// Map `map` (0 diffuse, 1 + m specular) bilinearly at unit direction t,
    /// clamped at the face's edges (`irradiance_maps.wgsl` reads the same).
    pub fn sample(&self, map: u32, t: Vec3) -> Vec3 {
        let n = self.size;
        sample_with(n, map, t, |map, face, x, y| {
            self.texels[((map * n + y) * 6 * n + face * n + x) as usize]
        })
    }

    /// (D(t), S(t, θ′)): the diffuse map, and the two specular maps around
    /// θ′ interpolated linearly (§3).
    pub fn lookup(&self, t: Vec3, theta_eye: f32) -> (Vec3, Vec3) {
        lookup_with(
            self.size,
            self.intervals,
            t,
            theta_eye,
            |map, face, x, y| {
                self.texels[((map * self.size + y) * 6 * self.size + face * self.size + x) as usize]
            },
        )
    }
}

/// Bilinear read of map `map` at unit direction t from texels given by
/// `texel(map, face, x, y)`, clamped at the face's edges.
pub fn sample_with(n: u32, map: u32, t: Vec3, texel: impl Fn(u32, u32, u32, u32) -> Vec3) -> Vec3 {
    let (face, s, tt) = cube::face_of(t);
    let fx = (s + 1.0) * 0.5 * n as f32 - 0.5;
    let fy = (tt + 1.0) * 0.5 * n as f32 - 0.5;
    let (x0, y0) = (fx.floor(), fy.floor());
    let (ax, ay) = (fx - x0, fy - y0);
    let clamp = |v: f32| (v as i64).clamp(0, n as i64 - 1) as u32;
    let at = |x: f32, y: f32| texel(map, face as u32, clamp(x), clamp(y));
    at(x0, y0) * (1.0 - ax) * (1.0 - ay)
        + at(x0 + 1.0, y0) * ax * (1.0 - ay)
        + at(x0, y0 + 1.0) * (1.0 - ax) * ay
        + at(x0 + 1.0, y0 + 1.0) * ax * ay
}

/// The lookup of [`IrradianceMaps::lookup`] over texels given by a
/// function, so a test can evaluate maps of any M at the few texels a lookup
/// reads instead of building them whole.
pub fn lookup_with(
    n: u32,
    intervals: u32,
    t: Vec3,
    theta_eye: f32,
    texel: impl Fn(u32, u32, u32, u32) -> Vec3,
) -> (Vec3, Vec3) {
    let m = intervals as f32;
    let f = (theta_eye.clamp(0.0, PI) / PI * m).min(m);
    let m0 = (f.floor() as u32).min(intervals);
    let m1 = (m0 + 1).min(intervals);
    let a = f - m0 as f32;
    let s = sample_with(n, 1 + m0, t, &texel) * (1.0 - a) + sample_with(n, 1 + m1, t, &texel) * a;
    (sample_with(n, 0, t, &texel), s)
}

/// θ′ of map `map` (1 + m ↦ mπ/M; the diffuse map 0 has none).
pub fn theta_of_map(map: u32, intervals: u32) -> f32 {
    map.saturating_sub(1) as f32 * PI / intervals as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::image::{EnvironmentImage, LinearImage};

    fn uniform(radiance: f32) -> EnvironmentImage {
        EnvironmentImage::from_equirect(LinearImage {
            width: 32,
            height: 16,
            texels: vec![[radiance; 3]; 512],
        })
        .expect("2:1")
    }

    #[test]
    fn a_uniform_environment_gives_diffuse_one() {
        let cube = EnvironmentCube::new(&uniform(1.0), 8, 2, 0.0);
        for t in [Vec3::X, Vec3::Y, Vec3::new(0.3, -0.5, 0.8).normalize()] {
            let (d, _) = brute_force(&cube, t, 1.0, 60.0);
            assert!((d.x - 1.0).abs() < 2e-3, "{d}");
        }
    }

    #[test]
    fn maps_match_brute_force_at_their_texel_centres() {
        let cube = EnvironmentCube::new(&super::super::sky::image(64), 8, 2, 0.0);
        let maps = IrradianceMaps::direct(&cube, 4, 4, 20.0);
        let t = cube::texel_direction(2, 4, 1, 2);
        let theta = theta_of_map(3, 4);
        let (d, s) = maps.lookup(t, theta);
        let (bd, bs) = brute_force(&cube, t, theta, 20.0);
        assert!(d.abs_diff_eq(bd, 1e-4 * bd.length().max(1.0)), "{d} {bd}");
        assert!(s.abs_diff_eq(bs, 1e-4 * bs.length().max(1.0)), "{s} {bs}");
    }
}
