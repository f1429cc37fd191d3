//! `opaque_shade`: the head and the ground, Lambert-lit, shadowed by the opaque
//! shadow map and by hair through the visibility provider
//! (Sintorn & Assarsson 2009 §3.5).

use plait_gpu::pass::PassType;
use plait_graph::{Access, PassShape, PassTypeSpec};

use crate::spec_util::{DEPTH, HDR, texture};
use crate::visibility;

/// With the params of the library's self-shadowing providers.
pub struct OpaqueShade {
    slots: Vec<plait_graph::SlotSpec>,
    params: Vec<plait_graph::ParamSpec>,
}

inventory::submit! { crate::RustPassType(|library| Box::new(OpaqueShade {
    slots: visibility::slots(library),
    params: visibility::params(library),
})) }

impl PassType for OpaqueShade {
    fn spec(&self) -> PassTypeSpec {
        let mut inputs = vec![texture(
            "shadow_map",
            Access::Sampled,
            DEPTH,
            "opaque shadow map from the light",
        )];
        inputs.extend(self.slots.iter().cloned());
        PassTypeSpec {
            inputs,
            outputs: vec![
                texture(
                    "color",
                    Access::ColorTarget,
                    HDR,
                    "linear premultiplied colour, alpha 1 on geometry",
                ),
                texture(
                    "depth",
                    Access::DepthTarget,
                    DEPTH,
                    "camera depth of opaque geometry",
                ),
            ],
            params: self.params.clone(),
            ..PassTypeSpec::new(
                "opaque_shade",
                PassShape::Raster,
                "Sintorn & Assarsson 2009 §3.5",
                "Lambert shading of opaque geometry with opaque and hair shadows.",
            )
        }
    }

    fn shader(&self) -> Option<&str> {
        Some("shaders/passes/opaque_shade.wgsl")
    }
}
