//! The look a groom read from a file gets when the file leaves it out: the
//! procedural groom's, so a TressFX asset renders as hair and not as the
//! format's placeholders.
//!
//! A `.tfx` file holds positions; TressFX's exporters write no thickness and
//! no colour (both offsets 0) because TressFX's renderer takes the fibre
//! radius, colour and opacity from its own settings. plait reads the absent
//! arrays as thickness 1 and opaque white — placeholders that make every
//! strand a fully covered, unshaded-white line (issue 20: the mohawk renders
//! as a saturated white blob). A scene's groom gets, instead:
//!
//! - colour and opacity: [`GroomSpec::default`]'s per-strand look (brown
//!   `color` ± `color_variation`, `alpha` ± `alpha_variation`), the built-in
//!   groom's material, drawn per strand by the groom's PRNG so strands differ;
//! - thickness: a root width tapering to `tip_thickness` whose size is set by
//!   density, not by the file's units: wide enough that the groom's strands
//!   cover its silhouette as many times over as the built-in scene's groom
//!   covers its own ([`REFERENCE_OPTICAL_DEPTH`]). A rendered strand stands
//!   for many real fibres (a head has ~100,000; assets hold a few thousand
//!   guides and followers), so its width must grow as the count falls, and a
//!   denser asset gets thinner strands: either way the hair is as see-through
//!   as the built-in groom's under the same alpha.
//!
//! `.hair` files are left alone: their header always states a default
//! thickness, transparency and colour, which are the author's.

use super::GroomSpec;
use super::grow::look;
use crate::rng::SplitMix64;
use crate::strands::{Aabb, Strands};

/// How many times over the strands of the built-in scene's groom (10,000
/// wavy strands, 0.006 thick at the root, `Scene::builtin_default`) cover its
/// silhouette: Σ segment length × width over the mean projected area of the
/// groom's bounds (a test measures it from that groom).
pub const REFERENCE_OPTICAL_DEPTH: f32 = 5.49;

/// Which parts of the look a file left out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Missing {
    /// No thickness: every strand has the format's placeholder width.
    pub thickness: bool,
    /// No colour and opacity (TressFX keeps them together, as RGBA).
    pub color: bool,
}

impl Missing {
    /// Nothing is missing.
    pub fn none(&self) -> bool {
        !self.thickness && !self.color
    }
}

/// The strands' optical depth: Σ over segments of length × mean width,
/// divided by the mean projected area of their bounding box (a quarter of
/// its surface area, Cauchy's formula for a convex body). Unchanged by a
/// uniform scale, so it compares grooms in any units. 0 for no strands or
/// bounds without area.
pub fn optical_depth(strands: &Strands) -> f32 {
    let mut covered = 0.0f64;
    for r in strands.ranges() {
        for i in r.start..r.end.saturating_sub(1) {
            let length = strands.points[i].distance(strands.points[i + 1]) as f64;
            let width = at(&strands.thickness, i) + at(&strands.thickness, i + 1);
            covered += length * width as f64 * 0.5;
        }
    }
    let area = mean_projected_area(strands.bounds());
    if area > 0.0 {
        (covered / area) as f32
    } else {
        0.0
    }
}

fn at(v: &[f32], i: usize) -> f32 {
    v.get(i).copied().unwrap_or(1.0)
}

fn mean_projected_area(b: Aabb) -> f64 {
    let e = b.extent().as_dvec3();
    (e.x * e.y + e.y * e.z + e.z * e.x) * 2.0 / 4.0
}

/// Gives `strands` the look `missing` names (see the module docs); the
/// rest stays the file's.
pub fn dress(strands: &mut Strands, missing: Missing) {
    if missing.none() || strands.strand_count() == 0 {
        return;
    }
    let spec = GroomSpec::default();
    let mut looks = Vec::with_capacity(strands.strand_count());
    for i in 0..strands.strand_count() {
        // One PRNG stream per strand, as the procedural groom draws its
        // strands: deterministic, and independent of the strand count.
        let mut rng = SplitMix64::stream(spec.seed, i as u64);
        looks.push(look(&spec, &mut rng));
    }
    let ranges: Vec<_> = strands.ranges().collect();
    if missing.color {
        for (r, lk) in ranges.iter().zip(&looks) {
            strands.color[r.clone()].fill(lk.color);
            strands.alpha[r.clone()].fill(lk.alpha);
        }
    }
    if missing.thickness {
        // Relative widths first (root 1 × the strand's variation, tapering),
        // then one scale that brings the optical depth to the reference.
        let tip = spec.tip_thickness;
        for (r, lk) in ranges.iter().zip(&looks) {
            let n = (r.len().max(2) - 1) as f32;
            let root = lk.thickness / spec.thickness;
            for (k, t) in strands.thickness[r.clone()].iter_mut().enumerate() {
                *t = root * (1.0 + (tip - 1.0) * k as f32 / n);
            }
        }
        // Bounds without area (a point, a line: a depth of 0) keep the
        // relative widths: there is no silhouette to fill.
        let scale = REFERENCE_OPTICAL_DEPTH / optical_depth(strands);
        if scale.is_finite() && scale > 0.0 {
            strands.thickness.iter_mut().for_each(|t| *t *= scale);
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::scene::{HairSource, Scene};

    /// Placeholder strands as a `.tfx` file without thickness and colour
    /// reads: `count` straight strands of 8 points, `unit` long.
    fn placeholder(count: usize, unit: f32) -> Strands {
        let mut s = Strands::new();
        for i in 0..count {
            let root = Vec3::new((i % 10) as f32, 0.0, (i / 10) as f32) * 0.1 * unit;
            let pts: Vec<Vec3> = (0..8)
                .map(|k| root - Vec3::Y * unit * k as f32 / 7.0)
                .collect();
            s.push_strand(&pts, |_| 1.0, |_| 1.0, Vec3::ONE);
        }
        s
    }

    #[test]
    fn the_reference_depth_is_the_built_in_grooms() {
        let scene = Scene::builtin_default();
        let HairSource::Procedural(spec) = &scene.hair.source else {
            panic!("the built-in groom is procedural")
        };
        let measured = optical_depth(&super::super::generate(spec));
        assert!(
            (measured / REFERENCE_OPTICAL_DEPTH - 1.0).abs() < 0.01,
            "measured {measured}, stated {REFERENCE_OPTICAL_DEPTH}"
        );
    }

    #[test]
    fn a_file_without_look_gets_the_default_grooms_in_any_units() {
        let spec = GroomSpec::default();
        let all = Missing {
            thickness: true,
            color: true,
        };
        let mut metres = placeholder(200, 1.0);
        dress(&mut metres, all);
        let depth = optical_depth(&metres);
        assert!(
            (depth / REFERENCE_OPTICAL_DEPTH - 1.0).abs() < 1e-3,
            "{depth}"
        );
        // Tapered from root to tip as the procedural groom's strands are.
        let r = metres.strand_range(0);
        let (root, tip) = (metres.thickness[r.start], metres.thickness[r.end - 1]);
        assert!(
            (tip / root - spec.tip_thickness).abs() < 1e-4,
            "{root} {tip}"
        );
        // Colours and alphas vary around the default groom's, per strand.
        let n = metres.point_count() as f32;
        let mean = metres.color.iter().copied().sum::<Vec3>() / n;
        assert!(
            (mean - Vec3::from(spec.color)).abs().max_element() < 0.03,
            "{mean}"
        );
        let alpha = metres.alpha.iter().sum::<f32>() / n;
        assert!((alpha - spec.alpha).abs() < 0.02, "{alpha}");
        assert!(metres.color[r.start] != metres.color[metres.strand_range(1).start]);
        // The same groom in millimetres: the same look, widths × 1000.
        let mut millimetres = placeholder(200, 1000.0);
        dress(&mut millimetres, all);
        assert_eq!(millimetres.color, metres.color);
        let ratio = millimetres.thickness[0] / metres.thickness[0];
        assert!((ratio / 1000.0 - 1.0).abs() < 1e-3, "{ratio}");
        // Four times the strands in the same bounds: a quarter of the width
        // (within the strands' own width variation).
        let mut dense = placeholder(200, 1.0);
        let copy = dense.clone();
        for _ in 0..3 {
            for r in copy.ranges() {
                dense.push_strand(&copy.points[r], |_| 1.0, |_| 1.0, Vec3::ONE);
            }
        }
        dress(&mut dense, all);
        let ratio = dense.thickness[0] / metres.thickness[0];
        assert!((ratio / 0.25 - 1.0).abs() < 0.03, "{ratio}");
    }

    #[test]
    fn what_the_file_states_is_kept() {
        let mut s = placeholder(20, 1.0);
        s.color.fill(Vec3::new(0.9, 0.1, 0.1));
        s.alpha.fill(0.3);
        let before = s.clone();
        dress(&mut s, Missing::default());
        assert_eq!(s, before);
        dress(
            &mut s,
            Missing {
                thickness: true,
                color: false,
            },
        );
        assert_eq!((&s.color, &s.alpha), (&before.color, &before.alpha));
        assert!(s.thickness[0] != 1.0, "{}", s.thickness[0]);
        let mut c = before.clone();
        dress(
            &mut c,
            Missing {
                thickness: false,
                color: true,
            },
        );
        assert_eq!(c.thickness, before.thickness);
        assert!(c.color[0] != before.color[0]);
    }
}
