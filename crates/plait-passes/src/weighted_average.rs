//! Weighted-average blending (Bavoil & Myers 2008), as Sintorn & Assarsson 2009
//! §2.2 describes it and Fig. 2 shows it ("weighted-average blending (72 fps)",
//! "very dull … compared to the depth-peeled image").
//!
//! `hair_weighted_average` draws the hair once, unsorted, adding α·rgb and α
//! into `color` and 1 into `count` (the depth complexity n) — additive
//! blending, so the draw order does not matter. `weighted_average_resolve`
//! takes the average colour C = Σα·rgb / Σα and the average alpha ᾱ = Σα / n,
//! and writes the hair as if n fragments of colour C and alpha ᾱ were blended:
//! premultiplied (C · (1 - (1-ᾱ)ⁿ), 1 - (1-ᾱ)ⁿ), for `compose_hair_over`.
//!
//! Cost: one hair draw + one fullscreen pass. Memory: two screen-size float
//! targets (rgba16float sums, r16float count — exact counts to 2048).

use plait_gpu::pass::{BlendPreset, BuiltinShader, DepthMode, PassType, RasterState, blend_preset};
use plait_gpu::{Capabilities, Define};
use plait_graph::{Access, Format, PassShape, PassTypeSpec, ScheduledPass};

use crate::spec_util::{DEPTH, HDR, texture};
use crate::transparency::{self, HAIR_SHADER};

const COUNT_FORMATS: &[Format] = &[Format::R16Float, Format::R32Float, Format::Rgba16Float];

pub struct HairWeightedAverage;

impl PassType for HairWeightedAverage {
    fn spec(&self) -> PassTypeSpec {
        let mut inputs = transparency::shading_inputs();
        inputs.push(texture(
            "depth",
            Access::DepthTarget,
            DEPTH,
            "camera depth of opaque geometry (tested, not written)",
        ));
        PassTypeSpec {
            inputs,
            outputs: vec![
                texture("color", Access::ColorTarget, HDR, "Σ α·rgb, Σ α"),
                texture(
                    "count",
                    Access::ColorTarget,
                    COUNT_FORMATS,
                    "n: hair fragments per pixel (red)",
                ),
            ],
            params: transparency::shading_params(),
            ..PassTypeSpec::new(
                "hair_weighted_average",
                PassShape::Raster,
                "Sintorn & Assarsson 2009 §2.2, Fig. 2",
                "Sum α·rgb, α and the fragment count of the hair, unsorted (weighted-average blending).",
            )
        }
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some(HAIR_SHADER)
    }
    fn defines(&self, pass: &ScheduledPass) -> Vec<(String, Define)> {
        transparency::defines(pass, "weighted_average")
    }
    fn raster_state(
        &self,
        _pass: &ScheduledPass,
        _caps: &Capabilities,
    ) -> Result<RasterState, String> {
        Ok(RasterState {
            depth: DepthMode::TestOnly(wgpu::CompareFunction::Less),
            blend: vec![blend_preset(BlendPreset::Additive); 2],
            ..RasterState::default()
        })
    }
}
