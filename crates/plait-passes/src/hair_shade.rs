//! `hair_shade`: hair shaded by the shared hair-fragment stage
//! (`plait::hair_fragment`: the shading, self_shadow, lighting and
//! ambient_occlusion providers; Kajiya-Kay by default, Halén & Wester 2007
//! §3.2.1; opaque shadows, Sintorn & Assarsson 2009 §3.5), blended
//! premultiplied "over" the colour target in draw order, not depth order —
//! the error every transparency technique (`techniques/transparency/`)
//! removes its own way. `pipelines/forward.toml` draws its hair with it.

use plait_gpu::Capabilities;
use plait_gpu::pass::{BlendPreset, DepthMode, PassType, RasterState, blend_preset};
use plait_graph::{Access, PassShape, PassTypeSpec, ScheduledPass};

use crate::hair_fragment;
use crate::spec_util::{DEPTH, HDR, SlotExt, texture};

/// With the params of the library's providers (their choices are the
/// providers found).
pub struct HairShade {
    inputs: Vec<plait_graph::SlotSpec>,
    params: Vec<plait_graph::ParamSpec>,
}

inventory::submit! { crate::RustPassType(|library| Box::new(HairShade {
    inputs: hair_fragment::shading_inputs(library),
    params: hair_fragment::shading_params(library),
})) }

impl PassType for HairShade {
    fn spec(&self) -> PassTypeSpec {
        let mut inputs = self.inputs.clone();
        inputs.insert(
            1,
            texture(
                "depth",
                Access::DepthTarget,
                DEPTH,
                "camera depth of opaque geometry (tested, not written)",
            ),
        );
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
            params: self.params.clone(),
            ..PassTypeSpec::new(
                "hair_shade",
                PassShape::Raster,
                "Halén & Wester 2007 §3.2.1; Sintorn & Assarsson 2009 §3.5",
                "Hair shading (shading, lighting, occlusion providers) with opaque and self shadows, blended over the target in draw order.",
            )
        }
    }

    fn shader(&self) -> Option<&str> {
        Some("shaders/passes/hair_shade.wgsl")
    }

    fn raster_state(
        &self,
        _pass: &ScheduledPass,
        _caps: &Capabilities,
    ) -> Result<RasterState, String> {
        Ok(RasterState {
            depth: DepthMode::TestOnly(wgpu::CompareFunction::Less),
            blend: vec![blend_preset(BlendPreset::Over)],
            ..RasterState::default()
        })
    }
}
