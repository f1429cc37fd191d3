//! `slab`: fragment counts per slab of slices per texel
//! (Sintorn & Assarsson 2009 §3.1, Fig. 8), counted exactly with `atomicAdd`
//! on a storage buffer: the paper's additive blending into a float target
//! would need `FLOAT32_BLENDABLE` here and rounds counts past 2048 in 16-bit
//! floats. `slabs` u32 counters per texel; 4 is the paper's choice for 128
//! slices, 1 turns the method into "occupancy bits alone" (F/S per set bit).

use plait_gpu::pass::{BuiltinShader, PassType};
use plait_graph::{Access, Format, PassShape, PassTypeSpec, ResolvedResource, ScheduledPass};

use crate::per_texel::check_words;
use crate::spec_util::{DEPTH, buffer, texture};

pub struct Slab;

impl PassType for Slab {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            name: "slab".into(),
            description: "Fragment count per slab per texel (atomicAdd), one u32 per slab.".into(),
            source: "Sintorn & Assarsson 2009 §3.1, Fig. 8".into(),
            shape: PassShape::Raster,
            inputs: vec![
                texture(
                    "range",
                    Access::Sampled,
                    &[Format::Rg32Float],
                    "depth range of the same view (depth_range)",
                ),
                texture(
                    "depth",
                    Access::DepthTarget,
                    DEPTH,
                    "opaque depth of the same view, tested not written",
                ),
            ],
            outputs: vec![buffer(
                "slabs",
                Access::StorageWrite,
                "fragment counts: slabs × u32 per texel",
            )],
            params: vec![],
            dynamic_slots: false,
            needs_shader: false,
            required_features: vec![],
        }
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some((
            "shaders/passes/slab.wgsl",
            include_str!("../../../shaders/passes/slab.wgsl"),
        ))
    }
    fn check_sizes(
        &self,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
    ) -> Result<(), String> {
        // One counter per slab, up to 32 slabs, as plait::occupancy reads them.
        check_words(pass, resources, "slabs", "range", 1, 32).map(|_| ())
    }
}
