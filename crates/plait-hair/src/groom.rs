//! Procedural grooms, deterministic by seed.
//!
//! Strands grow from a scalp region of an ellipsoidal head: they leave the
//! scalp along its normal, then bend downward under a gravity-like pull, and
//! are pushed out of the head so the hair drapes around it. Wavy and curly
//! styles add periodic offsets perpendicular to the strand. Stray strands
//! stand off the main volume — the case of Sintorn & Assarsson 2009 Fig. 4
//! and 5, where a lone strand between the light and the hair makes a sharp
//! early dip in visibility.
//!
//! Guide strands (Halén & Wester 2007 §2.5, after [ND05]): with
//! `guides = Some(g)`, about `g` guide strands grow at the vertices of a grid
//! over the scalp's (polar, azimuth) parameter square; the grid is
//! triangulated (two triangles per cell) and each rendered strand is the
//! barycentric blend of the three guides of the triangle its root falls in,
//! translated so that it starts at its own root. Done on the CPU.
//!
//! The PRNG is the in-crate [`SplitMix64`](crate::rng::SplitMix64): a few
//! lines, and its output can never change under us with a dependency update,
//! which keeps `seed = N` meaning the same groom forever.

use glam::Vec3;
use serde::Deserialize;

use crate::guides::{GuideBinding, Guides};
use crate::rng::SplitMix64;
use crate::strands::Strands;

/// Hair style.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Style {
    /// Smooth strands.
    #[default]
    Straight,
    /// Planar sine waves.
    Wavy,
    /// Helical curls.
    Curly,
}

impl std::str::FromStr for Style {
    type Err = String;
    fn from_str(s: &str) -> Result<Style, String> {
        match s {
            "straight" => Ok(Style::Straight),
            "wavy" => Ok(Style::Wavy),
            "curly" => Ok(Style::Curly),
            other => Err(format!(
                "unknown style {other:?} (expected straight, wavy or curly)"
            )),
        }
    }
}

/// The head the hair grows on: an ellipsoid.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeadShape {
    /// Center.
    pub center: [f32; 3],
    /// Semi-axes along x, y, z.
    pub radii: [f32; 3],
}

impl Default for HeadShape {
    fn default() -> Self {
        HeadShape {
            center: [0.0, 0.0, 0.0],
            radii: [0.9, 1.05, 1.0],
        }
    }
}

/// Where on the head hair grows, as angles on the ellipsoid's parameter
/// sphere: the polar angle is measured from the top (+Y), the face is toward +Z.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalpRegion {
    /// Largest polar angle (degrees from +Y) with hair at the back and sides.
    pub max_polar_degrees: f32,
    /// Largest polar angle over the face (the front, +Z side): the hairline.
    pub face_polar_degrees: f32,
    /// Half-width (degrees of azimuth around +Z) of the face region.
    pub face_half_width_degrees: f32,
}

impl Default for ScalpRegion {
    fn default() -> Self {
        ScalpRegion {
            max_polar_degrees: 105.0,
            face_polar_degrees: 50.0,
            face_half_width_degrees: 70.0,
        }
    }
}

/// A procedural groom. Every field has a default, so `[hair.procedural]`
/// may set only what it changes.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GroomSpec {
    /// straight, wavy or curly.
    pub style: Style,
    /// Number of rendered strands (not counting stray strands).
    pub strands: u32,
    /// Segments per strand (points = segments + 1), 1..=65535.
    pub segments: u32,
    /// PRNG seed; same seed, same groom.
    pub seed: u64,
    /// Mean strand length (model units).
    pub length: f32,
    /// Relative length variation: lengths are uniform in `length * (1 ± v)`.
    pub length_variation: f32,
    /// Root thickness (model units).
    pub thickness: f32,
    /// Relative thickness variation per strand.
    pub thickness_variation: f32,
    /// Tip thickness as a fraction of the root thickness.
    pub tip_thickness: f32,
    /// Strand opacity (1 - the format's transparency).
    pub alpha: f32,
    /// Absolute alpha variation per strand (clamped to 0..1).
    pub alpha_variation: f32,
    /// Base linear RGB color.
    pub color: [f32; 3],
    /// Per-strand brightness variation (relative).
    pub color_variation: f32,
    /// The head.
    pub head: HeadShape,
    /// Where hair grows.
    pub scalp: ScalpRegion,
    /// How strongly strands turn downward, per unit length.
    pub gravity: f32,
    /// Wave/curl amplitude (model units); `None` = the style's default.
    pub wave_amplitude: Option<f32>,
    /// Wave/curl period along the strand (model units); `None` = style default.
    pub wave_period: Option<f32>,
    /// Extra strands lifted off the main volume (appended after the others).
    pub stray_strands: u32,
    /// If set, about this many guide strands are grown and the rendered
    /// strands are interpolated from them (Halén & Wester 2007 §2.5).
    pub guides: Option<u32>,
}

impl Default for GroomSpec {
    fn default() -> Self {
        GroomSpec {
            style: Style::Straight,
            strands: 1000,
            segments: 16,
            seed: 1,
            length: 2.0,
            length_variation: 0.15,
            thickness: 0.006,
            thickness_variation: 0.2,
            tip_thickness: 0.4,
            alpha: 0.6,
            alpha_variation: 0.1,
            color: [0.32, 0.2, 0.11],
            color_variation: 0.15,
            head: HeadShape::default(),
            scalp: ScalpRegion::default(),
            gravity: 2.5,
            wave_amplitude: None,
            wave_period: None,
            stray_strands: 0,
            guides: None,
        }
    }
}

impl GroomSpec {
    /// Checks the numbers; the message names the offending field.
    pub fn validate(&self) -> Result<(), String> {
        if self.strands == 0 && self.stray_strands == 0 {
            return Err("strands must be at least 1".into());
        }
        if !(1..=65535).contains(&self.segments) {
            return Err(format!(
                "segments must be in 1..=65535, got {}",
                self.segments
            ));
        }
        let total = (u64::from(self.strands) + u64::from(self.stray_strands))
            * (u64::from(self.segments) + 1);
        // Refused before generating: past this the vertices outgrow memory
        // and any GPU buffer (see `follow::MAX_POINTS`).
        if total > crate::follow::MAX_POINTS {
            return Err(format!(
                "strands × (segments + 1) = {total} points exceeds plait's limit of {}",
                crate::follow::MAX_POINTS
            ));
        }
        let finite_nonneg = [
            ("length", self.length),
            ("length_variation", self.length_variation),
            ("thickness", self.thickness),
            ("thickness_variation", self.thickness_variation),
            ("tip_thickness", self.tip_thickness),
            ("alpha", self.alpha),
            ("alpha_variation", self.alpha_variation),
            ("color_variation", self.color_variation),
            ("gravity", self.gravity),
            ("wave_amplitude", self.wave_amplitude.unwrap_or(0.0)),
        ];
        for (name, v) in finite_nonneg {
            if !v.is_finite() || v < 0.0 {
                return Err(format!("{name} must be a finite number ≥ 0, got {v}"));
            }
        }
        if self.length <= 0.0 {
            return Err("length must be > 0".into());
        }
        if self.alpha > 1.0 {
            return Err(format!("alpha must be in 0..=1, got {}", self.alpha));
        }
        if let Some(p) = self.wave_period
            && !(p.is_finite() && p > 0.0)
        {
            return Err(format!("wave_period must be > 0, got {p}"));
        }
        if self.head.radii.iter().any(|r| !(r.is_finite() && *r > 0.0)) {
            return Err("head.radii must be finite and > 0".into());
        }
        if self
            .head
            .center
            .iter()
            .chain(&self.color)
            .any(|c| !c.is_finite())
        {
            return Err("head.center and color must be finite".into());
        }
        if self.guides == Some(0) {
            return Err("guides must be at least 1 (or absent)".into());
        }
        Ok(())
    }

    fn wave(&self) -> (f32, f32) {
        let (a, p) = match self.style {
            Style::Straight => (0.0, 1.0),
            Style::Wavy => (0.06, 0.5),
            Style::Curly => (0.05, 0.15),
        };
        (
            self.wave_amplitude.unwrap_or(a),
            self.wave_period.unwrap_or(p).max(1e-4),
        )
    }
}

/// Per-strand random attributes, drawn from the strand's own PRNG stream so
/// that strand `i` does not depend on how many other strands there are.
struct StrandLook {
    length: f32,
    thickness: f32,
    alpha: f32,
    color: Vec3,
    phase: f32,
}

fn look(spec: &GroomSpec, rng: &mut SplitMix64) -> StrandLook {
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
fn scalp_dir(spec: &GroomSpec, u: f32, v: f32) -> Vec3 {
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
fn sample_root(spec: &GroomSpec, rng: &mut SplitMix64) -> (f32, f32) {
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
fn head_point(spec: &GroomSpec, dir: Vec3) -> (Vec3, Vec3) {
    let r = Vec3::from(spec.head.radii).abs().max(Vec3::splat(1e-6));
    let p = Vec3::from(spec.head.center) + dir * r;
    (p, (dir / r).normalize_or(Vec3::Y))
}

/// Grows one strand centerline of `segments + 1` points from `root` along
/// `start_dir`, bending toward -Y and kept outside the (slightly inflated) head.
/// Horizontal unit vector of azimuth `v` (0 = +Z, the face).
fn azimuth_dir(v: f32) -> Vec3 {
    let phi = v * std::f32::consts::TAU;
    Vec3::new(phi.sin(), 0.0, phi.cos())
}

/// The direction a strand leaves the scalp: the normal, combed outward
/// along its azimuth so crown strands part instead of standing up.
fn comb(normal: Vec3, v: f32) -> Vec3 {
    (normal + azimuth_dir(v) * 0.6).normalize_or(normal)
}

fn grow(
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
fn add_waves(spec: &GroomSpec, pts: &mut [Vec3], phase: f32) {
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

fn push(strands: &mut Strands, spec: &GroomSpec, pts: &[Vec3], lk: &StrandLook) {
    let tip = spec.tip_thickness;
    let th = lk.thickness;
    let alpha = lk.alpha;
    strands.push_strand(pts, |t| th * (1.0 + (tip - 1.0) * t), |_| alpha, lk.color);
}

/// Generates the groom. Deterministic: the same spec gives bit-identical
/// strands. Out-of-range numbers are clamped (call [`GroomSpec::validate`]
/// first to report them instead).
pub fn generate(spec: &GroomSpec) -> Strands {
    generate_guided(spec).0
}

/// [`generate`], and with `guides = Some(g)` the guide strands and every
/// rendered strand's binding to them (stray strands are guides of their own),
/// for simulating the guides and interpolating the rest on the GPU.
pub fn generate_guided(spec: &GroomSpec) -> (Strands, Option<Guides>) {
    let mut strands = Strands::new();
    let mut guided: Option<Guides> = None;
    let lift_of = |u: f32| 0.02 + 0.06 * (1.0 - u); // crown strands lie on top of lower ones
    match spec.guides {
        None | Some(0) => {
            for i in 0..spec.strands {
                let mut rng = SplitMix64::stream(spec.seed, u64::from(i));
                let (u, v) = sample_root(spec, &mut rng);
                let lk = look(spec, &mut rng);
                let (root, normal) = head_point(spec, scalp_dir(spec, u, v));
                let mut pts = grow(
                    spec,
                    root,
                    comb(normal, v),
                    lk.length,
                    spec.gravity,
                    lift_of(u),
                );
                add_waves(spec, &mut pts, lk.phase);
                push(&mut strands, spec, &pts, &lk);
            }
        }
        Some(g) => guided = Some(interpolate_from_guides(spec, g, &mut strands, lift_of)),
    }
    for i in 0..spec.stray_strands {
        let mut rng = SplitMix64::stream(spec.seed ^ 0x0057_12A7, u64::from(i));
        // strays start near the crown and arc up and out of the volume
        let u = rng.range(0.05, 0.45);
        let v = rng.next_f32();
        let lk = look(spec, &mut rng);
        let (root, normal) = head_point(spec, scalp_dir(spec, u, v));
        let side = Vec3::new(normal.x, 0.0, normal.z).normalize_or(Vec3::Z);
        let dir = (normal + side * 0.6 + Vec3::Y * 0.4).normalize();
        let mut pts = grow(spec, root, dir, lk.length * 0.8, spec.gravity * 0.25, 0.35);
        add_waves(spec, &mut pts, lk.phase);
        push(&mut strands, spec, &pts, &lk);
        if let Some(g) = &mut guided {
            // A stray strand is a guide of its own: weight 1 on itself.
            g.bindings.push(GuideBinding {
                guides: [g.strands.strand_count() as u32; 3],
                weights: [1.0, 0.0, 0.0],
                root: pts[0],
                scale: 1.0,
            });
            push(&mut g.strands, spec, &pts, &lk);
        }
    }
    (strands, guided)
}

/// Guide grid layout for about `g` guides: `rows` polar rings (u = 0..=1)
/// times `cols` azimuth columns (v wraps around).
fn guide_grid(g: u32) -> (usize, usize) {
    let rows = ((g as f32 / 2.0).sqrt().round() as usize).max(2);
    let cols = (g as usize / rows).max(3);
    (rows, cols)
}

/// The triangle of the guide grid that scalp parameter (u, v) falls in:
/// grid corners `(row, col)` (col may equal `cols`, meaning column 0) and
/// barycentric weights (≥ 0, summing to 1). Each grid cell is split along
/// its anti-diagonal into two triangles.
fn locate(u: f32, v: f32, rows: usize, cols: usize) -> ([(usize, usize); 3], [f32; 3]) {
    let fu = u.clamp(0.0, 1.0) * (rows - 1) as f32;
    let fv = v.clamp(0.0, 1.0) * cols as f32;
    let i = (fu.floor() as usize).min(rows - 2);
    let j = (fv.floor() as usize).min(cols - 1);
    let (a, b) = (
        (fu - i as f32).clamp(0.0, 1.0),
        (fv - j as f32).clamp(0.0, 1.0),
    );
    if a + b <= 1.0 {
        ([(i, j), (i + 1, j), (i, j + 1)], [1.0 - a - b, a, b])
    } else {
        (
            [(i + 1, j + 1), (i, j + 1), (i + 1, j)],
            [a + b - 1.0, 1.0 - a, 1.0 - b],
        )
    }
}

/// Barycentric blend of three guide strands (Halén & Wester 2007 §2.5), translated so it
/// starts at `root`, its offsets from the root scaled by `scale`.
fn blend(tri: [&Vec<Vec3>; 3], w: [f32; 3], root: Vec3, scale: f32) -> Vec<Vec3> {
    let n = tri.iter().map(|g| g.len()).min().unwrap_or(0);
    if n == 0 {
        return Vec::new();
    }
    let at = |k: usize| tri[0][k] * w[0] + tri[1][k] * w[1] + tri[2][k] * w[2];
    let start = at(0);
    (0..n).map(|k| root + (at(k) - start) * scale).collect()
}

fn interpolate_from_guides(
    spec: &GroomSpec,
    g: u32,
    strands: &mut Strands,
    lift_of: impl Fn(f32) -> f32,
) -> Guides {
    let (rows, cols) = guide_grid(g);
    // Guides: grown with the mean length, with their own wave phase.
    let mut guides: Vec<Vec<Vec3>> = Vec::with_capacity(rows * cols);
    for i in 0..rows {
        for j in 0..cols {
            let u = i as f32 / (rows - 1) as f32;
            let v = j as f32 / cols as f32;
            let mut rng = SplitMix64::stream(spec.seed ^ 0x006D_1DE5, (i * cols + j) as u64);
            let phase = rng.range(0.0, std::f32::consts::TAU);
            let (root, normal) = head_point(spec, scalp_dir(spec, u, v));
            let mut pts = grow(
                spec,
                root,
                comb(normal, v),
                spec.length,
                spec.gravity,
                lift_of(u),
            );
            add_waves(spec, &mut pts, phase);
            guides.push(pts);
        }
    }
    let index = |i: usize, j: usize| i.min(rows - 1) * cols + j % cols;
    let mut bindings = Vec::with_capacity(spec.strands as usize);
    for s in 0..spec.strands {
        let mut rng = SplitMix64::stream(spec.seed, u64::from(s));
        let (u, v) = sample_root(spec, &mut rng);
        let lk = look(spec, &mut rng);
        let (corners, w) = locate(u, v, rows, cols);
        let ids = corners.map(|(i, j)| index(i, j));
        let tri = ids.map(|k| &guides[k]);
        let (root, _) = head_point(spec, scalp_dir(spec, u, v));
        let scale = lk.length / spec.length.max(1e-6);
        let pts = blend(tri, w, root, scale);
        push(strands, spec, &pts, &lk);
        bindings.push(GuideBinding {
            guides: ids.map(|k| k as u32),
            weights: w,
            root,
            scale,
        });
    }
    let mut guide_strands = Strands::new();
    for pts in &guides {
        let lk = StrandLook {
            length: spec.length,
            thickness: spec.thickness,
            alpha: spec.alpha,
            color: Vec3::from(spec.color),
            phase: 0.0,
        };
        push(&mut guide_strands, spec, pts, &lk);
    }
    Guides {
        strands: guide_strands,
        bindings,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(style: Style) -> GroomSpec {
        GroomSpec {
            style,
            strands: 200,
            segments: 12,
            seed: 7,
            ..GroomSpec::default()
        }
    }

    fn head_level(spec: &GroomSpec, p: Vec3) -> f32 {
        ((p - Vec3::from(spec.head.center)) / Vec3::from(spec.head.radii)).length()
    }

    #[test]
    fn deterministic_by_seed_and_counts() {
        for style in [Style::Straight, Style::Wavy, Style::Curly] {
            let s = spec(style);
            let a = generate(&s);
            let b = generate(&s);
            assert_eq!(a, b);
            assert_eq!(a.strand_count(), 200);
            assert_eq!(a.point_count(), 200 * 13);
            assert_eq!(a.segment_count(), 200 * 12);
            let c = generate(&GroomSpec {
                seed: 8,
                ..s.clone()
            });
            assert_ne!(a.points, c.points);
            assert!(a.points.iter().all(|p| p.is_finite()));
        }
    }

    #[test]
    fn roots_on_scalp_hair_drapes_outside_head() {
        let s = spec(Style::Straight);
        let h = generate(&s);
        for r in h.ranges() {
            let pts = &h.points[r];
            assert!(
                (head_level(&s, pts[0]) - 1.0).abs() < 1e-3,
                "root on the head surface"
            );
            assert!(pts[0].z < 0.95 || pts[0].y > 0.3, "no roots on the face");
            for p in &pts[1..] {
                assert!(head_level(&s, *p) > 0.999, "hair stays outside the head");
            }
            // it drapes: the tip is lower than the root
            assert!(pts[pts.len() - 1].y < pts[0].y);
        }
        // variation: strands differ in thickness, alpha and color
        assert!(
            h.thickness
                .iter()
                .any(|&t| (t - h.thickness[0]).abs() > 1e-6)
        );
        assert!(h.alpha.iter().any(|&a| a != h.alpha[0]));
        assert!(h.color.iter().any(|&c| c != h.color[0]));
        assert!(h.alpha.iter().all(|a| (0.0..=1.0).contains(a)));
    }

    fn mean_deviation_from_chord(h: &Strands) -> f32 {
        let mut sum = 0.0;
        let mut n = 0;
        for r in h.ranges() {
            let p = &h.points[r];
            for k in 1..p.len() - 1 {
                // second difference magnitude ~ local wiggle
                sum += (p[k - 1] + p[k + 1] - 2.0 * p[k]).length();
                n += 1;
            }
        }
        sum / n as f32
    }

    #[test]
    fn wavy_and_curly_wiggle_more_than_straight() {
        // enough segments to resolve the curl period
        let fine = |style| GroomSpec {
            segments: 64,
            ..spec(style)
        };
        let st = mean_deviation_from_chord(&generate(&fine(Style::Straight)));
        let wv = mean_deviation_from_chord(&generate(&fine(Style::Wavy)));
        let cu = mean_deviation_from_chord(&generate(&fine(Style::Curly)));
        assert!(wv > st * 1.2, "wavy {wv} vs straight {st}");
        assert!(cu > wv, "curly {cu} vs wavy {wv}");
    }

    #[test]
    fn stray_strands_stand_off_the_volume() {
        let s = GroomSpec {
            stray_strands: 5,
            ..spec(Style::Straight)
        };
        let h = generate(&s);
        assert_eq!(h.strand_count(), 205);
        let main = &h.points[..200 * 13];
        for i in 200..205 {
            // the farthest point of the stray from the main volume
            let off = h
                .strand(i)
                .iter()
                .map(|p| {
                    main.iter()
                        .map(|q| (*p - *q).length())
                        .fold(f32::INFINITY, f32::min)
                })
                .fold(0.0f32, f32::max);
            assert!(off > 0.2, "stray {i} only {off} away from the main volume");
            assert!(
                (head_level(&s, h.strand(i)[0]) - 1.0).abs() < 1e-3,
                "stray roots on the scalp"
            );
        }
    }

    #[test]
    fn guide_interpolation_is_barycentric() {
        let s = GroomSpec {
            guides: Some(60),
            style: Style::Wavy,
            ..spec(Style::Straight)
        };
        let h = generate(&s);
        assert_eq!(h.strand_count(), 200);
        assert_eq!(h.point_count(), 200 * 13);
        assert_eq!(h, generate(&s));
        // every rendered strand starts on the scalp and follows the guides'
        // overall shape (drapes down)
        for r in h.ranges() {
            let p = &h.points[r];
            assert!((head_level(&s, p[0]) - 1.0).abs() < 1e-3);
            assert!(p[p.len() - 1].y < p[0].y);
        }
        let (rows, cols) = guide_grid(60);
        assert!(rows * cols >= 40 && rows >= 2 && cols >= 3);
    }

    #[test]
    fn scalp_triangulation_gives_true_barycentric_coordinates() {
        let (rows, cols) = (5, 8);
        let mut rng = SplitMix64::new(3);
        for _ in 0..1000 {
            let (u, v) = (rng.next_f32(), rng.next_f32());
            let (corners, w) = locate(u, v, rows, cols);
            assert!(w.iter().all(|&x| x >= -1e-6), "{w:?}");
            assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-5);
            // the weighted corner parameters reproduce (u, v)
            let mut pu = 0.0;
            let mut pv = 0.0;
            for ((i, j), wt) in corners.iter().zip(w) {
                pu += wt * *i as f32 / (rows - 1) as f32;
                pv += wt * *j as f32 / cols as f32;
            }
            assert!(
                (pu - u).abs() < 1e-4 && (pv - v).abs() < 1e-4,
                "({u},{v}) -> ({pu},{pv})"
            );
        }
    }

    #[test]
    fn blend_reproduces_guides_and_averages() {
        let g0 = vec![
            Vec3::ZERO,
            Vec3::new(0.0, -1.0, 0.0),
            Vec3::new(0.5, -2.0, 0.0),
        ];
        let g1 = vec![
            Vec3::X,
            Vec3::new(1.0, -1.0, 1.0),
            Vec3::new(1.0, -2.0, 2.0),
        ];
        let g2 = vec![
            Vec3::Z,
            Vec3::new(0.0, -1.0, 1.0),
            Vec3::new(0.0, -3.0, 1.0),
        ];
        // weight 1 on a guide: that guide, moved to the new root
        let b = blend([&g0, &g1, &g2], [0.0, 1.0, 0.0], Vec3::X, 1.0);
        assert_eq!(b, g1);
        let b = blend([&g0, &g1, &g2], [1.0, 0.0, 0.0], Vec3::Y, 1.0);
        assert_eq!(b, g0.iter().map(|p| *p + Vec3::Y).collect::<Vec<_>>());
        // equal weights: the average shape
        let w = 1.0 / 3.0;
        let b = blend([&g0, &g1, &g2], [w, w, w], Vec3::ZERO, 1.0);
        let avg_tip = (g0[2] + g1[2] + g2[2]) * w - (g0[0] + g1[0] + g2[0]) * w;
        assert!((b[2] - avg_tip).length() < 1e-5);
    }

    #[test]
    fn validate_names_fields() {
        assert!(GroomSpec::default().validate().is_ok());
        let e = GroomSpec {
            segments: 0,
            ..GroomSpec::default()
        }
        .validate()
        .unwrap_err();
        assert!(e.contains("segments"));
        let e = GroomSpec {
            segments: 70000,
            ..GroomSpec::default()
        }
        .validate()
        .unwrap_err();
        assert!(e.contains("segments"));
        let e = GroomSpec {
            length: f32::NAN,
            ..GroomSpec::default()
        }
        .validate()
        .unwrap_err();
        assert!(e.contains("length"));
        let e = GroomSpec {
            strands: u32::MAX,
            segments: 65535,
            ..GroomSpec::default()
        }
        .validate()
        .unwrap_err();
        assert!(e.contains("points"));
    }

    #[test]
    fn spec_parses_from_toml_and_rejects_unknown_fields() {
        let s: GroomSpec =
            toml::from_str("style = \"curly\"\nstrands = 10\nguides = 30\n").expect("parse");
        assert_eq!(s.style, Style::Curly);
        assert_eq!(s.guides, Some(30));
        assert_eq!(s.segments, GroomSpec::default().segments);
        assert!(toml::from_str::<GroomSpec>("strandz = 3").is_err());
    }
}
