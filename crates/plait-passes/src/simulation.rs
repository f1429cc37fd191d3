//! `hair_simulation`: guide strands simulated on the GPU as chains of nodes —
//! Verlet integration with gravity, damping and wind, the spring model's
//! pull towards the rest shape, length constraints iterated `iterations`
//! times and collisions with the head — its ellipsoids and its mesh's signed
//! distance field (Halén & Wester 2007 §4, §4.4, §5.9);
//! `shaders/passes/sim_verlet.wgsl` has the equations.
//!
//! State is the scene's (`guide_positions`, `guide_previous`,
//! `plait_graph::scene_resources`): it persists from frame to frame and
//! starts at rest. Each frame takes `substeps` fixed steps of `time_step`
//! ("this works best with a fixed time step", §4).
//!
//! Faults: the kernel flags non-finite nodes, strands stretched past
//! `max_stretch` × their rest length, and strands whose loops the driver's
//! loop budget cut short (lavapipe: 65,535 iterations per group of 8
//! invocations, ≈ (substeps + 1) · (iterations + 1) · points · (colliders +
//! 3); a canary loop at the kernel's end, `plait::loop_budget`, tells) in a
//! small status buffer, which this
//! pass reads back after every frame ([`PreparedPass::finish`]) and turns into
//! an error naming the strand, so the frame is never returned.
//!
//! Stability, checked at load ([`PassType::check_sizes`]). A node on the
//! §4.4 spring (stiffness at most k, at the root; unit mass) steps by (4.1)
//! as x' = x + d·(x − x₋) − Δt²k·x, whose characteristic polynomial is
//! λ² − (1 + d − Δt²k)λ + d. Both roots lie inside the unit circle (Jury's
//! test, 0 ≤ d < 1) exactly when Δt²k < 2(1 + d): beyond that every step
//! amplifies the motion and the hair explodes whatever else is set. So
//! `time_step` · √`spring` ≥ √(2(1 + damping)) is rejected, naming the largest
//! stable step (d = 0 gives the undamped Størmer–Verlet limit Δt·ω < 2).
//! Damping above 1 would add energy every step, so the param stops at one.
//! The length projection (4.2) cannot diverge — each sweep only moves
//! nodes towards the rest lengths — so `iterations` sets accuracy, not
//! stability: too few for the time step shows as stretch, which the
//! `max_stretch` fault catches in the frame it happens.

use std::cell::Cell;

use plait_gpu::pass::{
    BuildContext, Finishing, PassType, PreparedPass, RecordContext, ShaderDraw, build_draw,
};
use plait_gpu::readback::map_buffer_async;
use plait_gpu::{Define, GpuError};
use plait_graph::{
    Access, ParamSpec, ParamType, PassShape, PassTypeSpec, ResolvedResource, ScheduledPass, SlotId,
    Value,
};

use crate::spec_util::{SlotExt, bound, buffer, float, int};

pub struct HairSimulation;

inventory::submit! { crate::RustPassType(|_| Box::new(HairSimulation)) }

const SHADER: &str = "shaders/passes/sim_verlet.wgsl";

/// Bytes of the status buffer the kernel writes: flags, strand, stretch, spare.
pub const STATUS_BYTES: u64 = 16;

fn aliased(mut slot: plait_graph::SlotSpec, binding: &str) -> plait_graph::SlotSpec {
    slot.binding = Some(binding.into());
    slot
}

/// The `status` slot: the faults the kernel flags, read back every frame.
pub(crate) const STATUS: SlotId = SlotId::Output(2);

pub(crate) fn spec() -> PassTypeSpec {
    PassTypeSpec {
        inputs: vec![
            aliased(
                buffer(
                    "rest",
                    Access::StorageRead,
                    "guide points at rest (scene resource guide_rest)",
                ),
                "guide_rest",
            ),
            aliased(
                buffer(
                    "strands",
                    Access::StorageRead,
                    "first point and count per guide (guide_strands)",
                ),
                "guide_strands",
            ),
            aliased(
                buffer(
                    "colliders",
                    Access::StorageRead,
                    "the head's ellipsoids (head_colliders)",
                ),
                "head_colliders",
            ),
            aliased(
                buffer(
                    "sdf",
                    Access::StorageRead,
                    "the head mesh's signed distance field (head_sdf)",
                ),
                "head_sdf",
            ),
        ],
        outputs: vec![
            aliased(
                buffer(
                    "positions",
                    Access::StorageWrite,
                    "guide points now (guide_positions), kept between frames",
                )
                .loads(),
                "guide_positions",
            ),
            aliased(
                buffer(
                    "previous",
                    Access::StorageWrite,
                    "guide points one step ago (guide_previous)",
                )
                .loads(),
                "guide_previous",
            ),
            buffer(
                "status",
                Access::StorageWrite,
                "16 bytes: fault flags, first faulty strand, stretch — read back every frame",
            ),
        ],
        params: vec![
            float(
                "time_step",
                1.0 / 120.0,
                1e-5,
                1.0,
                "Δt of one Verlet step, seconds",
            ),
            int("substeps", 4, 1, 64, "Verlet steps per frame"),
            int(
                "iterations",
                4,
                0,
                64,
                "length-constraint sweeps per step (4.2)",
            ),
            float(
                "damping",
                0.97,
                0.0,
                1.0,
                "k of (4.1): the fraction of the velocity kept per step",
            ),
            float(
                "gravity",
                9.8,
                0.0,
                1e3,
                "acceleration downward (−Y), model units / s²",
            ),
            float(
                "spring",
                40.0,
                0.0,
                1e6,
                "k of §4.4 at the root: pull towards the rest shape, 1/s²",
            ),
            float(
                "spring_min",
                0.2,
                0.0,
                1.0,
                "α of §4.4 as a fraction of k: what is left with the head upside down",
            ),
            float(
                "spring_falloff",
                1.0,
                0.0,
                1e3,
                "c: the spring falls off as k / (1 + c·L)², L the length from the root (§5.9)",
            ),
            ParamSpec {
                name: "wind".into(),
                ty: ParamType::Vec3,
                default: Some(Value::List(vec![Value::Float(0.0); 3])),
                doc: "wind: direction × strength, an acceleration (model units / s²)".into(),
            },
            float(
                "turbulence",
                0.0,
                0.0,
                10.0,
                "gusts: the wind varies by ± this fraction over space and time",
            ),
            float(
                "max_stretch",
                1.5,
                1.01,
                1e3,
                "a strand longer than this × its rest length is a fault",
            ),
        ],
        ..PassTypeSpec::new(
            "hair_simulation",
            PassShape::Compute,
            "Halén & Wester 2007 §4, §4.4, §5.9",
            "Verlet guide strands: gravity, damping, wind, springs to the rest shape, length constraints, head collisions; faults read back each frame.",
        )
    }
}

fn number(pass: &ScheduledPass, name: &str) -> f64 {
    pass.params.get(name).and_then(Value::as_f64).unwrap_or(0.0)
}

/// Why `pass`'s params cannot be stable, if they cannot.
pub fn instability(pass: &ScheduledPass) -> Option<String> {
    let dt = number(pass, "time_step");
    let k = number(pass, "spring");
    let d = number(pass, "damping");
    let limit = (2.0 * (1.0 + d)).sqrt();
    let omega_dt = dt * k.sqrt();
    (omega_dt >= limit).then(|| {
        format!(
            "time_step = {dt} with spring = {k} and damping = {d} cannot be stable: Verlet steps (4.1) of the spring grow without bound unless time_step · √spring < √(2·(1 + damping)) = {limit:.3} (here {omega_dt:.3}). Use time_step < {:.6} or spring < {:.3}",
            limit / k.sqrt(),
            limit * limit / (dt * dt)
        )
    })
}

impl PassType for HairSimulation {
    fn spec(&self) -> PassTypeSpec {
        spec()
    }
    fn shader(&self) -> Option<&str> {
        Some(SHADER)
    }
    fn defines(&self, _pass: &ScheduledPass) -> Vec<(String, Define)> {
        Vec::new()
    }
    fn check_sizes(
        &self,
        pass: &ScheduledPass,
        resources: &[ResolvedResource],
    ) -> Result<(), String> {
        if let Some(why) = instability(pass) {
            return Err(why);
        }
        if let Some(r) = pass.bound(STATUS).and_then(|b| b.resolved(resources))
            && r.desc.bytes() < STATUS_BYTES
        {
            return Err(format!(
                "`status` ({}) must hold at least {STATUS_BYTES} bytes",
                r.name
            ));
        }
        Ok(())
    }
    fn build(
        &self,
        pass: &ScheduledPass,
        ctx: &mut BuildContext<'_>,
    ) -> Result<Box<dyn PreparedPass>, GpuError> {
        let mut draw = ShaderDraw::of(self, pass, ctx)?;
        draw.threads = [ctx.geometry.guides.guide_count, 1, 1];
        let inner = build_draw(&draw, pass, ctx)?;
        let status = bound(pass, &spec(), STATUS)?.id();
        let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{} status readback", pass.name)),
            size: STATUS_BYTES,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(Box::new(Simulation {
            inner,
            status,
            staging,
            frames: Cell::new(0),
            max_stretch: number(pass, "max_stretch"),
        }))
    }
}

struct Simulation {
    inner: plait_gpu::pass::ShaderPass,
    status: plait_graph::ResourceId,
    staging: wgpu::Buffer,
    /// Frames simulated, for messages.
    frames: Cell<u64>,
    max_stretch: f64,
}

impl PreparedPass for Simulation {
    fn record(&self, ctx: &RecordContext<'_>, encoder: &mut wgpu::CommandEncoder) {
        self.inner.record(ctx, encoder);
        if let Some(status) = ctx.pool.buffer(self.status) {
            encoder.copy_buffer_to_buffer(status, 0, &self.staging, 0, STATUS_BYTES);
        }
        self.frames.set(self.frames.get() + 1);
    }

    fn finish(&self, device: &wgpu::Device) -> Result<(), String> {
        plait_gpu::wait::wait_for(self.check(device))?
    }

    fn finish_async<'a>(&'a self, device: &'a wgpu::Device) -> Finishing<'a> {
        Box::pin(self.check(device))
    }
}

impl Simulation {
    /// The status the frame's last step left, read back (awaited: in a
    /// browser the mapping completes through the page's event loop).
    async fn check(&self, device: &wgpu::Device) -> Result<(), String> {
        let bytes = map_buffer_async(device, &self.staging).await?;
        let word =
            |i: usize| u32::from_le_bytes(bytes[i * 4..i * 4 + 4].try_into().unwrap_or([0; 4]));
        let (flags, strand, stretch) = (word(0), u32::MAX - word(1), word(2));
        let frame = self.frames.get();
        // First: a cut-short step explains whatever else went wrong.
        if flags & 4 != 0 {
            return Err(format!(
                "the simulation could not finish frame {frame}: guide strand {strand}'s substeps × iterations × points ran past the driver's loop budget (lavapipe ends every loop of a group of 8 invocations after 65,535 iterations in all); lower substeps or iterations"
            ));
        }
        if flags & 1 != 0 {
            return Err(format!(
                "the simulation went unstable in frame {frame}: guide strand {strand} has a non-finite position (NaN or Inf); lower time_step or spring, or raise damping"
            ));
        }
        if flags & 2 != 0 {
            return Err(format!(
                "the simulation went unstable in frame {frame}: guide strand {strand} is {:.2}× its rest length (max_stretch = {}); raise iterations or lower time_step",
                stretch as f64 / 1000.0,
                self.max_stretch
            ));
        }
        Ok(())
    }
}
