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
            outputs: vec![texture(
                "depth",
                Access::DepthTarget,
                DEPTH,
                "nearest depth per texel",
            )],
            ..PassTypeSpec::new(
                "shadow_map",
                PassShape::Raster,
                "Sintorn & Assarsson 2009 §3.5; Halén & Wester 2007 §3.3.2",
                "Depth of the drawn geometry from the pass's view (no colour).",
            )
        }
    }

    fn shader(&self) -> Option<BuiltinShader> {
        Some(plait_gpu::builtin_shader!("passes/shadow_map.wgsl"))
    }
}
