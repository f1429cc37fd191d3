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
//!
//! `spec` is the groom's TOML table and its checks, `grow` grows and styles
//! one strand from a scalp point, `interpolate` grows guide strands and blends
//! the rendered ones from them; `generate` here puts them together.

mod dress;
mod grow;
mod interpolate;
mod spec;
#[cfg(test)]
mod tests;

use glam::Vec3;

use crate::guides::{GuideBinding, Guides};
use crate::rng::SplitMix64;
use crate::strands::Strands;

pub use dress::{Missing, REFERENCE_OPTICAL_DEPTH, dress, optical_depth};
use grow::{add_waves, comb, grow, head_point, look, push, sample_root, scalp_dir};
use interpolate::interpolate_from_guides;
pub use spec::{GroomSpec, HeadShape, ScalpRegion, Style};

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
