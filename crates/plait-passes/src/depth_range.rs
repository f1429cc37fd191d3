//! `depth_range`: nearest and farthest hair depth per texel
//! (Sintorn & Assarsson 2009 §3.1, Fig. 7), from the light for self-shadowing
//! or from the camera for occupancy-order blending.
//!
//! The paper found two depth-tested draws faster than one min/max-blended
//! draw (early-z discards most fragments). wgpu also has no min/max blending
//! on 32-bit float targets without `FLOAT32_BLENDABLE`, so plait draws twice
//! on every adapter: near with `Less` into red, far with `Greater` into green,
//! sharing one scratch depth buffer. Empty texels keep near = 1 > far = 0.

use plait_gpu::pass::{
    BuildContext, BuiltinShader, DepthMode, PassType, PreparedPass, RasterState, RecordContext,
    build_shader_pass,
};
use plait_gpu::{Capabilities, GpuError};
use plait_graph::{Access, Format, PassShape, PassTypeSpec, ScheduledPass};

use crate::spec_util::{DEPTH, texture};

pub struct DepthRange;

const SHADER: BuiltinShader = (
    "shaders/passes/depth_range.wgsl",
    include_str!("../../../shaders/passes/depth_range.wgsl"),
);

fn spec() -> PassTypeSpec {
    PassTypeSpec {
        name: "depth_range".into(),
        description:
            "Nearest (red) and farthest (green) hair depth per texel, linear in the view's depth."
                .into(),
        source: "Sintorn & Assarsson 2009 §3.1, Fig. 7".into(),
        shape: PassShape::Raster,
        inputs: vec![texture(
            "opaque_depth",
            Access::Sampled,
            DEPTH,
            "opaque depth from the same view; hair behind it is ignored (§3.5)",
        )],
        outputs: vec![
            texture(
                "range",
                Access::ColorTarget,
                &[Format::Rg32Float],
                "near (r) and far (g) linear depth",
            ),
            texture(
                "scratch",
                Access::DepthTarget,
                DEPTH,
                "depth buffer for the two depth-tested draws",
            ),
        ],
        params: vec![],
        dynamic_slots: false,
        needs_shader: false,
        required_features: vec![],
    }
}

/// One of the two draws.
struct Draw {
    far: bool,
}

impl PassType for Draw {
    fn spec(&self) -> PassTypeSpec {
        spec()
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some(SHADER)
    }
    fn raster_state(
        &self,
        _pass: &ScheduledPass,
        _caps: &Capabilities,
    ) -> Result<RasterState, String> {
        Ok(if self.far {
            RasterState {
                depth: DepthMode::TestWrite(wgpu::CompareFunction::Greater),
                clear_depth: 0.0,
                write_mask: vec![wgpu::ColorWrites::GREEN],
                load_colors: true,
                ..RasterState::default()
            }
        } else {
            RasterState {
                depth: DepthMode::TestWrite(wgpu::CompareFunction::Less),
                clear_color: wgpu::Color {
                    r: 1.0,
                    g: 0.0,
                    b: 0.0,
                    a: 0.0,
                },
                clear_depth: 1.0,
                write_mask: vec![wgpu::ColorWrites::RED],
                ..RasterState::default()
            }
        })
    }
}

struct TwoDraws {
    near: Box<dyn PreparedPass>,
    far: Box<dyn PreparedPass>,
}

impl PreparedPass for TwoDraws {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        self.near.record(ctx, encoder);
        self.far.record(ctx, encoder);
    }
}

impl PassType for DepthRange {
    fn spec(&self) -> PassTypeSpec {
        spec()
    }
    fn shader(&self) -> Option<BuiltinShader> {
        Some(SHADER)
    }
    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let near = build_shader_pass(&Draw { far: false }, pass, ctx)?;
        let far = build_shader_pass(&Draw { far: true }, pass, ctx)?;
        Ok(Box::new(TwoDraws { near, far }))
    }
}
