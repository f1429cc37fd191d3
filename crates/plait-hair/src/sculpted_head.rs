//! A simple sculpted head for the mesh-head example
//! (`examples/scenes/sculpted_head.glb`): the built-in scene's head
//! ellipsoid with a face, ears, a jaw and a neck, so the example reads as a
//! head rather than an egg.
//!
//! The shape is the ellipsoid's parameter sphere (polar angle θ from +Y,
//! azimuth φ around it, φ = 0 the face at +Z, as the groom's scalp is
//! parameterized) displaced along the radius by a few smooth bumps and dents,
//! and below the jaw drawn in to a neck. Where the procedural groom grows
//! hair (`groom::ScalpRegion`'s defaults: θ < 105° except the face,
//! θ > 50° within ±70° of +Z) the displacement is zero to within a
//! thousandth of the radius, so a groom grown over the ellipsoid keeps its
//! roots on this head. One grid of stacks × slices quads, the seam at the
//! back, normals from the surface's own derivatives: closed, outward.

use glam::Vec3;

use crate::mesh::{Mesh, MeshVertex};

/// The built-in head ellipsoid's radii (`Scene::builtin_default`).
const RADII: Vec3 = Vec3::new(0.9, 1.05, 1.0);
/// Where the neck starts (polar angle, degrees) and its radius and length.
const NECK_FROM: f32 = 132.0;
const NECK_RADIUS: f32 = 0.42;
const NECK_LENGTH: f32 = 0.9;

/// A bump on the parameter sphere: `height` (a fraction of the radius) at
/// (θ0, φ0) degrees, Gaussian with widths (sθ, sφ) degrees.
struct Bump {
    height: f32,
    theta: f32,
    phi: f32,
    s_theta: f32,
    s_phi: f32,
}

const fn bump(height: f32, theta: f32, phi: f32, s_theta: f32, s_phi: f32) -> Bump {
    Bump {
        height,
        theta,
        phi,
        s_theta,
        s_phi,
    }
}

/// The face and ears, mirrored where φ0 ≠ 0. Heights in fractions of the
/// radius; angles in degrees.
const FEATURES: [Bump; 11] = [
    bump(0.035, 74.0, 0.0, 6.0, 32.0),   // brow ridge
    bump(-0.055, 88.0, 25.0, 6.0, 10.0), // eye socket
    bump(0.025, 89.0, 25.0, 3.0, 6.0),   // eyeball in it
    bump(0.16, 99.0, 0.0, 8.0, 6.0),     // nose
    bump(0.05, 106.0, 0.0, 3.5, 7.0),    // nose tip and wings
    bump(0.03, 99.0, 42.0, 9.0, 14.0),   // cheekbone
    bump(0.03, 114.0, 0.0, 2.5, 13.0),   // upper lip
    bump(-0.02, 117.0, 0.0, 1.5, 15.0),  // mouth
    bump(0.025, 120.0, 0.0, 2.5, 11.0),  // lower lip
    bump(0.07, 125.0, 0.0, 5.0, 18.0),   // chin
    bump(0.16, 121.0, 90.0, 5.5, 5.0),   // ear, below the hair's lowest roots
];

fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// The radial displacement (fraction of the radius) at θ, φ (radians).
fn displacement(theta: f32, phi: f32) -> f32 {
    let (td, pd) = (theta.to_degrees(), phi.to_degrees());
    FEATURES
        .iter()
        .map(|b| {
            let along = (td - b.theta) / b.s_theta;
            let mut sum = 0.0;
            for side in if b.phi == 0.0 { &[1.0][..] } else { &[1.0, -1.0][..] } {
                let across = (pd - side * b.phi) / b.s_phi;
                sum += (-(along * along) - across * across).exp();
            }
            b.height * sum
        })
        .sum::<f32>()
        // The jaw narrower than the skull at the sides, below the roots.
        - 0.10 * smoothstep(105.0, 130.0, td) * phi.sin().powi(2)
}

/// The surface point at θ, φ (radians): the displaced ellipsoid, drawn in
/// to a cylinder of `NECK_RADIUS` below `NECK_FROM` and closed by a
/// rounded end `NECK_LENGTH` lower.
fn surface(theta: f32, phi: f32) -> Vec3 {
    let unit = Vec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        theta.sin() * phi.cos(),
    );
    let head = unit * RADII * (1.0 + displacement(theta, phi));
    let from = NECK_FROM.to_radians();
    if theta <= from {
        return head;
    }
    // s: 0 at the neck's start, 1 at the bottom pole.
    let s = (theta - from) / (std::f32::consts::PI - from);
    let start = Vec3::new(from.sin() * phi.sin(), from.cos(), from.sin() * phi.cos())
        * RADII
        * (1.0 + displacement(from, phi));
    let around = Vec3::new(phi.sin(), 0.0, phi.cos());
    let pull = smoothstep(0.0, 0.35, s);
    let radius = (start * Vec3::new(1.0, 0.0, 1.0)).length() * (1.0 - pull) + NECK_RADIUS * pull;
    // The last tenth closes the cylinder with a quarter circle.
    let close = ((s - 0.9) / 0.1).clamp(0.0, 1.0);
    let radius = radius * (1.0 - close * close).sqrt();
    // Drawn from the displaced start (continuous with the head above) to
    // one height all round (so the bottom pole is one point).
    let level = from.cos() * RADII.y;
    let y = start.y * (1.0 - pull) + level * pull
        - NECK_LENGTH * s.min(0.9) / 0.9
        - 0.1 * NECK_RADIUS * close;
    around * radius + Vec3::Y * y
}

/// The sculpted head: `stacks` rings from the top to the neck's end,
/// `slices` around (the seam at the back, −Z).
pub fn sculpted_head(stacks: u32, slices: u32) -> Mesh {
    let (stacks, slices) = (stacks.max(8), slices.max(8));
    let pi = std::f32::consts::PI;
    let angles = |i: u32, j: u32| {
        (
            pi * i as f32 / stacks as f32,
            pi * (2.0 * j as f32 / slices as f32 - 1.0),
        )
    };
    let mut vertices = Vec::with_capacity(((stacks + 1) * (slices + 1)) as usize);
    for i in 0..=stacks {
        for j in 0..=slices {
            let (theta, phi) = angles(i, j);
            let normal = if i == 0 {
                Vec3::Y
            } else if i == stacks {
                -Vec3::Y
            } else {
                // ∂p/∂θ × ∂p/∂φ points out (θ grows downward, φ toward +X at the face).
                let (dt, dp) = (1e-3, 1e-3);
                let d_theta = surface(theta + dt, phi) - surface(theta - dt, phi);
                let d_phi = surface(theta, phi + dp) - surface(theta, phi - dp);
                d_theta.cross(d_phi).normalize()
            };
            vertices.push(MeshVertex {
                position: surface(theta, phi).to_array(),
                normal: normal.to_array(),
            });
        }
    }
    let indices = crate::mesh::grid_indices(stacks, slices);
    Mesh {
        name: "head".into(),
        vertices,
        indices,
        albedo: [0.75, 0.55, 0.45],
        head: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where the procedural groom roots (θ < 105°, not the face) the head is
    /// the ellipsoid: a groom grown over it keeps its roots on the skin.
    #[test]
    fn the_scalp_is_the_ellipsoid() {
        let scalp = crate::groom::ScalpRegion::default();
        for ti in 0..=105 {
            for pi in -180..180 {
                let (theta, phi) = ((ti as f32).to_radians(), (pi as f32).to_radians());
                let face = (pi as f32).abs() < scalp.face_half_width_degrees
                    && ti as f32 > scalp.face_polar_degrees;
                if ti as f32 <= scalp.max_polar_degrees && !face {
                    let d = displacement(theta, phi);
                    assert!(d.abs() < 1e-3, "θ {ti}° φ {pi}°: displaced {d}");
                }
            }
        }
    }

    /// Every triangle faces the way its vertices' normals do, has an area,
    /// and the features are there: the nose stands out of the ellipsoid,
    /// the neck reaches below it.
    #[test]
    fn closed_outward_with_a_face_and_a_neck() {
        let m = sculpted_head(96, 128);
        crate::mesh::assert_outward(&m);
        let front = m
            .vertices
            .iter()
            .map(|v| v.position[2])
            .fold(f32::MIN, f32::max);
        let lowest = m
            .vertices
            .iter()
            .map(|v| v.position[1])
            .fold(f32::MAX, f32::min);
        assert!(front > 1.1 * RADII.z, "nose at z = {front}");
        assert!(lowest < -RADII.y - 0.3, "neck down to y = {lowest}");
    }
}
