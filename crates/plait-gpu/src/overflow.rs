//! Reading back the overflow counters a schedule declares
//! ([`plait_graph::OverflowCounter`]): what a bounded buffer could not hold.
//!
//! Each counter is copied into a small mappable buffer of its own right
//! after the pass that writes it, inside the frame's command buffer. Not at
//! the end of the frame: the memory plan may give the counter's allocation
//! to a later resource once its last pass is done. After the frame the
//! copies are mapped (a few bytes each), so every [`FrameReport`] says what
//! was dropped.
//!
//! [`FrameReport`]: crate::FrameReport

use plait_graph::{OverflowCounter, Schedule};

use crate::GpuError;
use crate::pool::ResourcePool;
use crate::readback::map_buffer_async;

/// What one overflow counter read after a frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Overflow {
    /// The pass that writes the counter (the first, when several do: the
    /// one that appends to `of`).
    pub pass: String,
    /// The counter buffer.
    pub counter: String,
    /// The bounded buffer it counts for.
    pub of: String,
    /// Items `of` could not hold this frame (0: it held everything).
    pub dropped: u64,
    /// The capacity, in items of `of`, that would have held them all
    /// (meaningful when `dropped > 0`).
    pub needed: u64,
    /// Items `of` holds.
    pub capacity: u64,
    /// The param that sizes `of`, and its value.
    pub param: String,
    pub value: i64,
    /// Items of `of` per unit of `param`.
    pub per: u64,
    /// The value of `param` that would hold `needed`.
    pub value_needed: u64,
    /// Shader invocations that could not finish their work this frame (the
    /// counter's `incomplete` word; 0 without one): the output lacks data
    /// no param can restore, so any count fails the frame.
    pub incomplete: u64,
    /// The pass after which the counter is read (its last writer): the one
    /// whose invocations `incomplete` counts.
    pub last_pass: String,
    /// Whether `param` has its technique's default, which the session may
    /// raise ([`OverflowCounter::grows`]); `false` for a value the user set.
    pub grows: bool,
}

struct Entry {
    counter: OverflowCounter,
    /// Index in `Schedule::passes` of the first pass writing the counter.
    first: usize,
    /// Index in `Schedule::passes` of the last pass writing the counter.
    writer: usize,
    staging: wgpu::Buffer,
}

/// The staging copies of every counter of a schedule.
pub(crate) struct OverflowReadback {
    entries: Vec<Entry>,
}

impl OverflowReadback {
    pub(crate) fn new(device: &wgpu::Device, schedule: &Schedule, pool: &ResourcePool) -> Self {
        let entries = schedule
            .overflow
            .iter()
            .filter_map(|c| {
                let writes = |p: &plait_graph::ScheduledPass| {
                    p.writes.iter().any(|b| b.resource == Some(c.counter))
                };
                let first = schedule.passes.iter().position(writes)?;
                let writer = schedule.passes.iter().rposition(writes)?;
                let size = pool.buffer(c.counter)?.size();
                let staging = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&format!("overflow readback {}", c.counter_name)),
                    size,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                Some(Entry {
                    counter: c.clone(),
                    first,
                    writer,
                    staging,
                })
            })
            .collect();
        OverflowReadback { entries }
    }

    /// Copies the counters written by pass `pass` (recorded right after it).
    pub(crate) fn record(
        &self,
        pass: usize,
        pool: &ResourcePool,
        encoder: &mut wgpu::CommandEncoder,
    ) {
        for e in self.entries.iter().filter(|e| e.writer == pass) {
            if let Some(buffer) = pool.buffer(e.counter.counter) {
                encoder.copy_buffer_to_buffer(buffer, 0, &e.staging, 0, e.staging.size());
            }
        }
    }

    /// Every counter as the last frame left it (a counter whose writer is a
    /// `run = "once"` pass keeps the first frame's count).
    pub(crate) async fn read(
        &self,
        device: &wgpu::Device,
        schedule: &Schedule,
    ) -> Result<Vec<Overflow>, GpuError> {
        let mut read = Vec::with_capacity(self.entries.len());
        for e in &self.entries {
            let bytes = map_buffer_async(device, &e.staging)
                .await
                .map_err(|message| GpuError::Readback {
                    resource: e.counter.counter_name.clone(),
                    message,
                })?;
            read.push(Self::counted(e, &bytes, schedule));
        }
        Ok(read)
    }

    /// What counter `e` holds in `bytes` (its staging copy).
    fn counted(e: &Entry, bytes: &[u8], schedule: &Schedule) -> Overflow {
        let word = |i: u32| {
            let at = i as usize * 4;
            bytes
                .get(at..at + 4)
                .map_or(0, |w| u32::from_le_bytes([w[0], w[1], w[2], w[3]]) as u64)
        };
        let c = &e.counter;
        let needed = c.needed_word.map_or(0, word);
        Overflow {
            pass: schedule.passes[e.first].name.clone(),
            counter: c.counter_name.clone(),
            of: c.of.clone(),
            dropped: c.dropped_word.map_or(0, word),
            needed,
            capacity: c.capacity(),
            param: c.param.clone(),
            value: c.value,
            per: c.per,
            value_needed: c.value_for(needed),
            incomplete: c.incomplete_word.map_or(0, word),
            last_pass: schedule.passes[e.writer].name.clone(),
            grows: c.grows,
        }
    }
}

/// `` `list_nodes` (pass `hair_lists`) dropped 1234: it holds 25600
/// (params.nodes_per_pixel=1); holding everything needs 40000
/// (--set params.nodes_per_pixel=2) ``.
impl std::fmt::Display for Overflow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.incomplete > 0 {
            write!(
                f,
                "{} shader invocations of pass `{}` could not finish their work (counted in `{}`): \
                 lavapipe, for one, ends every loop of an invocation once it has run 65,535 \
                 iterations in all",
                self.incomplete, self.last_pass, self.counter
            )?;
            if self.dropped == 0 {
                return Ok(());
            }
            f.write_str("; ")?;
        }
        write!(
            f,
            "`{}` (pass `{}`) dropped {}: it holds {} (params.{}={})",
            self.of, self.pass, self.dropped, self.capacity, self.param, self.value
        )?;
        if self.dropped > 0 {
            write!(
                f,
                "; holding everything needs {} (--set params.{}={})",
                self.needed, self.param, self.value_needed
            )?;
        }
        Ok(())
    }
}
