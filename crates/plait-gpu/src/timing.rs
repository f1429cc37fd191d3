//! Per-pass GPU timestamps, two ways.
//!
//! - **Inside the encoder** (`TIMESTAMP_QUERY_INSIDE_ENCODERS`, native
//!   adapters): one timestamp before the first pass and one after each, so
//!   pass `i` is `t[i]..t[i + 1]` and covers everything the pass recorded,
//!   copies and clears included.
//! - **Through pass descriptors** (`TIMESTAMP_QUERY` alone: WebGPU's
//!   `timestampWrites`, all a browser offers): each schedule pass owns two
//!   queries; the first wgpu render or compute pass it records writes the
//!   begin, and every one writes the end, so the last end stands. A pass is
//!   then its first wgpu pass's begin to its last one's end: the wgpu passes
//!   and whatever the pass recorded between them, but not the encoder
//!   commands before its first one or after its last (clears of its outputs,
//!   the overflow counters' copies, the history copies after the frame). A
//!   pass that records no wgpu pass with a timestamp (the ray-query strand
//!   structure: a compute pass with none, then an acceleration-structure
//!   build) has no time (`None`), never a zero.
//!
//! First begin to last end rather than a pair per wgpu pass summed: depth
//! peeling records a number of wgpu passes it learns only while recording
//! (the layers), and the span is what the encoder way measures too.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// How the adapter lets plait time passes ([`crate::Gpu::timestamp_way`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum TimestampWay {
    /// `TIMESTAMP_QUERY` + `TIMESTAMP_QUERY_INSIDE_ENCODERS`.
    InsideEncoders,
    /// `TIMESTAMP_QUERY` alone: timestamps written by the passes themselves.
    PassDescriptors,
}

/// What names the missing feature when an adapter has no timestamps at all.
pub const NO_TIMESTAMPS: &str = "this adapter has no timestamp queries (wgpu's TIMESTAMP_QUERY, WebGPU's \"timestamp-query\"): GPU times are not available";

/// The query set and buffers of one renderer's timestamps.
pub struct Timestamps {
    pub mode: TimestampWay,
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    period_ns: f32,
    passes: usize,
    /// The schedule pass being recorded (pass-descriptor way), `usize::MAX` outside one.
    current: AtomicUsize,
    /// Per pass: whether a wgpu pass wrote its begin this frame.
    begun: Vec<AtomicBool>,
}

impl Timestamps {
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        mode: TimestampWay,
        passes: usize,
    ) -> Self {
        // Inside encoders: n + 1 stamps; through descriptors: a pair per pass.
        let count = match mode {
            TimestampWay::InsideEncoders => passes as u32 + 1,
            TimestampWay::PassDescriptors => 2 * passes as u32,
        }
        .max(2);
        let size = count as u64 * 8;
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        Timestamps {
            mode,
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("pass timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: buffer(
                "timestamp resolve",
                wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            ),
            readback: buffer(
                "timestamp readback",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            ),
            period_ns: queue.get_timestamp_period(),
            passes,
            current: AtomicUsize::new(usize::MAX),
            begun: (0..passes).map(|_| AtomicBool::new(false)).collect(),
        }
    }

    /// Before the frame's first pass.
    pub fn frame_start(&self, encoder: &mut wgpu::CommandEncoder) {
        match self.mode {
            TimestampWay::InsideEncoders => encoder.write_timestamp(&self.queries, 0),
            TimestampWay::PassDescriptors => self
                .begun
                .iter()
                .for_each(|b| b.store(false, Ordering::Relaxed)),
        }
    }

    /// Before pass `i` records.
    pub fn pass_start(&self, i: usize) {
        self.current.store(i, Ordering::Relaxed);
    }

    /// After pass `i` (and, for the last, the history copies) recorded.
    pub fn pass_end(&self, i: usize, encoder: &mut wgpu::CommandEncoder) {
        self.current.store(usize::MAX, Ordering::Relaxed);
        if self.mode == TimestampWay::InsideEncoders {
            encoder.write_timestamp(&self.queries, i as u32 + 1);
        }
    }

    /// The begin and end query of the wgpu pass about to start: both for a
    /// schedule pass's first, the end alone after. `None` on the encoder way
    /// or outside a schedule pass.
    fn writes(&self) -> Option<(Option<u32>, u32)> {
        let i = self.current.load(Ordering::Relaxed);
        if self.mode != TimestampWay::PassDescriptors || i >= self.passes {
            return None;
        }
        let first = !self.begun[i].swap(true, Ordering::Relaxed);
        Some((first.then_some(2 * i as u32), 2 * i as u32 + 1))
    }

    pub fn render_writes(&self) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        self.writes()
            .map(|(begin, end)| wgpu::RenderPassTimestampWrites {
                query_set: &self.queries,
                beginning_of_pass_write_index: begin,
                end_of_pass_write_index: Some(end),
            })
    }

    pub fn compute_writes(&self) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        self.writes()
            .map(|(begin, end)| wgpu::ComputePassTimestampWrites {
                query_set: &self.queries,
                beginning_of_pass_write_index: begin,
                end_of_pass_write_index: Some(end),
            })
    }

    /// After the frame's last pass: the stamps into the readback buffer.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        let n = self.queries_used();
        if n == 0 {
            return;
        }
        encoder.resolve_query_set(&self.queries, 0..n, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.readback, 0, n as u64 * 8);
    }

    fn queries_used(&self) -> u32 {
        match self.mode {
            TimestampWay::InsideEncoders => self.passes as u32 + 1,
            TimestampWay::PassDescriptors => 2 * self.passes as u32,
        }
    }

    /// The frame's stamps, read back once it finished.
    pub async fn read(&self, device: &wgpu::Device) -> Result<FrameStamps, String> {
        let bytes = crate::readback::map_buffer_async(device, &self.readback).await?;
        let ticks: Vec<u64> = bytes
            .chunks_exact(8)
            .map(|c| u64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect();
        let ms = |a: u64, b: u64| b.saturating_sub(a) as f64 * self.period_ns as f64 / 1e6;
        let spans: Vec<Option<(u64, u64)>> = (0..self.passes)
            .map(|i| match self.mode {
                TimestampWay::InsideEncoders => Some((ticks[i], ticks[i + 1])),
                // A pass whose wgpu passes wrote nothing this frame has no
                // time: its queries hold an older frame's stamps, or zero.
                TimestampWay::PassDescriptors => self.begun[i]
                    .load(Ordering::Relaxed)
                    .then(|| (ticks[2 * i], ticks[2 * i + 1])),
            })
            .collect();
        let total = match self.mode {
            TimestampWay::InsideEncoders => Some(ms(ticks[0], ticks[self.passes])),
            TimestampWay::PassDescriptors => {
                let first = spans.iter().flatten().map(|s| s.0).min();
                let last = spans.iter().flatten().map(|s| s.1).max();
                first.zip(last).map(|(a, b)| ms(a, b))
            }
        };
        Ok(FrameStamps {
            passes: spans.iter().map(|s| s.map(|(a, b)| ms(a, b))).collect(),
            total,
        })
    }
}

/// One frame's times in milliseconds.
pub struct FrameStamps {
    /// Per pass; `None` for a pass skipped or not timed this frame.
    pub passes: Vec<Option<f64>>,
    /// First stamp to last.
    pub total: Option<f64>,
}
