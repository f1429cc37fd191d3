//! Timings and memory of a variant, in the report's shapes.

use plait_compare::Stats;
use plait_compare::report::{Memory, Overflow, PassStats, ResourceMemory, Timing};
use plait_gpu::FrameReport;
use plait_graph::Schedule;

/// The memory plan of a schedule: peak with sharing, every resource's bytes.
pub(super) fn memory(s: &Schedule) -> Memory {
    Memory {
        peak_bytes: s.memory.peak_bytes,
        unpooled_bytes: s.memory.unpooled_bytes,
        allocations: s.physical.len(),
        resources: s
            .resources
            .iter()
            .enumerate()
            .map(|(id, r)| ResourceMemory {
                name: r.name.clone(),
                desc: r.desc.label(),
                bytes: r.desc.bytes(),
                shares_memory_with: s
                    .shares_memory_with(plait_graph::ResourceId::new(id))
                    .into_iter()
                    .map(str::to_string)
                    .collect(),
            })
            .collect(),
    }
}

/// The timed frames of one variant on one scene.
pub(super) struct Samples {
    /// `Renderer::render` on the CPU clock, ms.
    wall: Vec<f64>,
    /// The frame's GPU time, when the adapter has timestamp queries.
    total_gpu: Vec<f64>,
    /// `per_pass[k]`: pass k's GPU times.
    per_pass: Vec<Vec<f64>>,
    /// Each overflow counter at the frame it dropped the most.
    overflow: Vec<plait_gpu::Overflow>,
}

impl Samples {
    pub(super) fn new(schedule: &Schedule) -> Self {
        Samples {
            wall: Vec::new(),
            total_gpu: Vec::new(),
            per_pass: vec![Vec::new(); schedule.passes.len()],
            overflow: Vec::new(),
        }
    }

    /// Keeps each counter's worst frame (the warm-up's too: a frame that
    /// dropped data counts whether or not it was timed).
    pub(super) fn add_overflow(&mut self, frame: &FrameReport) {
        if self.overflow.is_empty() {
            self.overflow = frame.overflow.clone();
            return;
        }
        for (worst, now) in self.overflow.iter_mut().zip(&frame.overflow) {
            if now.dropped > worst.dropped {
                *worst = now.clone();
            }
        }
    }

    /// The counters that dropped anything, at their worst frame.
    pub(super) fn dropped(&self) -> Vec<plait_gpu::Overflow> {
        self.overflow
            .iter()
            .filter(|o| o.dropped > 0)
            .cloned()
            .collect()
    }

    /// The counters of bounded buffers in the report's shape (a counter of
    /// incomplete invocations alone has no buffer to show, and any count
    /// failed its frame).
    pub(super) fn overflow(&self) -> Vec<Overflow> {
        self.overflow
            .iter()
            .filter(|o| !o.of.is_empty())
            .map(|o| Overflow {
                pass: o.pass.clone(),
                counter: o.counter.clone(),
                of: o.of.clone(),
                dropped: o.dropped,
                needed: o.needed,
                capacity: o.capacity,
                param: o.param.clone(),
                value: o.value,
                value_needed: o.value_needed,
            })
            .collect()
    }

    pub(super) fn add(&mut self, wall_ms: f64, frame: &FrameReport) {
        self.add_overflow(frame);
        self.wall.push(wall_ms);
        if let Some(t) = frame.total_gpu_ms {
            self.total_gpu.push(t);
        }
        for (pass, list) in frame.passes.iter().zip(&mut self.per_pass) {
            if let Some(ms) = pass.gpu_ms {
                list.push(ms);
            }
        }
    }

    /// Median and spread of every measure.
    pub(super) fn timing(&self, schedule: &Schedule) -> Timing {
        Timing {
            total_gpu_ms: Stats::of(&self.total_gpu),
            wall_ms: Stats::of(&self.wall).unwrap_or_default(),
            passes: schedule
                .passes
                .iter()
                .zip(&self.per_pass)
                .map(|(pass, ms)| PassStats {
                    name: pass.name.clone(),
                    type_name: pass.type_name.clone(),
                    gpu_ms: Stats::of(ms),
                })
                .collect(),
        }
    }
}
