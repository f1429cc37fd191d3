//! Follow strands around guide strands, as TressFX generates them at load
//! (TressFX files hold guides only): each guide gets `count` copies whose
//! roots are offset within `radius` of its root, in the plane across the
//! root segment, and whose offset grows along the strand by
//! `1 + tip_spread · t` (t = 0 at the root, 1 at the tip) — TressFX's "tip
//! separation factor": 0 keeps follows parallel to their guide, > 0 fans
//! them out toward the tip, -1 gathers them onto it.
//!
//! Unlike TressFX, offsets are uniform over a disc (TressFX draws two
//! independent uniform numbers, a square) and deterministic by `seed`
//! (plait's [`SplitMix64`], as the procedural grooms are). A follow strand
//! takes its guide's thickness, opacity and colour.

use glam::Vec3;
use serde::Deserialize;

use crate::rng::SplitMix64;
use crate::strands::Strands;

/// Most points plait will build from a groom: 2^27 points are 6 GiB of
/// vertices, past any GPU buffer limit, so larger requests are refused
/// before allocating.
pub const MAX_POINTS: u64 = 1 << 27;

/// Follow strands per guide (the scene's `[hair]` `follow_*` fields).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowStrands {
    /// Follow strands added per guide strand.
    pub count: u32,
    /// Largest root offset from the guide's root, in the groom file's units.
    pub radius: f32,
    /// Growth of the offset toward the tip (TressFX's tip separation factor).
    pub tip_spread: f32,
    /// Seed of the offsets.
    pub seed: u64,
}

impl FollowStrands {
    /// Checks the numbers; the message names the field.
    pub fn validate(&self) -> Result<(), String> {
        if !(self.radius.is_finite() && self.radius >= 0.0) {
            return Err(format!(
                "follow_radius must be finite and ≥ 0, got {}",
                self.radius
            ));
        }
        if !(self.tip_spread.is_finite() && self.tip_spread >= -1.0) {
            return Err(format!(
                "follow_tip_spread must be finite and ≥ -1, got {}",
                self.tip_spread
            ));
        }
        Ok(())
    }

    /// Points the guides plus their follows will have, checked against
    /// [`MAX_POINTS`] before anything is allocated.
    pub fn check_size(&self, guides: &Strands) -> Result<u64, String> {
        let total = guides.point_count() as u64 * (u64::from(self.count) + 1);
        if total > MAX_POINTS {
            return Err(format!(
                "follow_strands = {} gives {} guides × {} = {total} points, more than plait builds ({MAX_POINTS})",
                self.count,
                guides.strand_count(),
                u64::from(self.count) + 1
            ));
        }
        Ok(total)
    }

    /// The guides, each followed by its follow strands (TressFX's order).
    /// Call [`FollowStrands::check_size`] first; this clamps nothing.
    pub fn apply(&self, guides: &Strands) -> Strands {
        let mut out = Strands::new();
        let capacity = guides.point_count() * (self.count as usize + 1);
        out.points.reserve(capacity);
        out.thickness.reserve(capacity);
        out.alpha.reserve(capacity);
        out.color.reserve(capacity);
        for (g, range) in guides.ranges().enumerate() {
            copy_strand(&mut out, guides, range.clone(), |_, p| p);
            let pts = &guides.points[range.clone()];
            if pts.is_empty() {
                continue;
            }
            let (t0, t1) = across(pts);
            let last = (pts.len() - 1).max(1) as f32;
            let mut rng = SplitMix64::stream(self.seed, g as u64);
            for _ in 0..self.count {
                let offset = disc_point(&mut rng, self.radius);
                let offset = t0 * offset.x + t1 * offset.y;
                copy_strand(&mut out, guides, range.clone(), |k, p| {
                    p + offset * (1.0 + self.tip_spread * k as f32 / last)
                });
            }
        }
        out
    }
}

/// Appends strand `range` of `from`, its points mapped by `place(k, point)`.
fn copy_strand(
    out: &mut Strands,
    from: &Strands,
    range: std::ops::Range<usize>,
    place: impl Fn(usize, Vec3) -> Vec3,
) {
    for (k, i) in range.enumerate() {
        out.points.push(place(k, from.points[i]));
        out.thickness
            .push(from.thickness.get(i).copied().unwrap_or(1.0));
        out.alpha.push(from.alpha.get(i).copied().unwrap_or(1.0));
        out.color
            .push(from.color.get(i).copied().unwrap_or(Vec3::ONE));
    }
    out.offsets.push(out.points.len() as u32);
}

/// Two unit vectors across the strand's root segment (any pair for a
/// degenerate strand).
fn across(pts: &[Vec3]) -> (Vec3, Vec3) {
    let dir = pts
        .windows(2)
        .map(|w| w[1] - w[0])
        .find(|d| d.length_squared() > 0.0)
        .map_or(Vec3::Y, Vec3::normalize);
    dir.any_orthonormal_pair()
}

/// A point uniform over the disc of `radius` (x, y).
fn disc_point(rng: &mut SplitMix64, radius: f32) -> glam::Vec2 {
    let r = radius * rng.next_f32().sqrt();
    let a = rng.range(0.0, std::f32::consts::TAU);
    glam::Vec2::new(r * a.cos(), r * a.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn guides() -> Strands {
        let mut s = Strands::new();
        let line = |x: f32| [0.0, 1.0, 2.0, 3.0].map(|y| Vec3::new(x, -y, 0.0));
        s.push_strand(&line(0.0), |t| 0.1 * (1.0 - t), |_| 0.5, Vec3::X);
        s.push_strand(&line(5.0), |_| 0.2, |_| 0.7, Vec3::Y);
        s
    }

    #[test]
    fn follows_surround_their_guide_and_spread_toward_the_tip() {
        let g = guides();
        let spec = FollowStrands {
            count: 6,
            radius: 0.5,
            tip_spread: 1.0,
            seed: 7,
        };
        let out = spec.apply(&g);
        assert_eq!(out.strand_count(), 2 * 7);
        assert_eq!(out.point_count() as u64, spec.check_size(&g).expect("fits"));
        for s in 0..out.strand_count() {
            let guide = s / 7;
            let (pts, gp) = (out.strand(s), g.strand(guide));
            let root_offset = pts[0] - gp[0];
            // across the root segment (the guide runs along -Y), within the radius
            assert!(root_offset.y.abs() < 1e-6 && root_offset.length() <= 0.5 + 1e-6);
            // the tip's offset is twice the root's (1 + tip_spread)
            let tip_offset = pts[3] - gp[3];
            assert!((tip_offset - root_offset * 2.0).length() < 1e-5);
            // the look comes from the guide
            let r = out.strand_range(s);
            assert_eq!(out.color[r.start], g.color[g.strand_range(guide).start]);
            assert_eq!(
                out.thickness[r.end - 1],
                g.thickness[g.strand_range(guide).end - 1]
            );
        }
        // the guide itself comes first, unchanged; follows differ
        assert_eq!(out.strand(0), g.strand(0));
        assert_ne!(out.strand(1), out.strand(2));
        // deterministic by seed
        assert_eq!(spec.apply(&g), out);
        let other = FollowStrands {
            seed: 8,
            ..spec.clone()
        }
        .apply(&g);
        assert_ne!(other, out);
    }

    #[test]
    fn gathering_onto_the_tip_and_limits() {
        let g = guides();
        let spec = FollowStrands {
            count: 3,
            radius: 0.2,
            tip_spread: -1.0,
            seed: 1,
        };
        let out = spec.apply(&g);
        for s in 0..out.strand_count() {
            assert!((out.strand(s)[3] - g.strand(s / 4)[3]).length() < 1e-6);
        }
        let absurd = FollowStrands {
            count: u32::MAX,
            ..spec.clone()
        };
        let e = absurd.check_size(&g).unwrap_err();
        assert!(e.contains("follow_strands"), "{e}");
        let bad = FollowStrands {
            radius: f32::NAN,
            ..spec.clone()
        };
        assert!(bad.validate().unwrap_err().contains("follow_radius"));
        let bad = FollowStrands {
            tip_spread: -2.0,
            ..spec
        };
        assert!(bad.validate().unwrap_err().contains("follow_tip_spread"));
    }
}
