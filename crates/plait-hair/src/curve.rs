//! The smooth curve a strand stands for, as `plait export mitsuba` hands it
//! to the path tracer: the natural cubic spline through the strand's points
//! with one unit of parameter a segment (`crates/plait/src/mitsuba/write.rs`
//! writes the same curve as uniform B-spline control points).
//!
//! plait draws each segment straight, but shades it about this curve's
//! tangent: its vertex tangents are the spline's derivative directions at the
//! points ([`knot_directions`]), and `shaders/lib/strand_curve.wgsl` bends the
//! tangent between them as a cubic Hermite piece does. A tangent interpolated
//! linearly is up to several degrees off inside a segment that turns, which
//! moves the narrow R and TRT highlights (docs/formats.md, "Against the
//! path tracer: the shading tangent").

use glam::Vec3;

/// The natural cubic spline's derivatives at the points `p` (uniform
/// parameter, one unit a segment), from its tridiagonal system:
/// 2 D₀ + D₁ = 3 (p₁ − p₀); D₍ᵢ₋₁₎ + 4 Dᵢ + D₍ᵢ₊₁₎ = 3 (p₍ᵢ₊₁₎ − p₍ᵢ₋₁₎);
/// D₍ₙ₋₂₎ + 2 D₍ₙ₋₁₎ = 3 (p₍ₙ₋₁₎ − p₍ₙ₋₂₎) (the second derivative is 0 at
/// both ends), solved by Thomas's algorithm. Fewer than two points: none.
pub fn knot_derivatives(p: &[Vec3]) -> Vec<Vec3> {
    let n = p.len();
    if n < 2 {
        return vec![Vec3::ZERO; n];
    }
    let (mut lower, mut diag, mut upper) = (vec![1.0f32; n], vec![4.0f32; n], vec![1.0f32; n]);
    let mut rhs = vec![Vec3::ZERO; n];
    for i in 0..n {
        rhs[i] = 3.0 * (p[(i + 1).min(n - 1)] - p[i.saturating_sub(1)]);
    }
    diag[0] = 2.0;
    diag[n - 1] = 2.0;
    lower[0] = 0.0;
    upper[n - 1] = 0.0;
    // Forward elimination, then back substitution.
    for i in 1..n {
        let w = lower[i] / diag[i - 1];
        diag[i] -= w * upper[i - 1];
        rhs[i] = rhs[i] - w * rhs[i - 1];
    }
    let mut d = vec![Vec3::ZERO; n];
    d[n - 1] = rhs[n - 1] / diag[n - 1];
    for i in (0..n - 1).rev() {
        d[i] = (rhs[i] - upper[i] * d[i + 1]) / diag[i];
    }
    d
}

/// Unit tangents of the spline at the points (the directions of
/// [`knot_derivatives`]); where the derivative vanishes (repeated points),
/// the previous point's, and +Y before any.
pub fn knot_directions(p: &[Vec3]) -> Vec<Vec3> {
    let mut last = Vec3::Y;
    knot_derivatives(p)
        .into_iter()
        .map(|d| {
            let t = d.normalize_or_zero();
            if t != Vec3::ZERO {
                last = t;
            }
            last
        })
        .collect()
}

/// The shading tangent at `u` ∈ [0, 1] along the segment from `p0` to `p1`
/// with unit end tangents `t0`, `t1`: the derivative of the cubic Hermite
/// piece whose end derivatives are the tangents times the chord's length
/// (the spline's own lengths are not stored; on the wavy groom at 24
/// segments this piece's tangent is a median 0.3°, at most 1.5°, from the
/// spline's), normalized. The CPU twin of `strand_curve_tangent` in
/// `shaders/lib/strand_curve.wgsl`.
pub fn segment_tangent(p0: Vec3, p1: Vec3, t0: Vec3, t1: Vec3, u: f32) -> Vec3 {
    let chord = (p1 - p0).normalize_or_zero();
    if chord == Vec3::ZERO {
        // A segment of length 0 has no piece: its tangents, interpolated.
        return t0.lerp(t1, u).normalize_or_zero();
    }
    (6.0 * u * (1.0 - u) * chord + (1.0 - u) * (1.0 - 3.0 * u) * t0 + u * (3.0 * u - 2.0) * t1)
        .normalize_or_zero()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic Hermite piece's second derivative at u = 0 and u = 1.
    fn second(p0: Vec3, p1: Vec3, d0: Vec3, d1: Vec3) -> (Vec3, Vec3) {
        let c = p1 - p0;
        (
            6.0 * c - 4.0 * d0 - 2.0 * d1,
            -6.0 * c + 2.0 * d0 + 4.0 * d1,
        )
    }

    /// The defining properties of the natural spline: the pieces meet with
    /// equal curvature at every interior point and have none at the ends.
    #[test]
    fn knot_derivatives_make_the_natural_spline() {
        let p: Vec<Vec3> = (0..7)
            .map(|i| {
                let a = i as f32 * 0.6;
                Vec3::new(a.sin(), i as f32 * 0.3, (a * 0.7).cos() * 0.5)
            })
            .collect();
        let d = knot_derivatives(&p);
        let mut ends = vec![];
        for j in 0..p.len() - 1 {
            ends.push(second(p[j], p[j + 1], d[j], d[j + 1]));
        }
        assert!(ends[0].0.length() < 1e-4, "{:?}", ends[0].0);
        assert!(ends[ends.len() - 1].1.length() < 1e-4);
        for j in 1..ends.len() {
            assert!((ends[j - 1].1 - ends[j].0).length() < 1e-4, "knot {j}");
        }
    }

    /// Points on a straight line, evenly spaced: the spline is the line.
    #[test]
    fn a_straight_strand_keeps_its_direction() {
        let p: Vec<Vec3> = (0..5)
            .map(|i| Vec3::new(i as f32, 2.0 * i as f32, 0.0))
            .collect();
        for d in knot_derivatives(&p) {
            assert!((d - Vec3::new(1.0, 2.0, 0.0)).length() < 1e-5);
        }
        assert_eq!(knot_directions(&[Vec3::ONE]), vec![Vec3::Y]);
        assert_eq!(knot_directions(&[Vec3::ONE, Vec3::ONE]), vec![Vec3::Y; 2]);
    }

    /// On points of a circle, the piece's tangent at u stays within 0.5° of
    /// the circle's at the matching angle (a segment turning by 20°), and
    /// the linear interpolation of the end tangents does not at u = ¼.
    #[test]
    fn segment_tangent_follows_an_arc() {
        let step = 20f32.to_radians();
        let at = |a: f32| Vec3::new(a.cos(), a.sin(), 0.0);
        let tan = |a: f32| Vec3::new(-a.sin(), a.cos(), 0.0);
        let (p0, p1) = (at(0.0), at(step));
        for u in [0.0, 0.25, 0.5, 0.75, 1.0] {
            let t = segment_tangent(p0, p1, tan(0.0), tan(step), u);
            let angle = t.dot(tan(u * step)).clamp(-1.0, 1.0).acos().to_degrees();
            assert!(angle < 0.5, "u {u}: {angle}°");
        }
        assert_eq!(segment_tangent(p0, p0, Vec3::X, Vec3::X, 0.5), Vec3::X);
    }

    /// A wave sampled coarsely (each segment turns by tens of degrees, with
    /// inflections): the piece's tangent stays within 3° of the spline's own (2.5°)
    /// (its Hermite pieces with the spline's derivatives), where the end
    /// tangents interpolated linearly are more than 10° off somewhere (11.4°).
    #[test]
    fn segment_tangent_is_the_splines_where_lerp_is_not() {
        let p: Vec<Vec3> = (0..9)
            .map(|i| Vec3::new(i as f32 * 0.5, (i as f32 * 1.1).sin() * 0.5, 0.0))
            .collect();
        let (d, t) = (knot_derivatives(&p), knot_directions(&p));
        let (mut worst, mut worst_lerp) = (0f32, 0f32);
        for j in 0..p.len() - 1 {
            for u in [0.1, 0.25, 0.5, 0.75, 0.9] {
                let c = p[j + 1] - p[j];
                let exact = (6.0 * u * (1.0 - u) * c
                    + (1.0 - u) * (1.0 - 3.0 * u) * d[j]
                    + u * (3.0 * u - 2.0) * d[j + 1])
                    .normalize();
                let angle = |v: Vec3| v.dot(exact).clamp(-1.0, 1.0).acos().to_degrees();
                worst = worst.max(angle(segment_tangent(p[j], p[j + 1], t[j], t[j + 1], u)));
                worst_lerp = worst_lerp.max(angle(t[j].lerp(t[j + 1], u).normalize()));
            }
        }
        assert!(worst < 3.0, "the piece is {worst}° from the spline");
        assert!(
            worst_lerp > 10.0,
            "lerp only {worst_lerp}°: the case is too easy"
        );
    }
}
