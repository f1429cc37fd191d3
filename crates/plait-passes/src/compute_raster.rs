//! The compute rasterizer's passes (`techniques/transparency/compute_raster`):
//! hair segments binned into screen tiles, then blended per tile front to
//! back with analytic coverage, all in compute (Tafuri 2019, Frostbite;
//! Unreal Engine 5's hair rasterizer; Unity HDRP High Quality Lines).
//!
//! All are data-only compute passes (their slots are their shaders'
//! bindings); Rust is needed for what TOML cannot say: `tile_count` and
//! `strand_bin` run one thread per hair segment (only the built geometry
//! knows how many), `tile_scan` one workgroup; `tile_scan` and `tile_blend`
//! keep and add to what an earlier pass wrote (output slots that load, so
//! they run after it); and each checks the tiling params when the pipeline
//! is loaded, so a tile size the workgroup cannot hold is an error naming
//! the param, before any GPU work.

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
/// The pool's slots are u32 indices, and tile_blend's words after them two
/// per slot: 3 × slots must stay a u32 index.
pub const MAX_BINNED_SEGMENTS: i64 = (u32::MAX / 3) as i64;
/// tile_scan runs as one workgroup of this many threads (scan.wgsl).
const SCAN_THREADS: u32 = 256;

/// The tiling params a pass sets (`param` looks one up), each checked; the
/// message names the param.
fn check_params<'v>(param: impl Fn(&str) -> Option<&'v Value>) -> Result<(), String> {
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
    if let Some(c) = int("binned_segments")
        && !(1..=MAX_BINNED_SEGMENTS).contains(&c)
    {
        return Err(format!(
            "params.binned_segments = {c}: the pool holds 1 to {MAX_BINNED_SEGMENTS} (tile, segment) pairs (u32 slot indices, 12 bytes each)"
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
/// `tile_scan`: one workgroup turns the tiles' counts into their first
/// slots in the shared pool.
pub struct TileScan;
/// `tile_blend`: one workgroup per screen tile (the default dispatch: one
/// thread per texel of the first written texture) blends its segments.
pub struct TileBlend;

inventory::submit! { crate::RustPassType(|_| Box::new(StrandBin)) }
inventory::submit! { crate::RustPassType(|_| Box::new(TileScan)) }
inventory::submit! { crate::RustPassType(|_| Box::new(TileBlend)) }

const SOURCE: &str =
    "Tafuri 2019 (Frostbite); Unreal Engine 5 hair rasterizer; Unity HDRP High Quality Lines";

impl PassType for StrandBin {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            source: SOURCE.into(),
            // tile_count and strand_bin both count their unfinished
            // invocations in it: the second keeps the first's count.
            outputs: vec![
                buffer(
                    "bin_status",
                    Access::StorageWrite,
                    "the invocations whose walk over a segment's tiles could not finish",
                )
                .loads()
                .optional(),
            ],
            ..PassTypeSpec::data_only(
                "strand_bin",
                PassShape::Compute,
                "A WGSL compute shader run once per hair segment (the scene's segment count of threads; with geometry = wisps, once per quad of the wisps' strips): bins segments into screen tiles; slots are the shader's bindings; tile_size, depth_bins, binned_segments checked at load.",
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
        // When the geometry choice draws a triangle mesh for the hair (the
        // wisps' strips: the session builds one only for a technique that
        // asks for it), a "segment" is one quad of a strip (two consecutive
        // spine points, two triangles): tiles.wgsl bins it as a wide segment.
        let segments = match &ctx.geometry.wisps {
            Some(mesh) => mesh.index_count / 6,
            None => ctx.geometry.segment_count,
        };
        draw.threads = [segments.max(1), 1, 1];
        Ok(Box::new(build_draw(&draw, pass, ctx)?))
    }
}

impl PassType for TileScan {
    fn spec(&self) -> PassTypeSpec {
        PassTypeSpec {
            source: SOURCE.into(),
            // Adds each tile's first slot to the counts tile_count wrote.
            outputs: vec![
                buffer(
                    "tile_ranges",
                    Access::StorageWrite,
                    "per tile its count in (tile_count's), its first slot out",
                )
                .loads(),
            ],
            ..PassTypeSpec::data_only(
                "tile_scan",
                PassShape::Compute,
                "A WGSL compute shader run as one workgroup of 256 threads: the tiles' first slots in the shared pool (a prefix sum of their counts); slots are the shader's bindings.",
            )
        }
    }

    fn shader(&self) -> Option<&str> {
        None
    }

    fn compute_threads(&self, _: &ScheduledPass, _: &plait_graph::Schedule) -> [u32; 3] {
        [SCAN_THREADS, 1, 1]
    }

    fn check_sizes(&self, pass: &ScheduledPass, _: &[ResolvedResource]) -> Result<(), String> {
        check_params(|name| pass.params.get(name))
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
                    "strand_bin's binned segments in, the tiles' sorted orders out",
                )
                .loads(),
                buffer(
                    "raster_counter",
                    Access::StorageWrite,
                    "tile_scan's drop counts kept; the invocations that could not finish counted",
                )
                .loads(),
            ],
            ..PassTypeSpec::data_only(
                "tile_blend",
                PassShape::Compute,
                "A WGSL compute shader run as one workgroup per screen tile (threads: the first written texture's texels); slots are the shader's bindings; tile_size, depth_bins, binned_segments checked at load.",
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
        let e = check(&[("binned_segments", Value::Int(0))]).unwrap_err();
        assert!(e.contains("params.binned_segments"), "{e}");
        let e = check(&[("opacity_threshold", Value::Float(1.5))]).unwrap_err();
        assert!(e.contains("params.opacity_threshold"), "{e}");
    }
}
