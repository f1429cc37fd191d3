//! `hair_shade`: hair lit by the shading, lighting and occlusion providers
//! (Kajiya-Kay by default, Halén & Wester 2007 §3.2.1), shadowed by
//! opaque objects (Sintorn & Assarsson 2009 §3.5) and by the hair itself through
//! the visibility provider, blended "over" the colour target.
//!
//! Transparency by the `blend` param:
//! - `over`: premultiplied "over" in draw order, not depth order — the error
//!   occupancy-order blending removes;
//! - `occupancy_order`: each fragment weighted (1-α)^o · α with o its depth
//!   order estimated from camera-view occupancy maps (the `order_*` slots),
//!   added unsorted into a float target (Sintorn & Assarsson 2009 §3.4); the
//!   `compose` pass applies the Λ correction. The fragments in front count
//!   with the mean alpha ᾱ: per pixel (`mean_alpha = "pixel"`, Σα / n from
//!   the `order_alpha` slot) or one constant for the frame (`"frame"`).

use plait_gpu::Capabilities;
use plait_gpu::pass::{BlendPreset, BuiltinShader, DepthMode, PassType, RasterState, blend_preset};
use plait_graph::{Access, PassShape, PassTypeSpec, ScheduledPass};

use crate::spec_util::{DEPTH, HDR, SlotExt, buffer, choice, texture};
use crate::transparency;

pub struct HairShade;

/// Premultiplied-alpha "over".
impl PassType for HairShade {
    fn spec(&self) -> PassTypeSpec {
        let mut inputs = transparency::shading_inputs();
        inputs.insert(
            1,
            texture(
                "depth",
                Access::DepthTarget,
                DEPTH,
                "camera depth of opaque geometry (tested, not written)",
            ),
        );
        inputs.extend([
            texture(
                "order_range",
                Access::Sampled,
                &[plait_graph::Format::Rg32Float],
                "occupancy_order: camera-view depth range",
            )
            .optional(),
            buffer(
                "order_bits",
                Access::StorageRead,
                "occupancy_order: camera-view occupancy bits",
            )
            .optional(),
            buffer(
                "order_slabs",
                Access::StorageRead,
                "occupancy_order: camera-view slab counts",
            )
            .optional(),
            texture(
                "order_alpha",
                Access::Sampled,
                &[
                    plait_graph::Format::Rg32Float,
                    plait_graph::Format::Rg16Float,
                    plait_graph::Format::Rgba32Float,
                    plait_graph::Format::Rgba16Float,
                ],
                "occupancy_order, mean_alpha = \"pixel\": Σα and n per pixel (alpha_sum)",
            )
            .optional(),
        ]);
        let mut params = transparency::shading_params();
        params.push(choice(
            "blend",
            "over",
            &["over", "occupancy_order"],
            "transparency: draw-order `over`, or occupancy-order weights (§3.4)",
        ));
        params.push(choice(
            "mean_alpha",
            "frame",
            &["frame", "pixel"],
            "occupancy_order: the alpha of the fragments in front — `frame`: the CPU mean over every vertex (hair_stats.x); `pixel`: Σα / n of the pixel's visible fragments (`order_alpha`)",
        ));
        PassTypeSpec {
            inputs,
            outputs: vec![
                texture(
                    "color",
                    Access::ColorTarget,
                    HDR,
                    "premultiplied colour, blended over",
                )
                .loads(),
            ],
            params,
            ..PassTypeSpec::new(
                "hair_shade",
                PassShape::Raster,
                "Halén & Wester 2007 §3.2.1; Sintorn & Assarsson 2009 §3.2-3.5",
                "Hair shading (shading, lighting, occlusion providers) with opaque and self shadows, blended over the target.",
            )
        }
    }

    fn shader(&self) -> Option<BuiltinShader> {
        Some(plait_gpu::builtin_shader!("passes/hair_shade.wgsl"))
    }

    fn raster_state(
        &self,
        pass: &ScheduledPass,
        _caps: &Capabilities,
    ) -> Result<RasterState, String> {
        let blend = match pass.params.get("blend").and_then(|v| v.as_str()) {
            Some("occupancy_order") => BlendPreset::Additive,
            _ => BlendPreset::Over,
        };
        Ok(RasterState {
            depth: DepthMode::TestOnly(wgpu::CompareFunction::Less),
            blend: vec![blend_preset(blend)],
            ..RasterState::default()
        })
    }
}
