//! Per-vertex ambient occlusion read back from a frame, and the statistics
//! the occlusion tests compare techniques by (`tests/occlusion.rs`,
//! `tests/ray_traced_occlusion.rs`).

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;

use crate::repo_root;

/// Per-vertex ambient visibility by the `ambient_occlusion` technique
/// `technique` with `sets` (one value per hair vertex), through the fixture
/// pipeline that outputs `ao_vertex`, and the frame's report (its overflow
/// counters).
pub fn vertex_ao_report(
    gpu: &Gpu,
    scene: &SceneData,
    technique: &str,
    sets: &[String],
    size: (u32, u32),
) -> (Vec<f32>, plait_gpu::FrameReport) {
    let pipeline = repo_root().join("tests/fixtures/ambient_occlusion.toml");
    let mut all = vec![format!("techniques.ambient_occlusion={technique}")];
    all.extend(sets.iter().cloned());
    let prepared = prepare(gpu, &pipeline, &all, scene, size)
        .unwrap_or_else(|e| panic!("{technique} {sets:?}: {e}"));
    let report = prepared.render_unchecked().expect("renders");
    let bytes = prepared.read_buffer("ao_vertex").expect("ao_vertex");
    let n = scene.strands.points.len();
    let ao = bytes
        .chunks_exact(4)
        .take(n)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    (ao, report)
}

/// Mean |a − b| over the vertices.
pub fn mean_abs_diff(a: &[f32], b: &[f32]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() as f64)
        .sum::<f64>()
        / a.len() as f64
}

/// Mean visibility of the vertices nearest to and farthest from the hair's
/// centre (the innermost and outermost fifth).
pub fn inner_outer(scene: &SceneData, ao: &[f32]) -> (f64, f64) {
    let center = scene.strands.bounds().center();
    let mut by_distance: Vec<(f32, f32)> = scene
        .strands
        .points
        .iter()
        .zip(ao)
        .map(|(p, &a)| (p.distance(center), a))
        .collect();
    by_distance.sort_by(|x, y| x.0.total_cmp(&y.0));
    let fifth = by_distance.len() / 5;
    let mean = |s: &[(f32, f32)]| s.iter().map(|x| x.1 as f64).sum::<f64>() / s.len() as f64;
    (
        mean(&by_distance[..fifth]),
        mean(&by_distance[by_distance.len() - fifth..]),
    )
}

/// Pearson's correlation of two per-vertex values.
pub fn correlation(a: &[f32], b: &[f32]) -> f64 {
    let n = a.len() as f64;
    let mean = |v: &[f32]| v.iter().map(|&x| x as f64).sum::<f64>() / n;
    let (ma, mb) = (mean(a), mean(b));
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (&x, &y) in a.iter().zip(b) {
        let (x, y) = (x as f64 - ma, y as f64 - mb);
        ab += x * y;
        aa += x * x;
        bb += y * y;
    }
    ab / (aa * bb).sqrt().max(1e-30)
}
