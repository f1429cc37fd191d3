//! The viewer's per-pass GPU times: the last frames' medians, so one slow
//! frame on a shared software rasterizer does not make the table jump.

use std::collections::{HashMap, VecDeque};
use std::time::Instant;

use plait_gpu::FrameReport;
use plait_graph::Schedule;

/// Frames a pass's median GPU time is taken over.
const WINDOW: usize = 15;

/// The last `WINDOW` GPU times of each pass (by name) and of whole frames.
#[derive(Default)]
pub struct Timings {
    passes: HashMap<String, VecDeque<f64>>,
    frames: VecDeque<f64>,
}

fn push(window: &mut VecDeque<f64>, value: f64) {
    window.push_back(value);
    if window.len() > WINDOW {
        window.pop_front();
    }
}

fn median(values: &VecDeque<f64>) -> Option<f64> {
    let mut v: Vec<f64> = values.iter().copied().collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    Some(v[v.len() / 2])
}

impl Timings {
    /// Adds a frame's pass times, and its total: the GPU's when the adapter
    /// has timestamps, else the wall time since `started`.
    pub fn record(&mut self, report: &FrameReport, started: Instant) {
        for t in &report.passes {
            if let Some(ms) = t.gpu_ms {
                push(self.passes.entry(t.name.clone()).or_default(), ms);
            }
        }
        let total = report
            .total_gpu_ms
            .unwrap_or_else(|| started.elapsed().as_secs_f64() * 1e3);
        push(&mut self.frames, total);
    }

    /// Each of `schedule`'s passes' median, in its order.
    pub fn pass_medians(&self, schedule: &Schedule) -> Vec<Option<f64>> {
        schedule
            .passes
            .iter()
            .map(|p| self.passes.get(&p.name).and_then(median))
            .collect()
    }

    pub fn frame_median(&self) -> Option<f64> {
        median(&self.frames)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_is_of_the_last_window() {
        let mut w = VecDeque::new();
        for v in 0..(WINDOW + 10) {
            push(&mut w, v as f64);
        }
        assert_eq!(w.len(), WINDOW);
        assert_eq!(median(&w), Some(10.0 + (WINDOW / 2) as f64));
        assert_eq!(median(&VecDeque::new()), None);
    }
}
