//! The browser's way of timing passes, natively: lavapipe opened without
//! `TIMESTAMP_QUERY_INSIDE_ENCODERS` (as WebGPU has no timestamps inside
//! encoders), so every pass is timed through its wgpu passes'
//! `timestamp_writes` (`plait_gpu::timing`).

use plait::session::{SceneData, prepare};
use plait_gpu::TimestampWay;
use plait_tests::{open_gpu, repo_root};

use crate::{SIZE, gallery, small_scene};

/// The one pass type whose wgpu work carries no timestamp: the ray-query
/// strand structure (a compute pass, then an acceleration-structure build
/// that no pass descriptor can time). It must say `None`, never a zero.
const UNTIMED: &str = "strand_structure";

/// Every gallery pipeline at the page's test size: each pass has a positive
/// time (a pass type that records several wgpu passes — depth peeling's
/// layers, submitted in batches — is its first begin to its last end), and
/// the passes, which run one after another, sum to no more than the frame's
/// first-to-last span.
#[test]
fn passes_are_timed_through_pass_descriptors() {
    // The tests' GPU lock and the usual device (timestamps inside
    // encoders), beside one of this test's own.
    let (_lock, usual) = open_gpu();
    let gpu = plait_gpu::Gpu::new_without_features(&["TIMESTAMP_QUERY_INSIDE_ENCODERS"])
        .expect("lavapipe");
    assert_eq!(
        gpu.timestamp_way(),
        Some(TimestampWay::PassDescriptors),
        "lavapipe has TIMESTAMP_QUERY: without timestamps inside encoders it times through pass descriptors"
    );
    let scene = small_scene();
    let mut failures = Vec::new();
    for name in gallery() {
        let path = repo_root().join("pipelines").join(&name);
        let prepared = match prepare(&gpu, &path, &[], &scene, SIZE) {
            Ok(p) => p,
            // A pipeline this adapter refuses (none on lavapipe today) is
            // another test's subject: tests/web.rs's limits test.
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let report = prepared
            .render()
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .report;
        let times: Vec<String> = report
            .passes
            .iter()
            .map(|p| format!("{} {:?}", p.name, p.gpu_ms))
            .collect();
        let sum: f64 = report.passes.iter().filter_map(|p| p.gpu_ms).sum();
        let total = report.total_gpu_ms;
        eprintln!("{name}: frame {total:?} ms, passes sum {sum:.4} ms: {times:?}");
        for p in &report.passes {
            match (p.type_name.as_str(), p.gpu_ms) {
                (UNTIMED, None) => {}
                (UNTIMED, Some(ms)) => failures.push(format!(
                    "{name}: pass `{}` reports {ms} ms, but its work carries no timestamp",
                    p.name
                )),
                (_, Some(ms)) if ms > 0.0 && ms.is_finite() => {}
                (_, other) => failures.push(format!(
                    "{name}: pass `{}` ({}) has gpu_ms {other:?}, not a positive time",
                    p.name, p.type_name
                )),
            }
        }
        match total {
            Some(t) if sum <= t * (1.0 + 1e-9) => {}
            _ => failures.push(format!(
                "{name}: the passes sum to {sum} ms, beyond the frame's span {total:?}"
            )),
        }
    }
    failures.extend(peeling_share(&usual, &gpu, &scene));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The pass that records many wgpu passes, measured both ways: depth
/// peeling's share of its frame through pass descriptors within a factor
/// 1.5 of its share inside encoders. A share, not a time, since the two
/// frames run at different moments on a shared machine; a span that lost
/// its first begin or its last end (one layer's draws, say) would be a
/// small fraction of the other.
fn peeling_share(
    usual: &plait_gpu::Gpu,
    descriptors: &plait_gpu::Gpu,
    scene: &SceneData,
) -> Option<String> {
    let path = repo_root().join("pipelines/depth_peeling.toml");
    let share = |gpu: &plait_gpu::Gpu| {
        let prepared = prepare(gpu, &path, &[], scene, SIZE).expect("depth_peeling");
        let report = prepared.render().expect("frame").report;
        let peel = report.passes.iter().find(|p| p.name == "hair_peel");
        peel.and_then(|p| p.gpu_ms)
            .zip(report.total_gpu_ms)
            .map(|(p, t)| p / t)
    };
    let (encoders, passes) = (share(usual), share(descriptors));
    eprintln!(
        "depth_peeling: hair_peel's share of the frame: inside encoders {encoders:?}, through pass descriptors {passes:?}"
    );
    match encoders.zip(passes) {
        Some((e, p)) if p >= e / 1.5 && p <= e * 1.5 => None,
        _ => Some(format!(
            "depth_peeling: hair_peel's share of the frame through pass descriptors {passes:?}, inside encoders {encoders:?}"
        )),
    }
}
