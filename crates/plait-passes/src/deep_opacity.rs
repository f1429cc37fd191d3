//! `deep_opacity`: the opacity map of deep opacity maps (Yuksel & Keyser
//! 2008, Yuksel & Keyser 2008 §3, Fig. 2).
//!
//! Step one of the paper — the per-texel start depth z0 of the hair — is the
//! near depth (red) of a `depth_range` pass, reused. This pass is step two:
//! the hair drawn once from the light; each fragment finds its layer k among
//! K layers `[z0 + d_{k-1}, z0 + d_k)` and counts itself there with
//! `atomicAdd` on a storage buffer (the paper's additive blending into colour
//! channels; exact integer counts here, and no FLOAT32_BLENDABLE needed).
//! Layer sizes grow linearly, `d_k − d_{k−1} = k · layer_size` (the paper's
//! choice, §3 end), the same for every texel; fragments beyond the last layer
//! go to the last layer (the paper's second option, §3). The provider
//! `plait::visibility::deep_opacity` prefix-sums the counts ("the fragment
//! contributes to its layer and all layers behind it") and interpolates
//! linearly between layer boundaries: opacity = w · count.
//!
//! `layers` holds K u32 per texel; K = its words per texel (3 by default:
//! `size = "${light_size} * ${light_size} * ${dom_layers} * 4"`).
//! Memory: 512² × 3 × 4 B = 3 MiB, plus the 2 MiB depth range.

use plait_gpu::pass::{BuiltinShader, PassType};
use plait_graph::{Access, Format, PassShape, PassTypeSpec, ResolvedResource, ScheduledPass};

use crate::per_texel::check_words;
use crate::spec_util::{DEPTH, buffer, float, texture};

pub struct DeepOpacity;

impl PassType for DeepOpacity {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            name: "deep_opacity".into(),
            description: "Deep opacity map: fragment count per layer after the texel's start depth z0 (atomicAdd), K u32 per texel.".into(),
            source: "Yuksel & Keyser 2008 §3".into(),
            shape: PassShape::Raster,
            inputs: vec![
                texture("range", Access::Sampled, &[Format::Rg32Float], "depth range of the same view; near (red) is z0"),
                texture("depth", Access::DepthTarget, DEPTH, "opaque depth of the same view, tested not written"),
            ],
            outputs: vec![buffer("layers", Access::StorageWrite, "fragment counts: K × u32 per texel")],
            params: vec![float("layer_size", 0.05, 1e-6, 1e6, "size of the first layer in world units; layer k is k times as thick")],
            dynamic_slots: false,
            needs_shader: false,
            required_features: vec![],
        }
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some((
            "shaders/passes/deep_opacity.wgsl",
            include_str!("../../../shaders/passes/deep_opacity.wgsl"),
        ))
    }
    fn check_sizes(
        &self,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
    ) -> Result<(), String> {
        check_words(pass, resources, "layers", "range", 1, 32)?;
        Ok(())
    }
}
