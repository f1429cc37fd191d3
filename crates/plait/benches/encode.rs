//! Executor overhead: CPU time to encode one frame of the default pipeline
//! (`pipelines/occupancy.toml`) with plait's executor against the same passes
//! written by hand against wgpu (`support/handwritten/`):
//! `cargo bench -p plait --bench encode`.
//!
//! Both record every pass with a timestamp after it and finish the command
//! buffer without submitting it, so only CPU work is timed: plait's per-pass
//! dispatch, clears, attachment lists and debug groups against a straight
//! sequence of wgpu calls. Criterion times each; then both are timed in
//! interleaved turns and the ratio of their medians is printed (the issue's
//! target: ≤ 1.05×).

mod support;

use std::time::Instant;

use criterion::{Criterion, criterion_group};
use plait::gpu::Gpu;
use plait::session::{SceneData, prepare, repo_root};
use support::handwritten::HandWritten;
use support::timing::median;

/// Encoding does not depend on the image size; a small one keeps setup short.
const SIZE: (u32, u32) = (64, 48);

fn setup<'g>(gpu: &'g Gpu, scene: &SceneData) -> (plait::session::Prepared<'g>, HandWritten<'g>) {
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let prepared = prepare(gpu, &pipeline, &[], scene, SIZE).unwrap_or_else(|e| panic!("{e}"));
    // One frame each: pipelines created, first-frame work done.
    prepared.render().unwrap_or_else(|e| panic!("{e}"));
    let hand = HandWritten::new(gpu, scene, SIZE).unwrap_or_else(|e| panic!("{e}"));
    hand.render();
    (prepared, hand)
}

fn encode(c: &mut Criterion) {
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let scene = SceneData::load(None).unwrap_or_else(|e| panic!("{e}"));
    let (prepared, hand) = setup(&gpu, &scene);
    let mut group = c.benchmark_group("encode occupancy.toml");
    group.bench_function("plait executor", |b| b.iter(|| prepared.encode_only()));
    group.bench_function("hand-written wgpu", |b| b.iter(|| hand.encode()));
    group.finish();

    // Interleaved turns, so both see the same machine load.
    let turns = 400;
    let (mut ours, mut theirs) = (Vec::new(), Vec::new());
    for _ in 0..turns {
        let t = Instant::now();
        drop(prepared.encode_only());
        ours.push(t.elapsed().as_secs_f64() * 1e6);
        let t = Instant::now();
        drop(hand.encode());
        theirs.push(t.elapsed().as_secs_f64() * 1e6);
    }
    let (p, h) = (median(&ours), median(&theirs));
    println!(
        "encode one frame of occupancy.toml ({} passes), median of {turns} interleaved turns on {}: plait {p:.1} µs, hand-written wgpu {h:.1} µs, plait / hand-written = {:.3}×",
        prepared.schedule().passes.len(),
        gpu.adapter_name(),
        p / h
    );
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(30)
        .warm_up_time(std::time::Duration::from_secs(1))
        .measurement_time(std::time::Duration::from_secs(3));
    targets = encode
}

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
}
