//! `depth_range`: nearest and farthest hair depth per texel
//! (Sintorn & Assarsson 2009 §3.1, Fig. 7), from the light for self-shadowing
//! or from the camera for occupancy-order blending.
//!
//! The paper found two depth-tested draws faster than one min/max-blended
//! draw (early-z discards most fragments). wgpu also has no min/max blending
//! on 32-bit float targets without `FLOAT32_BLENDABLE`, so plait draws twice
//! on every adapter: near with `Less` into red, far with `Greater` into green,
//! sharing one scratch depth buffer. Empty texels keep near = 1 > far = 0.

use plait_gpu::GpuError;
use plait_gpu::pass::{
    BuildContext, DepthMode, PassType, PreparedPass, RasterState, RecordContext, ShaderDraw,
    build_draw,
};
use plait_graph::{
    Access, Format, PassShape, PassTypeSpec, ResolvedResource, ResourceDesc, ScheduledPass, SlotId,
};

use crate::spec_util::{DEPTH, texture};

pub struct DepthRange;

inventory::submit! { crate::RustPassType(|_| Box::new(DepthRange)) }

pub(crate) const SHADER: &str = "shaders/passes/depth_range.wgsl";

/// Its slots' handles ([`SlotId`]), in `spec`'s order.
pub(crate) const OPAQUE_DEPTH: SlotId = SlotId::Input(0);
pub(crate) const RANGE: SlotId = SlotId::Output(0);

pub(crate) fn spec() -> PassTypeSpec {
    PassTypeSpec {
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
        ..PassTypeSpec::new(
            "depth_range",
            PassShape::Raster,
            "Sintorn & Assarsson 2009 §3.1, Fig. 7",
            "Nearest (red) and farthest (green) hair depth per texel, linear in the view's depth.",
        )
    }
}

/// The two draws: near (`Less` into red) then far (`Greater` into green).
pub(crate) fn draw_states() -> [RasterState; 2] {
    [
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
        },
        RasterState {
            depth: DepthMode::TestWrite(wgpu::CompareFunction::Greater),
            clear_depth: 0.0,
            write_mask: vec![wgpu::ColorWrites::GREEN],
            load_colors: true,
            ..RasterState::default()
        },
    ]
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
    fn shader(&self) -> Option<&str> {
        Some(SHADER)
    }
    /// The shader drops hair behind opaque geometry with the depth test the
    /// occupancy and slab passes make (`less`, at the fragment's own texel),
    /// so the opaque depth must be a texel-for-texel match of the range map.
    fn check_sizes(
        &self,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
    ) -> Result<(), String> {
        check_same_size(pass, resources, OPAQUE_DEPTH, RANGE)
    }
    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let mut draw = ShaderDraw::of(self, pass, ctx)?;
        let [near_state, far_state] = draw_states();
        draw.state = near_state;
        let near = Box::new(build_draw(&draw, pass, ctx)?);
        draw.state = far_state;
        let far = Box::new(build_draw(&draw, pass, ctx)?);
        Ok(Box::new(TwoDraws { near, far }))
    }
}

/// Both texture slots bound and of one size (unbound or culled: nothing to check).
fn check_same_size(
    pass: &ScheduledPass,
    resources: &[ResolvedResource],
    slot: SlotId,
    like: SlotId,
) -> Result<(), String> {
    let size = |slot: SlotId| {
        let binding = pass.bound(slot)?;
        match binding.resolved(resources)? {
            ResolvedResource {
                name,
                desc: ResourceDesc::Texture { width, height, .. },
                ..
            } => Some((name.clone(), binding.slot.clone(), *width, *height)),
            _ => None,
        }
    };
    match (size(slot), size(like)) {
        (Some((name, slot, w, h)), Some((like_name, like, lw, lh))) if (w, h) != (lw, lh) => {
            Err(format!(
                "`{name}` (slot `{slot}`) is {w}x{h} but `{like_name}` (slot `{like}`) is {lw}x{lh}: the opaque depth is tested texel for texel, give both one size"
            ))
        }
        _ => Ok(()),
    }
}
