//! Shading-space providers: every `shading_space` technique answers
//! `strand_radiance(strand, segment, along) -> vec4` in the hair fragment
//! stage: a radiance shaded elsewhere this frame (w ≥ 0) or "shade this
//! fragment" (w < 0; `fragment`, the default), w a constant of the provider
//! so the hair draws' branch on it is compiled out. Strand space's tip
//! fading, which every hair draw's vertex coverage takes, is its own
//! `strand_tip` (`plait::strand_coverage`). Its uniform is
//! `shading_space_params` (binding 50), its resources bind at 51–54 through
//! the optional slots below.
//!
//! `strand` (Tafuri 2019, Frostbite's "strand space") fills its buffer with
//! the `strand_shading` pass: one thread per shading point of every drawn
//! strand, its WGSL in the technique's folder.

use plait_gpu::GpuError;
use plait_gpu::pass::{BuildContext, PassType, PreparedPass, ShaderDraw, build_draw};
use plait_graph::{ParamSpec, PassShape, PassTypeSpec, ResourceDesc, ScheduledPass, SlotSpec};

use crate::occlusion_directions::int_param;

/// Bytes of one shading point's radiance (`vec4<f32>`).
const RADIANCE_BYTES: u64 = 16;

/// The providers, by param value: every module `plait::shading_space::NAME` found.
pub fn providers(library: &plait_gpu::PassLibrary) -> Vec<String> {
    library.shaders.providers("shading_space")
}

/// The optional input slots any provider may need
/// (`techniques/shading_space/point.toml`, `[inputs]`).
pub fn slots(library: &plait_gpu::PassLibrary) -> Vec<SlotSpec> {
    crate::points::slots(library, "shading_space")
}

/// Params of the providers (filled into `shading_space_params` by member name).
pub fn params(library: &plait_gpu::PassLibrary) -> Vec<ParamSpec> {
    crate::points::params(library, "shading_space")
}

/// `strand_shading`: a data-only compute pass (its slots are its shader's
/// bindings) dispatched over the scene's strands × `shading_points`, which
/// only the built geometry knows — hence Rust.
pub struct StrandShading;

inventory::submit! { crate::RustPassType(|_| Box::new(StrandShading)) }

impl PassType for StrandShading {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            source: "Tafuri 2019".into(),
            ..PassTypeSpec::data_only(
                "strand_shading",
                PassShape::Compute,
                "A WGSL compute shader run once per shading point of every drawn strand (strands × `shading_points` threads); slots are the shader's bindings.",
            )
        }
    }

    fn shader(&self) -> Option<&str> {
        None
    }

    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let error = |message: String| GpuError::Pass {
            pass: pass.name.clone(),
            message,
        };
        let points = int_param(pass, "shading_points").max(1) as u64;
        let strands = u64::from(ctx.geometry.strand_count);
        // A data-only pass's slots are its shader's bindings, which declare
        // no handle: this one is the binding the dispatch is sized for.
        let out = pass
            .writes
            .iter()
            .find(|b| b.slot == "strand_radiance")
            .ok_or_else(|| error("slot `strand_radiance` is not bound".into()))?;
        let resource = &ctx.schedule.resources[out.id()];
        if let ResourceDesc::Buffer { size } = resource.desc
            && size < strands * points * RADIANCE_BYTES
        {
            return Err(error(format!(
                "`{}` holds {} strands of {points} shading points ({size} bytes) but the hair has {strands} strands: raise the technique's `shading_max_strands` param",
                resource.name,
                size / (points * RADIANCE_BYTES)
            )));
        }
        let threads = u32::try_from(strands * points).map_err(|_| {
            error(format!(
                "{strands} strands × {points} shading points are too many threads"
            ))
        })?;
        let mut draw = ShaderDraw::of(self, pass, ctx)?;
        draw.threads = [threads, 1, 1];
        Ok(Box::new(build_draw(&draw, pass, ctx)?))
    }
}
