//! `shadow_map`: depth from a view, no colour.
//!
//! The opaque shadow map of Sintorn & Assarsson (2009 §3.5)
//! when drawing opaque geometry from the light; the nearest-hair depth of the
//! modified shadow map (Halén & Wester 2007 §3.3.2) when drawing hair.

use plait_gpu::pass::{BuiltinShader, PassType};
use plait_graph::{Access, PassShape, PassTypeSpec};

use crate::spec_util::{DEPTH, texture};

pub struct ShadowMap;

impl PassType for ShadowMap {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            name: "shadow_map".into(),
            description: "Depth of the drawn geometry from the pass's view (no colour).".into(),
            source: "Sintorn & Assarsson 2009 §3.5; Halén & Wester 2007 §3.3.2".into(),
            shape: PassShape::Raster,
            inputs: vec![],
            outputs: vec![texture(
                "depth",
                Access::DepthTarget,
                DEPTH,
                "nearest depth per texel",
            )],
            params: vec![],
            dynamic_slots: false,
            needs_shader: false,
            required_features: vec![],
        }
    }

    fn shader(&self) -> Option<BuiltinShader> {
        Some((
            "shaders/passes/shadow_map.wgsl",
            include_str!("../../../shaders/passes/shadow_map.wgsl"),
        ))
    }
}
