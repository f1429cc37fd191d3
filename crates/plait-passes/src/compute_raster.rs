//! The compute rasterizer's passes (`techniques/transparency/compute_raster`):
//! hair segments binned into screen tiles, then blended per tile front to
//! back with analytic coverage, all in compute (Tafuri 2019, Frostbite;
//! Unreal Engine 5's hair rasterizer; Unity HDRP High Quality Lines).
//!
//! Both are data-only compute passes (their slots are their shaders'
//! bindings); Rust is needed for what TOML cannot say: `strand_bin` runs one
//! thread per hair segment (only the built geometry knows how many), and
//! both check the tiling params when the pipeline is loaded, so a tile size
//! the workgroup cannot hold is an error naming the param, before any GPU
//! work.

use plait_gpu::GpuError;
use plait_gpu::pass::{BuildContext, PassType, PreparedPass, ShaderDraw, build_draw};
use plait_graph::{Access, PassShape, PassTypeSpec, ResolvedResource, ScheduledPass, Value};

use crate::spec_util::{SlotExt, buffer};

/// The largest tile side: a tile is one workgroup of tile_size² threads, and
/// 16 × 16 = 256 is the invocations per workgroup every WebGPU adapter
/// offers (`max_compute_invocations_per_workgroup`'s default).
pub const MAX_TILE_SIZE: i64 = 16;
/// The depth bins' counters live in workgroup memory (blend.wgsl's `MAX_BINS`).
pub const MAX_DEPTH_BINS: i64 = 64;

/// The tiling params a pass sets (`param` looks one up), each checked, and
/// the geometry it is asked to draw; the
/// message names the param.
fn check_params<'v>(param: impl Fn(&str) -> Option<&'v Value>) -> Result<(), String> {
    // A line rasterizer bins strand segments; the wisps of `geometry = wisps`
    // are triangle strips it cannot draw. Refused here rather than drawn as
    // strands, which would compare another geometry than the one chosen.
    if let Some(Value::Str(g)) = param("geometry")
        && g == "wisps"
    {
        return Err(
            "techniques.transparency = compute_raster rasterizes strand segments, but \
             techniques.geometry = wisps draws triangle strips: choose geometry strands or lod \
             with compute_raster, or another transparency technique with wisps"
                .into(),
        );
    }
    let int = |name: &str| param(name).and_then(Value::as_i64);
    if let Some(t) = int("tile_size")
        && (!(2..=MAX_TILE_SIZE).contains(&t) || (t & (t - 1)) != 0)
    {
        return Err(format!(
            "params.tile_size = {t}: a tile is one workgroup of tile_size² threads, so tile_size must be a power of two from 2 to {MAX_TILE_SIZE} ({MAX_TILE_SIZE}² = 256 invocations, the WebGPU workgroup limit)"
        ));
    }
    if let Some(b) = int("depth_bins")
        && !(1..=MAX_DEPTH_BINS).contains(&b)
    {
        return Err(format!(
            "params.depth_bins = {b} is out of range 1..={MAX_DEPTH_BINS}"
        ));
    }
    if let Some(c) = int("segments_per_tile")
        && c < 1
    {
        return Err(format!(
            "params.segments_per_tile = {c}: a tile must hold at least one segment"
        ));
    }
    if let Some(v) = param("opacity_threshold") {
        match v.as_f64() {
            Some(x) if x > 0.0 && x <= 1.0 => {}
            _ => {
                return Err(format!(
                    "params.opacity_threshold = {v}: it must be in (0, 1]"
                ));
            }
        }
    }
    Ok(())
}

/// `strand_bin`: one thread per hair segment appends it to every screen tile
/// it touches.
pub struct StrandBin;
/// `tile_blend`: one workgroup per screen tile (the default dispatch: one
/// thread per texel of the first written texture) blends its segments.
pub struct TileBlend;

inventory::submit! { crate::RustPassType(|| Box::new(StrandBin)) }
inventory::submit! { crate::RustPassType(|| Box::new(TileBlend)) }

const SOURCE: &str =
    "Tafuri 2019 (Frostbite); Unreal Engine 5 hair rasterizer; Unity HDRP High Quality Lines";

impl PassType for StrandBin {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            source: SOURCE.into(),
            ..PassTypeSpec::data_only(
                "strand_bin",
                PassShape::Compute,
                "A WGSL compute shader run once per hair segment (the scene's segment count of threads): bins segments into screen tiles; slots are the shader's bindings; tile_size, depth_bins, segments_per_tile checked at load.",
            )
        }
    }

    fn shader(&self) -> Option<&str> {
        None
    }

    fn check_sizes(&self, pass: &ScheduledPass, _: &[ResolvedResource]) -> Result<(), String> {
        check_params(|name| pass.params.get(name))
    }

    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let mut draw = ShaderDraw::of(self, pass, ctx)?;
        draw.threads = [ctx.geometry.segment_count.max(1), 1, 1];
        Ok(Box::new(build_draw(&draw, pass, ctx)?))
    }
}

impl PassType for TileBlend {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            source: SOURCE.into(),
            // Written over what strand_bin left (its bins and tile counts are
            // read first), so it runs after it: the two slots that load.
            outputs: vec![
                buffer(
                    "tile_segments",
                    Access::StorageWrite,
                    "strand_bin's binned segments in, the tile's sorted order out",
                )
                .loads(),
                buffer(
                    "raster_counter",
                    Access::StorageWrite,
                    "strand_bin's tile counts in; the invocations that could not finish counted",
                )
                .loads(),
            ],
            ..PassTypeSpec::data_only(
                "tile_blend",
                PassShape::Compute,
                "A WGSL compute shader run as one workgroup per screen tile (threads: the first written texture's texels); slots are the shader's bindings; tile_size, depth_bins, segments_per_tile checked at load.",
            )
        }
    }

    fn shader(&self) -> Option<&str> {
        None
    }

    fn check_sizes(&self, pass: &ScheduledPass, _: &[ResolvedResource]) -> Result<(), String> {
        check_params(|name| pass.params.get(name))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(params: &[(&str, Value)]) -> Result<(), String> {
        check_params(|name| params.iter().find(|(k, _)| *k == name).map(|(_, v)| v))
    }

    #[test]
    fn tiling_params_are_checked_by_name() {
        assert!(check(&[("tile_size", Value::Int(8))]).is_ok());
        for t in [0, 1, 6, 32] {
            let e = check(&[("tile_size", Value::Int(t))]).unwrap_err();
            assert!(e.contains("params.tile_size"), "{e}");
        }
        let e = check(&[("depth_bins", Value::Int(65))]).unwrap_err();
        assert!(e.contains("params.depth_bins"), "{e}");
        let e = check(&[("segments_per_tile", Value::Int(0))]).unwrap_err();
        assert!(e.contains("params.segments_per_tile"), "{e}");
        let e = check(&[("opacity_threshold", Value::Float(1.5))]).unwrap_err();
        assert!(e.contains("params.opacity_threshold"), "{e}");
    }
}
