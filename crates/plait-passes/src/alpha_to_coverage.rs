//! `hair_alpha_to_coverage`: alpha to coverage (Halén & Wester 2007
//! §3.1.2, §5.6; NVIDIA 2005): the hair is drawn like opaque geometry — depth
//! test and write, no sorting — into a multisampled target, and the
//! fragment's alpha decides how many of the pixel's samples it covers; the
//! resolve averages the samples. With `samples = 4` a pixel shows 5 levels of
//! transparency, with 8 nine: low-alpha hair dithers (§3.1.2 "dithering
//! aliasing"), and a strand covers the strands behind it wholly where its
//! samples land.
//!
//! The pipeline makes `scene` and `depth` multisampled (`samples =
//! "${samples}"`), so the opaque pass renders into them too, and binds
//! `color_resolve`: the engine resolves a colour target `X` into the
//! resource bound to `X_resolve` at the end of the pass.
//!
//! Cost: one hair draw at the MSAA rate (samples × the depth/colour traffic).
//! Memory: samples × (colour + depth) at screen size, plus the resolved colour.
//!
//! [`HairCoverage`] with `alpha_to_coverage: false` is `hair_opaque`
//! (opaque_hair.rs): the same draw with alpha 1.

use plait_gpu::pass::{BuiltinShader, DepthMode, PassType, RasterState};
use plait_gpu::{Capabilities, Define};
use plait_graph::{Access, PassShape, PassTypeSpec, ScheduledPass};

use crate::spec_util::{DEPTH, HDR, SlotExt, texture};
use crate::transparency::{self, HAIR_SHADER};

pub struct HairCoverage {
    pub alpha_to_coverage: bool,
}

pub const HAIR_ALPHA_TO_COVERAGE: HairCoverage = HairCoverage {
    alpha_to_coverage: true,
};

impl PassType for HairCoverage {
    fn spec(&self) -> PassTypeSpec {
        let (name, description, source) = if self.alpha_to_coverage {
            (
                "hair_alpha_to_coverage",
                "Hair with depth write; alpha becomes MSAA sample coverage; resolved into color_resolve.",
                "Halén & Wester 2007 §3.1.2, §5.6",
            )
        } else {
            (
                "hair_opaque",
                "Hair as opaque strands (alpha 1) with depth test and write: no transparency.",
                "Sintorn & Assarsson 2009 Fig. 2 (no transparency)",
            )
        };
        PassTypeSpec {
            inputs: transparency::shading_inputs(),
            outputs: vec![
                texture(
                    "color",
                    Access::ColorTarget,
                    HDR,
                    "the scene the hair is drawn into (multisampled for alpha to coverage)",
                )
                .loads(),
                texture(
                    "color_resolve",
                    Access::ColorTarget,
                    HDR,
                    "single-sampled resolve of `color` at the end of the pass",
                )
                .optional(),
                texture(
                    "depth",
                    Access::DepthTarget,
                    DEPTH,
                    "camera depth, tested and written",
                )
                .loads(),
            ],
            params: transparency::shading_params(),
            ..PassTypeSpec::new(name, PassShape::Raster, source, description)
        }
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some(HAIR_SHADER)
    }
    fn defines(&self, pass: &ScheduledPass) -> Vec<(String, Define)> {
        let mut d = transparency::defines(pass, "coverage");
        if !self.alpha_to_coverage {
            d.push(("OPAQUE_HAIR".into(), Define::Bool(true)));
        }
        d
    }
    fn raster_state(
        &self,
        _pass: &ScheduledPass,
        _caps: &Capabilities,
    ) -> Result<RasterState, String> {
        Ok(RasterState {
            depth: DepthMode::TestWrite(wgpu::CompareFunction::Less),
            alpha_to_coverage: self.alpha_to_coverage,
            ..RasterState::default()
        })
    }
}
