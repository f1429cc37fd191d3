//! `density_clustering`: self-shadowing by density clustering (Mertens, Kautz,
//! Bekaert & Van Reeth 2004 — the sketch's
//! construction of V; as summarised in Halén & Wester 2007 §3.3.2).
//!
//! Per light texel the fragment depths along the line of sight are summarised
//! into K = 4 clusters by k-means, iterated INSIDE this one pass by drawing the
//! hair several times:
//! - draw 0: the clusters are 4 uniform slices of the texel's hair range
//!   (near/far from `depth_range`); each fragment adds itself (count, Σz,
//!   Σz²) to its slice — "rendering uniform slices yielding the mean z-value
//!   of each slice, one k-means iteration" (Halén & Wester 2007 §3.3.2);
//! - draws 1..=`iterations`: each fragment joins the cluster whose mean (from
//!   the previous draw's sums) is nearest and adds itself there.
//!
//! Sums are fixed point (z relative to the texel range × 2^18) with
//! `atomicAdd`, one stage of 4 × 3 u32 per texel per draw, so a draw reads the
//! previous stage while writing its own (no read-write hazard inside a draw).
//! The provider `plait::self_shadow::density_clustering` reads the last stage:
//! each cluster becomes a histogram bin centred on its mean, 2√3·σ wide (the
//! width of a uniform distribution of standard deviation σ: "bin widths
//! proportional to the standard deviation of each cluster"), holding its
//! fragment count; the density integrated up to z gives the fragment count
//! in front, visibility exp(-w · ∫d) — piecewise linear, as in the paper.
//! Mertens et al. found one iteration enough (Halén & Wester 2007 §3.3.2): uniform slices,
//! then one reassignment that also gathers σ — `iterations = 1` (2 draws).
//!
//! Memory: (iterations + 1) × 4 × 3 × 4 B per texel = 24 MiB at 512² with
//! one refinement, plus the 2 MiB depth range.

use plait_gpu::pass::{
    BuildContext, PassType, PreparedPass, RecordContext, ShaderDraw, build_draw,
};
use plait_gpu::{Define, GpuError};
use plait_graph::{
    Access, Format, PassShape, PassTypeSpec, ResolvedResource, ScheduledPass, SlotId, Value,
};

use crate::spec_util::{DEPTH, buffer, int, texture};
use plait_graph::pass_type_file::{WordsPerTexel, check_words_per_texel};

pub struct DensityClustering;

inventory::submit! { crate::RustPassType(|_| Box::new(DensityClustering)) }

/// Clusters per texel (the paper's K = 4: one RGBA texel).
pub const CLUSTERS: u64 = 4;
/// u32 words per cluster per stage: count, Σz, Σz² (fixed point).
pub const WORDS_PER_CLUSTER: u64 = 3;

const SHADER: &str = "shaders/passes/density_clustering.wgsl";

/// The `clusters` slot ([`SlotId`]): cleared by the first draw only.
pub(crate) const CLUSTERS_SLOT: SlotId = SlotId::Output(0);

pub(crate) fn spec() -> PassTypeSpec {
    PassTypeSpec {
        inputs: vec![
            texture(
                "range",
                Access::Sampled,
                &[Format::Rg32Float],
                "depth range of the same view (depth_range): initial uniform clusters",
            ),
            texture(
                "depth",
                Access::DepthTarget,
                DEPTH,
                "opaque depth of the same view, tested not written",
            ),
        ],
        outputs: vec![buffer(
            "clusters",
            Access::StorageWrite,
            "(iterations + 1) stages × 4 clusters × (count, Σz, Σz²) u32 per texel",
        )],
        params: vec![int(
            "iterations",
            1,
            0,
            8,
            "k-means refinements after the uniform-slice draw (the paper: 1 is enough)",
        )],
        ..PassTypeSpec::new(
            "density_clustering",
            PassShape::Raster,
            "Mertens et al. 2004; Halén & Wester 2007 §3.3.2",
            "K = 4 k-means clusters of fragment depth per texel (count, Σz, Σz²), refined over several hair draws in one pass.",
        )
    }
}

/// The draw of k-means stage `stage` (0: uniform slices) reads stage − 1.
fn set_stage(defines: &mut Vec<(String, Define)>, stage: u32) {
    defines.retain(|(k, _)| k != "STAGE");
    defines.push(("STAGE".into(), Define::UInt(stage)));
}

struct Draws(Vec<Box<dyn PreparedPass>>);

impl PreparedPass for Draws {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        for d in &self.0 {
            d.record(ctx, encoder);
        }
    }
}

impl PassType for DensityClustering {
    fn spec(&self) -> PassTypeSpec {
        spec()
    }
    fn shader(&self) -> Option<&str> {
        Some(SHADER)
    }
    fn defines(&self, pass: &ScheduledPass) -> Vec<(String, Define)> {
        let mut d = plait_gpu::pass::default_defines(pass);
        set_stage(&mut d, 0);
        d
    }
    fn check_sizes(
        &self,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
    ) -> Result<(), String> {
        let iterations = match pass.params.get("iterations") {
            Some(Value::Int(i)) => *i as u64,
            _ => 1,
        };
        let per_stage = CLUSTERS * WORDS_PER_CLUSTER;
        let clusters = WordsPerTexel {
            slot: "clusters".into(),
            of: "range".into(),
            multiple: per_stage,
            max: per_stage * 9,
            hint: None,
        };
        if let Some(words) = check_words_per_texel(&clusters, pass, resources)?
            && words != per_stage * (iterations + 1)
        {
            return Err(format!(
                "`clusters` holds {words} words per texel; iterations = {iterations} needs (iterations + 1) × {per_stage} = {}",
                per_stage * (iterations + 1)
            ));
        }
        Ok(())
    }
    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let iterations = match pass.params.get("iterations") {
            Some(Value::Int(i)) => *i as u64,
            _ => 1,
        };
        let mut draw = ShaderDraw::of(self, pass, ctx)?;
        let mut draws: Vec<Box<dyn PreparedPass>> = Vec::new();
        for stage in 0..=iterations as u32 {
            // Only the first draw clears the buffer; later draws add to it.
            let mut p = pass.clone();
            if stage > 0 {
                for b in p
                    .writes
                    .iter_mut()
                    .filter(|b| b.slot_id == Some(CLUSTERS_SLOT))
                {
                    b.loads = true;
                }
            }
            set_stage(&mut draw.defines, stage);
            draws.push(Box::new(build_draw(&draw, &p, ctx)?));
        }
        Ok(Box::new(Draws(draws)))
    }
}
