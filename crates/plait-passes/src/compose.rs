//! `compose`: the occupancy-order blended hair over the scene
//! (Sintorn & Assarsson 2009 §3.4): scene × (1-α)^n + hair.rgb × Λ / hair.a,
//! Λ = 1-(1-α)^n, n the pixel's hair fragments from the camera-view slab
//! counts. The paper prints the correction as hair.a / Λ; the factor that
//! restores the intensity the weights should have summed to is Λ / hair.a.

use plait_gpu::pass::{BuiltinShader, PassType};
use plait_graph::{Access, PassShape, PassTypeSpec};

use crate::spec_util::{HDR, buffer, final_image, texture};

pub struct Compose;

impl PassType for Compose {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            inputs: vec![
                texture(
                    "hair",
                    Access::Sampled,
                    HDR,
                    "additively blended hair: Σ (1-α)^o α (rgb, 1)",
                ),
                texture(
                    "scene",
                    Access::Sampled,
                    HDR,
                    "opaque objects, premultiplied; background where alpha < 1",
                ),
                buffer(
                    "counts",
                    Access::StorageRead,
                    "camera-view slab counts (slab pass): n per pixel",
                ),
            ],
            outputs: vec![final_image()],
            ..PassTypeSpec::new(
                "compose",
                PassShape::Fullscreen,
                "Sintorn & Assarsson 2009 §3.4",
                "Order-blended hair over the scene with the Λ correction, to sRGB.",
            )
        }
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some(plait_gpu::builtin_shader!("passes/compose.wgsl"))
    }
}
