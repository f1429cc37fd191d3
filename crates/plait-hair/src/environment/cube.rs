//! Cube maps as plait lays them out: six faces +x, −x, +y, −y, +z, −z with
//! the Vulkan / Direct3D orientation, side by side in one 6n × n atlas (face
//! f's texel (x, y) at (f·n + x, y)). The same functions are in
//! `shaders/lib/cube.wgsl`.

use glam::Vec3;

use super::image::EnvironmentImage;

/// Direction through face `face` at s, t ∈ [−1, 1] (s to the right, t down
/// the face image); not normalized.
pub fn direction(face: usize, s: f32, t: f32) -> Vec3 {
    match face {
        0 => Vec3::new(1.0, -t, -s),
        1 => Vec3::new(-1.0, -t, s),
        2 => Vec3::new(s, 1.0, t),
        3 => Vec3::new(s, -1.0, -t),
        4 => Vec3::new(s, -t, 1.0),
        _ => Vec3::new(-s, -t, -1.0),
    }
}

/// (face, s, t) of a direction: the inverse of [`direction`].
pub fn face_of(d: Vec3) -> (usize, f32, f32) {
    let a = d.abs();
    if a.x >= a.y && a.x >= a.z {
        if d.x > 0.0 {
            (0, -d.z / a.x, -d.y / a.x)
        } else {
            (1, d.z / a.x, -d.y / a.x)
        }
    } else if a.y >= a.z {
        if d.y > 0.0 {
            (2, d.x / a.y, d.z / a.y)
        } else {
            (3, d.x / a.y, -d.z / a.y)
        }
    } else if d.z > 0.0 {
        (4, d.x / a.z, -d.y / a.z)
    } else {
        (5, -d.x / a.z, -d.y / a.z)
    }
}

/// Unit direction through the centre of texel (x, y) of a face of n × n.
pub fn texel_direction(face: usize, n: u32, x: u32, y: u32) -> Vec3 {
    let s = 2.0 * (x as f32 + 0.5) / n as f32 - 1.0;
    let t = 2.0 * (y as f32 + 0.5) / n as f32 - 1.0;
    direction(face, s, t).normalize()
}

/// Solid angle of texel (x, y) of an n × n face, exactly: the integral of
/// (1 + s² + t²)^(−3/2) over the texel, whose antiderivative is
/// atan(st / √(1 + s² + t²)). The six faces sum to 4π.
pub fn texel_solid_angle(n: u32, x: u32, y: u32) -> f32 {
    let corner = |i: u32| 2.0 * i as f64 / n as f64 - 1.0;
    let area = |s: f64, t: f64| (s * t).atan2((1.0 + s * s + t * t).sqrt());
    let (s0, s1, t0, t1) = (corner(x), corner(x + 1), corner(y), corner(y + 1));
    (area(s1, t1) - area(s0, t1) - area(s1, t0) + area(s0, t0)) as f32
}

/// The environment averaged over the texels of an n × n × 6 cube: what the
/// lighting techniques sum (`environment_cube.wgsl` computes the same on the
/// GPU). Each texel holds its mean radiance and its solid angle.
#[derive(Debug, Clone, PartialEq)]
pub struct EnvironmentCube {
    pub size: u32,
    /// Mean radiance, atlas order (6n × n, row by row).
    pub radiance: Vec<Vec3>,
    /// Solid angle of each texel, same order.
    pub solid_angle: Vec<f32>,
}

impl EnvironmentCube {
    /// Average `env` over each texel with `samples` × `samples` evenly spaced
    /// samples (bilinear each), after turning it by `rotate_degrees` about +y
    /// (as [`EnvironmentImage::radiance_turned`]).
    pub fn new(env: &EnvironmentImage, size: u32, samples: u32, rotate_degrees: f32) -> Self {
        let width = 6 * size;
        let mut radiance = Vec::with_capacity((width * size) as usize);
        let mut solid_angle = Vec::with_capacity((width * size) as usize);
        for y in 0..size {
            for ax in 0..width {
                let (face, x) = ((ax / size) as usize, ax % size);
                let mut sum = Vec3::ZERO;
                for j in 0..samples {
                    for i in 0..samples {
                        let s = 2.0 * (x as f32 + (i as f32 + 0.5) / samples as f32) / size as f32
                            - 1.0;
                        let t = 2.0 * (y as f32 + (j as f32 + 0.5) / samples as f32) / size as f32
                            - 1.0;
                        sum +=
                            env.radiance_turned(direction(face, s, t).normalize(), rotate_degrees);
                    }
                }
                radiance.push(sum / (samples * samples) as f32);
                solid_angle.push(texel_solid_angle(size, x, y));
            }
        }
        EnvironmentCube {
            size,
            radiance,
            solid_angle,
        }
    }

    /// Unit direction of atlas texel `i`.
    pub fn direction(&self, i: usize) -> Vec3 {
        let n = self.size;
        let (ax, y) = (i as u32 % (6 * n), i as u32 / (6 * n));
        texel_direction((ax / n) as usize, n, ax % n, y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_round_trip_and_solid_angles_sum_to_4pi() {
        for face in 0..6 {
            for (s, t) in [(0.0, 0.0), (0.5, -0.3), (-0.9, 0.8)] {
                let (f, s2, t2) = face_of(direction(face, s, t));
                assert_eq!(f, face);
                assert!((s - s2).abs() < 1e-6 && (t - t2).abs() < 1e-6);
            }
        }
        let n = 16;
        let total: f64 = (0..n)
            .flat_map(|y| (0..n).map(move |x| texel_solid_angle(n, x, y) as f64))
            .sum::<f64>()
            * 6.0;
        assert!((total - 4.0 * std::f64::consts::PI).abs() < 1e-4, "{total}");
    }

    #[test]
    fn neighbouring_faces_meet() {
        // The right edge of +z is the left edge of +x, and so on around.
        for (a, b) in [(4, 0), (0, 5), (5, 1), (1, 4)] {
            let right = direction(a, 1.0, 0.3).normalize();
            let left = direction(b, -1.0, 0.3).normalize();
            assert!(right.abs_diff_eq(left, 1e-6), "{a} {b}");
        }
        assert!(direction(2, 0.2, 1.0).abs_diff_eq(direction(4, 0.2, -1.0), 1e-6));
        assert!(direction(3, 0.2, -1.0).abs_diff_eq(direction(4, 0.2, 1.0), 1e-6));
    }
}
