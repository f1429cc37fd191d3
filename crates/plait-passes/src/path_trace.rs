//! `path_trace`: plait's own path tracer (issue 48, `pipelines/physical/path_traced.toml`),
//! a data-only compute shader (the pass's `shader`, slots its bindings)
//! dispatched `spp` times per frame, each dispatch adding one path per pixel
//! to the storage buffers it writes.
//!
//! Why dispatches and not a loop in the shader: lavapipe gives each group of
//! eight invocations one budget of 65,535 loop iterations
//! (`shaders/lib/loop_budget.wgsl`), and every ray query's traversal is a
//! loop; one path per invocation per dispatch keeps a pixel's work for a
//! dispatch to one path's rays, whatever `spp` is. The shader still checks
//! the budget at its end and counts an invocation it cut in an `incomplete`
//! counter (which fails the frame).
//!
//! The written buffers are cleared once, before the first dispatch, and
//! accumulate over the rest: the shader keeps its own per-pixel sample count
//! there (the index of the next sample, so each dispatch draws fresh random
//! numbers without a uniform per dispatch).

use plait_gpu::GpuError;
use plait_gpu::pass::{
    BuildContext, PassType, PreparedPass, RecordContext, ShaderDraw, ShaderPassKind, build_draw,
};
use plait_graph::{PassShape, PassTypeSpec, ResourceDesc, Schedule, ScheduledPass};

use crate::occlusion_directions::int_param;
use crate::spec_util::{float, int};

pub struct PathTrace;

inventory::submit! { crate::RustPassType(|_| Box::new(PathTrace)) }

/// The most samples per pixel one frame takes: each is one dispatch
/// recorded into the frame's command buffer.
pub const MAX_SPP: i64 = 4096;
/// The longest path, in Mitsuba 3's `max_depth` convention (path vertices
/// after the camera's: 2 = single scattering).
pub const MAX_DEPTH: i64 = 64;
/// Bytes per pixel of the accumulation buffer (`pt_sum`): the radiance sum
/// and the primary rays' hits, then the sample count.
pub const SUM_BYTES_PER_PIXEL: u64 = 32;

fn spec() -> PassTypeSpec {
    PassTypeSpec {
        params: vec![
            int(
                "spp",
                64,
                1,
                MAX_SPP,
                "samples per pixel this frame: one path per pixel per dispatch",
            ),
            int(
                "max_depth",
                16,
                1,
                MAX_DEPTH,
                "path vertices after the camera's, as Mitsuba 3's max_depth: 1 = what the camera ray meets (emitters and background), 2 = single scattering",
            ),
            int(
                "seed",
                0,
                0,
                i64::from(i32::MAX),
                "random sequence: another seed, another image of the same expected value",
            ),
            float(
                "chiang_beta_m",
                0.3,
                0.02,
                1.0,
                "longitudinal roughness β_m (Chiang et al. 2016 §4.1)",
            ),
            float(
                "chiang_beta_n",
                0.3,
                0.15,
                1.0,
                "azimuthal roughness β_n (§4.1; also in colour → absorption, §4.2)",
            ),
            float(
                "chiang_tilt",
                2.0,
                -10.0,
                10.0,
                "cuticle scale tilt α in degrees",
            ),
            float("chiang_eta", 1.55, 1.1, 2.0, "index of refraction η"),
        ],
        ..PassTypeSpec::data_only(
            "path_trace",
            PassShape::Compute,
            "A WGSL compute shader dispatched `spp` times per frame, one path per pixel each, into the storage buffers it writes (cleared once per frame); slots are the shader's bindings.",
        )
    }
}

impl PassType for PathTrace {
    fn spec(&self) -> PassTypeSpec {
        spec()
    }
    fn shader(&self) -> Option<&str> {
        None
    }
    /// One thread per pixel: the first written buffer holds
    /// [`SUM_BYTES_PER_PIXEL`] per pixel.
    fn compute_threads(&self, pass: &ScheduledPass, schedule: &Schedule) -> [u32; 3] {
        let size = pass
            .writes
            .first()
            .and_then(|b| b.resolved(&schedule.resources))
            .map(|r| match r.desc {
                ResourceDesc::Buffer { size } => size / SUM_BYTES_PER_PIXEL,
                _ => 1,
            })
            .unwrap_or(1);
        [size.min(u64::from(u32::MAX)) as u32, 1, 1]
    }
    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let draw = ShaderDraw::of(self, pass, ctx)?;
        let built = build_draw(&draw, pass, ctx)?;
        let ShaderPassKind::Compute {
            pipeline,
            workgroups,
        } = built.kind
        else {
            return Err(GpuError::Pass {
                pass: pass.name.clone(),
                message: "a path_trace pass is a compute dispatch".into(),
            });
        };
        // The param's range (1 ..= MAX_SPP) is checked at load.
        let spp = int_param(pass, "spp").clamp(1, MAX_SPP) as u32;
        Ok(Box::new(Samples {
            name: built.name,
            pipeline,
            workgroups,
            bind_group: built.bind_group,
            clears: built.clears,
            spp,
        }))
    }
}

struct Samples {
    name: String,
    pipeline: wgpu::ComputePipeline,
    workgroups: [u32; 3],
    bind_group: Option<wgpu::BindGroup>,
    clears: Vec<plait_graph::ResourceId>,
    spp: u32,
}

impl PreparedPass for Samples {
    /// The clears once, then `spp` dispatches in one compute pass (wgpu
    /// orders a dispatch's storage writes before the next one's reads), so
    /// the pass's timestamps span every sample.
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        for &id in &self.clears {
            if let plait_gpu::pool::GpuResource::Buffer(b) = ctx.pool.get(id) {
                encoder.clear_buffer(b, 0, None);
            }
        }
        let mut cpass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(&self.name),
            timestamp_writes: ctx.compute_timestamps(),
        });
        cpass.set_pipeline(&self.pipeline);
        cpass.set_bind_group(0, ctx.frame_bind_group, &[]);
        if let Some(bg) = &self.bind_group {
            cpass.set_bind_group(1, bg, &[]);
        }
        let [x, y, z] = self.workgroups;
        for _ in 0..self.spp {
            cpass.dispatch_workgroups(x, y, z);
        }
    }
}
