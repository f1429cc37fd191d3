//! Spherical harmonics for the irradiance maps (Xing et al. 2012 §5).
//!
//! The environment is projected on real SH up to band n − 1 (eq. 10:
//! wᵢ = Σⱼ L(lⱼ) Yᵢ(lⱼ) dωⱼ over the cube's texels); the maps are rebuilt
//! from the coefficients (eq. 11). The paper precomputes the transfer
//! Σⱼ Yᵢ(lⱼ) f(t, lⱼ) dω per map texel; Kajiya-Kay's f depends on t only
//! through t · l, so by the Funk–Hecke theorem that transfer is λ_l Yᵢ(t)
//! with one number per band, λ_l = 2π ∫ f(x) P_l(x) dx (Ramamoorthi &
//! Hanrahan 2001 §2 use the same for the diffuse cosine). The maps are
//! then I(t) = Σ_l λ_l Σ_m w_lm Y_lm(t) — the paper's eq. 11 computed
//! exactly, with the transfer reduced to (M + 2) × n numbers.
//!
//! Bands: 3 (9 coefficients) for the diffuse map and √p for the specular
//! ones (p = 64 → 8 bands, 64 coefficients), as §5 takes from King 2005.
//! The basis is Green 2003's real SH (with the Condon–Shortley phase),
//! index l² + l + m; `shaders/lib/sh.wgsl` evaluates the same.

use std::f64::consts::PI;

use glam::Vec3;

use super::cube::EnvironmentCube;
use super::irradiance::{
    IrradianceMaps, NORMALIZATION, diffuse_response, specular_response, theta_of_map,
};

/// Bands a projection may use: the GPU kernels loop over at most 16.
pub const MAX_BANDS: u32 = 16;

/// Associated Legendre polynomial P_l^m(x), m ≥ 0 (Green 2003's recurrence).
pub fn legendre(l: u32, m: u32, x: f64) -> f64 {
    let mut pmm = 1.0;
    if m > 0 {
        let somx2 = ((1.0 - x) * (1.0 + x)).max(0.0).sqrt();
        let mut fact = 1.0;
        for _ in 0..m {
            pmm *= -fact * somx2;
            fact += 2.0;
        }
    }
    if l == m {
        return pmm;
    }
    let mut pmmp1 = x * (2 * m + 1) as f64 * pmm;
    if l == m + 1 {
        return pmmp1;
    }
    let mut pll = 0.0;
    for ll in m + 2..=l {
        pll = ((2 * ll - 1) as f64 * x * pmmp1 - (ll + m - 1) as f64 * pmm) / (ll - m) as f64;
        pmm = pmmp1;
        pmmp1 = pll;
    }
    pll
}

fn normalization(l: u32, m: u32) -> f64 {
    // (l − m)! / (l + m)! as a product, so no factorial overflows.
    let ratio: f64 = (l - m + 1..=l + m).map(|k| 1.0 / k as f64).product();
    ((2 * l + 1) as f64 / (4.0 * PI) * ratio).sqrt()
}

/// Real SH Y_lm of a unit direction, −l ≤ m ≤ l; y is the polar axis.
pub fn basis(l: u32, m: i32, d: Vec3) -> f64 {
    let cos_theta = d.y.clamp(-1.0, 1.0) as f64;
    let phi = (d.z as f64).atan2(d.x as f64);
    let am = m.unsigned_abs();
    let k = normalization(l, am) * legendre(l, am, cos_theta);
    match m.cmp(&0) {
        std::cmp::Ordering::Equal => k,
        std::cmp::Ordering::Greater => std::f64::consts::SQRT_2 * k * (m as f64 * phi).cos(),
        std::cmp::Ordering::Less => std::f64::consts::SQRT_2 * k * (am as f64 * phi).sin(),
    }
}

/// Every Y_lm of `d` for l < bands, index l² + l + m.
pub fn basis_all(bands: u32, d: Vec3) -> Vec<f64> {
    let mut out = Vec::with_capacity((bands * bands) as usize);
    for l in 0..bands {
        for m in -(l as i32)..=l as i32 {
            out.push(basis(l, m, d));
        }
    }
    out
}

/// The environment's coefficients for l < bands (eq. 10), RGB.
pub fn project(cube: &EnvironmentCube, bands: u32) -> Vec<Vec3> {
    let mut w = vec![[0.0f64; 3]; (bands * bands) as usize];
    for i in 0..cube.radiance.len() {
        let weight = cube.radiance[i].as_dvec3() * cube.solid_angle[i] as f64;
        for (wi, y) in w.iter_mut().zip(basis_all(bands, cube.direction(i))) {
            for c in 0..3 {
                wi[c] += weight[c] * y;
            }
        }
    }
    w.iter()
        .map(|c| Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32))
        .collect()
}

/// Steps of the midpoint rule in θ for the zonal integrals: the specular
/// lobe at p = 60 is about 0.3 rad wide, some 200 steps.
const ZONAL_STEPS: u32 = 2048;

/// λ_l = 2π ∫₀^π f(cos θ) P_l(cos θ) sin θ dθ for l < bands.
pub fn zonal(bands: u32, f: impl Fn(f32) -> f32) -> Vec<f64> {
    let dt = PI / ZONAL_STEPS as f64;
    (0..bands)
        .map(|l| {
            (0..ZONAL_STEPS)
                .map(|i| {
                    let theta = (i as f64 + 0.5) * dt;
                    let x = theta.cos();
                    f(x as f32) as f64 * legendre(l, 0, x) * theta.sin() * dt
                })
                .sum::<f64>()
                * 2.0
                * PI
        })
        .collect()
}

/// The zonal kernel of map `map` (0 diffuse, 1 + m specular at mπ/M).
pub fn map_kernel(map: u32, intervals: u32, exponent: f32, bands: u32) -> Vec<f64> {
    if map == 0 {
        zonal(bands, diffuse_response)
    } else {
        let theta_eye = theta_of_map(map, intervals);
        zonal(bands, |x| specular_response(x, theta_eye, exponent))
    }
}

/// An environment's SH projection with the transfer of every map: the
/// texels of the irradiance maps rebuilt from SH (eq. 11), one at a time.
#[derive(Debug, Clone)]
pub struct ShMaps {
    pub intervals: u32,
    pub diffuse_bands: u32,
    pub specular_bands: u32,
    /// The environment's coefficients over `specular_bands` bands.
    pub coefficients: Vec<Vec3>,
    /// λ_l per map (0 diffuse, 1 + m specular).
    pub kernels: Vec<Vec<f64>>,
}

impl ShMaps {
    /// Project `cube` on `specular_bands` bands; the diffuse map uses the
    /// first `diffuse_bands` of them (at most as many).
    pub fn new(
        cube: &EnvironmentCube,
        intervals: u32,
        exponent: f32,
        diffuse_bands: u32,
        specular_bands: u32,
    ) -> ShMaps {
        let diffuse_bands = diffuse_bands.min(specular_bands);
        let kernels = (0..intervals + 2)
            .map(|map| {
                let b = if map == 0 {
                    diffuse_bands
                } else {
                    specular_bands
                };
                map_kernel(map, intervals, exponent, b)
            })
            .collect();
        ShMaps {
            intervals,
            diffuse_bands,
            specular_bands,
            coefficients: project(cube, specular_bands),
            kernels,
        }
    }

    /// Map `map` at unit direction t: 1/π² Σ_l λ_l Σ_m w_lm Y_lm(t).
    pub fn value(&self, map: u32, t: Vec3) -> Vec3 {
        let y = basis_all(self.specular_bands, t);
        let mut sum = glam::DVec3::ZERO;
        for (l, lambda) in self.kernels[map as usize].iter().enumerate() {
            let band = l * l..(l + 1) * (l + 1);
            for (w, y) in self.coefficients[band.clone()].iter().zip(&y[band]) {
                sum += w.as_dvec3() * (lambda * y);
            }
        }
        (sum * NORMALIZATION as f64).as_vec3()
    }

    /// Every map at size × size × 6.
    pub fn maps(&self, size: u32) -> IrradianceMaps {
        IrradianceMaps::from_fn(size, self.intervals, |map, t| self.value(map, t))
    }
}

/// Irradiance maps rebuilt from the environment's SH coefficients (eq. 11):
/// `diffuse_bands` for the diffuse map, `specular_bands` for the others.
pub fn maps(
    cube: &EnvironmentCube,
    size: u32,
    intervals: u32,
    exponent: f32,
    diffuse_bands: u32,
    specular_bands: u32,
) -> IrradianceMaps {
    ShMaps::new(cube, intervals, exponent, diffuse_bands, specular_bands).maps(size)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::cube::EnvironmentCube;
    use crate::environment::irradiance::IrradianceMaps;

    #[test]
    fn the_basis_is_orthonormal_on_the_cube() {
        // Σ Yᵢ Yⱼ dω over a fine cube ≈ δᵢⱼ.
        let n = 32;
        let (bands, count) = (5u32, 25usize);
        let mut gram = vec![0.0f64; count * count];
        for face in 0..6 {
            for y in 0..n {
                for x in 0..n {
                    let d = crate::environment::cube::texel_direction(face, n, x, y);
                    let dw = crate::environment::cube::texel_solid_angle(n, x, y) as f64;
                    let b = basis_all(bands, d);
                    for i in 0..count {
                        for j in 0..count {
                            gram[i * count + j] += b[i] * b[j] * dw;
                        }
                    }
                }
            }
        }
        for i in 0..count {
            for j in 0..count {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!(
                    (gram[i * count + j] - want).abs() < 5e-3,
                    "{i},{j}: {}",
                    gram[i * count + j]
                );
            }
        }
    }

    #[test]
    fn diffuse_from_nine_coefficients_is_close_to_the_direct_map() {
        let cube = EnvironmentCube::new(&crate::environment::sky::image(64), 8, 2, 0.0);
        let direct = IrradianceMaps::direct(&cube, 4, 2, 20.0);
        let from_sh = maps(&cube, 4, 2, 20.0, 3, 5);
        let n = (6 * 4 * 4) as usize;
        let mean = direct.texels[..n].iter().map(|v| v.x).sum::<f32>() / n as f32;
        let worst = direct.texels[..n]
            .iter()
            .zip(&from_sh.texels[..n])
            .map(|(a, b)| (*a - *b).abs().max_element())
            .fold(0.0f32, f32::max);
        assert!(worst < 0.1 * mean, "worst {worst} mean {mean}");
    }
}
