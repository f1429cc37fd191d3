//! `opacity_shadow_maps`: opacity shadow maps (Kim & Neumann 2001, in the
//! one-pass form of Nguyen & Donnelly 2005 described by
//! Halén & Wester 2007 §3.3.2 and §5.7; compared in
//! Yuksel & Keyser 2008 §2).
//!
//! N uniform slices between the hair's near and far depth; every fragment is
//! counted in its slice with `atomicAdd` on a storage buffer (N u32 per
//! texel) in ONE hair draw — the paper's 4 targets × 4 channels with additive
//! blending, without the 16-map limit: N = the buffer's words per texel
//! (16 by default, up to 256). The provider
//! `plait::visibility::opacity_shadow_maps` rebuilds the opacity thickness
//! σ(z_i) at the slice boundaries (a prefix sum: a fragment counts in every
//! map behind it) and interpolates linearly between the two closest maps
//! (§5.7, formula 5.1); transmittance exp(-w·σ) (formula 3.1, k = w).
//!
//! Slicing range: PER TEXEL — near and far are the texel's own hair range from
//! the `depth_range` pass (the light_range map of occupancy.toml), not one
//! global pair of planes for the whole hair volume as in the papers. That
//! only helps OSM (no slices wasted on empty space) and makes it directly
//! comparable with the occupancy maps, which slice the same range.
//!
//! Memory: 512² × 16 × 4 B = 16 MiB (the paper's 4 rgba16f targets would
//! be 8 MiB, rgba8 4 MiB), plus the 2 MiB depth range.

use plait_gpu::pass::{BuiltinShader, PassType};
use plait_graph::{Access, Format, PassShape, PassTypeSpec, ResolvedResource, ScheduledPass};

use crate::per_texel::check_words;
use crate::spec_util::{DEPTH, buffer, texture};

pub struct OpacityShadowMaps;

/// The most slices a texel may have (the provider's loop bound).
pub const MAX_SLICES: u64 = 256;

impl PassType for OpacityShadowMaps {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            name: "opacity_shadow_maps".into(),
            description: "Opacity shadow maps: fragment count per uniform slice of the texel's hair range (atomicAdd), N u32 per texel, one draw.".into(),
            source: "Halén & Wester 2007 §3.3.2, §5.7; Yuksel & Keyser 2008 §2".into(),
            shape: PassShape::Raster,
            inputs: vec![
                texture("range", Access::Sampled, &[Format::Rg32Float], "depth range of the same view (depth_range): the slicing range"),
                texture("depth", Access::DepthTarget, DEPTH, "opaque depth of the same view, tested not written"),
            ],
            outputs: vec![buffer("slices", Access::StorageWrite, "fragment counts: N × u32 per texel")],
            params: vec![],
            dynamic_slots: false,
            needs_shader: false,
            required_features: vec![],
        }
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some((
            "shaders/passes/opacity_shadow_maps.wgsl",
            include_str!("../../../shaders/passes/opacity_shadow_maps.wgsl"),
        ))
    }
    fn check_sizes(
        &self,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
    ) -> Result<(), String> {
        check_words(pass, resources, "slices", "range", 1, MAX_SLICES)?;
        Ok(())
    }
}
