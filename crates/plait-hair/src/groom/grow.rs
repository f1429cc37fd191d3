//! Growing one strand: its random look from its own PRNG stream, a root
//! sampled on the scalp, a centerline bent by gravity and kept outside the
//! head, the style's waves or curls, and its per-point thickness and alpha.

use glam::Vec3;

use super::spec::{GroomSpec, Style};
use crate::rng::SplitMix64;
use crate::strands::Strands;

/// Per-strand random attributes, drawn from the strand's own PRNG stream so
/// that strand `i` does not depend on how many other strands there are.
pub(super) struct StrandLook {
    pub(super) length: f32,
    pub(super) thickness: f32,
    pub(super) alpha: f32,
    pub(super) color: Vec3,
    pub(super) phase: f32,
}

pub(super) fn look(spec: &GroomSpec, rng: &mut SplitMix64) -> StrandLook {
    let length = spec.length * (1.0 + spec.length_variation * rng.signed()).max(0.05);
    let thickness = (spec.thickness * (1.0 + spec.thickness_variation * rng.signed())).max(0.0);
    let alpha = (spec.alpha + spec.alpha_variation * rng.signed()).clamp(0.0, 1.0);
    let bright = (1.0 + spec.color_variation * rng.signed()).max(0.0);
    let tint = Vec3::new(rng.signed(), rng.signed(), rng.signed()) * spec.color_variation * 0.15;
    let color = ((Vec3::from(spec.color) + tint) * bright).max(Vec3::ZERO);
    StrandLook {
        length,
        thickness,
        alpha,
        color,
        phase: rng.range(0.0, std::f32::consts::TAU),
    }
}

/// Scalp parameter (u, v) in [0,1]² → unit direction on the parameter sphere.
/// u maps to polar angle 0..max_polar, v to azimuth 0..2π (v = 0 is the face, +Z).
pub(super) fn scalp_dir(spec: &GroomSpec, u: f32, v: f32) -> Vec3 {
    let theta = u * spec.scalp.max_polar_degrees.to_radians();
    let phi = v * std::f32::consts::TAU;
    Vec3::new(
        theta.sin() * phi.sin(),
        theta.cos(),
        theta.sin() * phi.cos(),
    )
}

fn in_scalp(spec: &GroomSpec, u: f32, v: f32) -> bool {
    let theta = u * spec.scalp.max_polar_degrees;
    let az = (v * 360.0 + 180.0).rem_euclid(360.0) - 180.0; // -180..180, 0 = face
    !(az.abs() < spec.scalp.face_half_width_degrees && theta > spec.scalp.face_polar_degrees)
}

/// A random scalp parameter, area-uniform over the cap, outside the face.
pub(super) fn sample_root(spec: &GroomSpec, rng: &mut SplitMix64) -> (f32, f32) {
    let max = spec
        .scalp
        .max_polar_degrees
        .to_radians()
        .clamp(1e-3, std::f32::consts::PI);
    let mut last = (0.0, 0.0);
    for _ in 0..64 {
        let cos_t = 1.0 - rng.next_f32() * (1.0 - max.cos());
        let u = (cos_t.clamp(-1.0, 1.0).acos() / max).clamp(0.0, 1.0);
        let v = rng.next_f32();
        last = (u, v);
        if in_scalp(spec, u, v) {
            return last;
        }
    }
    (
        last.0
            .min(spec.scalp.face_polar_degrees / spec.scalp.max_polar_degrees.max(1e-3)),
        last.1,
    )
}

/// Surface point and outward normal of the head for a parameter direction.
pub(super) fn head_point(spec: &GroomSpec, dir: Vec3) -> (Vec3, Vec3) {
    let r = Vec3::from(spec.head.radii).abs().max(Vec3::splat(1e-6));
    let p = Vec3::from(spec.head.center) + dir * r;
    (p, (dir / r).normalize_or(Vec3::Y))
}

/// Horizontal unit vector of azimuth `v` (0 = +Z, the face).
fn azimuth_dir(v: f32) -> Vec3 {
    let phi = v * std::f32::consts::TAU;
    Vec3::new(phi.sin(), 0.0, phi.cos())
}

/// The direction a strand leaves the scalp: the normal, combed outward
/// along its azimuth so crown strands part instead of standing up.
pub(super) fn comb(normal: Vec3, v: f32) -> Vec3 {
    (normal + azimuth_dir(v) * 0.6).normalize_or(normal)
}

/// Grows one strand centerline of `segments + 1` points from `root` along
/// `start_dir`, bending toward -Y and kept outside the (slightly inflated) head.
pub(super) fn grow(
    spec: &GroomSpec,
    root: Vec3,
    start_dir: Vec3,
    length: f32,
    gravity: f32,
    lift: f32,
) -> Vec<Vec3> {
    let n = spec.segments.max(1) as usize;
    let step = length / n as f32;
    let center = Vec3::from(spec.head.center);
    let r = Vec3::from(spec.head.radii).abs().max(Vec3::splat(1e-6));
    let mut pts = Vec::with_capacity(n + 1);
    let mut p = root;
    let mut d = start_dir;
    pts.push(p);
    for k in 0..n {
        d = (d + Vec3::NEG_Y * gravity * step).normalize_or(Vec3::NEG_Y);
        p += d * step;
        // keep outside the head, layered by the strand's root-dependent lift
        let shell = 1.0 + lift * ((k + 1) as f32 / n as f32).min(1.0);
        let q = (p - center) / r;
        let len = q.length();
        if len < shell && len > 1e-6 {
            p = center + q / len * shell * r;
            // slide along the surface: remove the inward component
            let nrm = (q / r).normalize_or(Vec3::Y);
            d = (d - nrm * d.dot(nrm).min(0.0)).normalize_or(Vec3::NEG_Y);
        }
        pts.push(p);
    }
    pts
}

/// Adds the style's periodic offsets perpendicular to the strand, ramping in
/// from the root so roots stay on the scalp.
pub(super) fn add_waves(spec: &GroomSpec, pts: &mut [Vec3], phase: f32) {
    let (amp, period) = spec.wave();
    if spec.style == Style::Straight || amp == 0.0 || pts.len() < 2 {
        return;
    }
    let base: Vec<Vec3> = pts.to_vec();
    let mut s = 0.0f32;
    let mut prev_b1 = Vec3::X;
    for k in 1..base.len() {
        s += (base[k] - base[k - 1]).length();
        let t = (base[(k + 1).min(base.len() - 1)] - base[k - 1]).normalize_or(Vec3::NEG_Y);
        // a frame perpendicular to the tangent, kept continuous along the strand
        let mut b1 = (prev_b1 - t * prev_b1.dot(t)).normalize_or_zero();
        if b1 == Vec3::ZERO {
            b1 = t.any_orthonormal_vector();
        }
        prev_b1 = b1;
        let b2 = t.cross(b1);
        let ramp = (s / (0.15 * spec.length.max(1e-3))).min(1.0);
        let a = std::f32::consts::TAU * s / period + phase;
        let off = match spec.style {
            Style::Wavy => b1 * a.sin(),
            Style::Curly => b1 * a.sin() + b2 * a.cos() - b2 * phase.cos(),
            Style::Straight => Vec3::ZERO,
        };
        pts[k] = base[k] + off * amp * ramp;
    }
}

pub(super) fn push(strands: &mut Strands, spec: &GroomSpec, pts: &[Vec3], lk: &StrandLook) {
    let tip = spec.tip_thickness;
    let th = lk.thickness;
    let alpha = lk.alpha;
    strands.push_strand(pts, |t| th * (1.0 + (tip - 1.0) * t), |_| alpha, lk.color);
}
