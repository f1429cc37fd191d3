//! Guide strands and how every rendered strand follows them (Halén & Wester
//! 2007 §2.5, §5.4): the simulation moves only the guides; each rendered
//! strand is rebuilt every frame as a barycentric blend of three guides,
//! translated to its own root and scaled to its own length:
//!
//! `p_k = root + scale · (Σᵢ wᵢ gᵢ[k] − Σᵢ wᵢ gᵢ[0])`
//!
//! which is exactly how [`crate::groom`] grows a guided groom on the CPU, so
//! interpolating the rest guides reproduces the rest groom. A groom without
//! guides (a file, follow strands, a plain procedural groom) is its own guide
//! set: every strand is a guide of weight 1 ([`Guides::identity`]), and the
//! same formula returns the strand itself.
//!
//! [`Guides::interpolate`] is the CPU reference the GPU interpolation pass
//! (`shaders/passes/sim_interpolate.wgsl`) is tested against.

use glam::Vec3;

use crate::scene::{HairSource, Scene, SceneError};
use crate::strands::Strands;

/// Which guides one rendered strand follows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuideBinding {
    /// Indices of the three guides (repeated when fewer matter).
    pub guides: [u32; 3],
    /// Barycentric weights, ≥ 0, summing to 1.
    pub weights: [f32; 3],
    /// The strand's root at rest (model space).
    pub root: Vec3,
    /// The strand's length over the blended guide's.
    pub scale: f32,
}

/// The guide strands of a groom and the binding of every rendered strand.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Guides {
    /// The guides at rest.
    pub strands: Strands,
    /// One per rendered strand, in rendered order.
    pub bindings: Vec<GuideBinding>,
}

impl Guides {
    /// Every strand its own guide: simulation moves the rendered strands.
    pub fn identity(strands: &Strands) -> Guides {
        let bindings = strands
            .ranges()
            .enumerate()
            .map(|(i, r)| GuideBinding {
                guides: [i as u32; 3],
                weights: [1.0, 0.0, 0.0],
                root: strands.points.get(r.start).copied().unwrap_or(Vec3::ZERO),
                scale: 1.0,
            })
            .collect();
        Guides {
            strands: strands.clone(),
            bindings,
        }
    }

    /// Whether every strand is its own guide.
    pub fn is_identity(&self) -> bool {
        self.bindings.len() == self.strands.strand_count()
            && self
                .bindings
                .iter()
                .enumerate()
                .all(|(i, b)| b.guides[0] == i as u32 && b.weights[0] == 1.0)
    }

    pub fn guide_count(&self) -> usize {
        self.strands.strand_count()
    }

    /// Points of rendered strand `binding` (with `count` points) from the guide
    /// positions `guide_points` (laid out like `self.strands.points`), with
    /// the strand's root at `root` (its rest root, moved with the head).
    pub fn strand_points(
        &self,
        binding: &GuideBinding,
        count: usize,
        guide_points: &[Vec3],
        root: Vec3,
    ) -> Vec<Vec3> {
        let offsets = &self.strands.offsets;
        let at = |k: usize| {
            (0..3).fold(Vec3::ZERO, |acc, i| {
                let g = binding.guides[i] as usize;
                let first = offsets[g] as usize;
                let len = (offsets[g + 1] - offsets[g]) as usize;
                acc + guide_points[first + k.min(len.saturating_sub(1))] * binding.weights[i]
            })
        };
        let start = at(0);
        (0..count)
            .map(|k| root + (at(k) - start) * binding.scale)
            .collect()
    }

    /// The rendered strands from guide positions `guide_points`: `rendered`
    /// gives the strand layout (and thickness, alpha, colour, copied as they are).
    pub fn interpolate(&self, rendered: &Strands, guide_points: &[Vec3]) -> Strands {
        let mut out = rendered.clone();
        for (s, r) in rendered.ranges().enumerate() {
            let b = &self.bindings[s];
            let pts = self.strand_points(b, r.len(), guide_points, b.root);
            out.points[r].copy_from_slice(&pts);
        }
        out
    }

    /// Moves guides and roots by the groom's placement.
    pub fn transform(&mut self, transform: &crate::transform::Transform) -> Result<(), String> {
        transform.apply(&mut self.strands)?;
        let m = transform.matrix();
        for b in &mut self.bindings {
            b.root = m.transform_point3(b.root);
        }
        Ok(())
    }
}

/// The guides of a scene's hair, for `strands` = [`Scene::strands`]: a
/// procedural groom with `guides = g` has its own guides (regenerated:
/// grooms are deterministic); any other hair is its own guide set.
pub fn scene_guides(scene: &Scene, strands: &Strands) -> Result<Guides, SceneError> {
    let guided = match &scene.hair.source {
        HairSource::Procedural(spec) if spec.guides.is_some() && scene.hair.follow.is_none() => {
            crate::groom::generate_guided(spec).1
        }
        _ => None,
    };
    let Some(mut guides) = guided else {
        return Ok(Guides::identity(strands));
    };
    if let Some(t) = &scene.hair.transform {
        guides.transform(t).map_err(|message| SceneError::Invalid {
            path: "<procedural groom>".into(),
            message,
        })?;
    }
    Ok(guides)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::groom::{GroomSpec, generate, generate_guided};

    #[test]
    fn interpolating_the_rest_guides_gives_the_rest_groom() {
        let spec = GroomSpec {
            strands: 120,
            segments: 8,
            guides: Some(24),
            stray_strands: 3,
            ..GroomSpec::default()
        };
        let (strands, guides) = generate_guided(&spec);
        let guides = guides.expect("a guided groom has guides");
        assert_eq!(
            strands,
            generate(&spec),
            "same groom with or without guides"
        );
        assert_eq!(guides.bindings.len(), strands.strand_count());
        let back = guides.interpolate(&strands, &guides.strands.points);
        for (a, b) in back.points.iter().zip(&strands.points) {
            assert!((*a - *b).length() < 1e-5, "{a} vs {b}");
        }
    }

    #[test]
    fn identity_reproduces_any_strands() {
        let strands = generate(&GroomSpec {
            strands: 30,
            segments: 5,
            ..GroomSpec::default()
        });
        let g = Guides::identity(&strands);
        assert!(g.is_identity());
        let back = g.interpolate(&strands, &strands.points);
        // root + (p − root): exact up to one rounding per coordinate.
        for (a, b) in back.points.iter().zip(&strands.points) {
            assert!(
                (*a - *b).abs().max_element()
                    <= 4.0 * f32::EPSILON * b.abs().max_element().max(1.0)
            );
        }
    }
}
