//! `shading/marschner`: the angles of `shaders/lib/marschner.wgsl`.

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

/// The cases of `tests/fixtures/marschner_angles.wgsl`: (sin θi, sin θr,
/// cos φ), known exactly.
const ANGLES: [[f32; 3]; 4] = [
    [1.0, 0.0, 0.0],
    [1.0, 0.0, 1.0],
    [-1.0, 1.0, 1.0],
    [1.0, -1.0, 1.0],
];

/// `hair_angles` (§5.8's sin θi, sin θr, cos φ from dot products): the
/// azimuth is computed wherever the perpendicular parts' norms² pass 1e-12
/// and is the backscatter one (cos φ = 1) below it; the sines stay in
/// [-1, 1] when rounding puts a dot of unit vectors past 1 (asin of them
/// would be NaN in the reference model). Exact values. Kills, in
/// `shaders/lib/marschner.wgsl`, the threshold 1e-12 → 1.1e-12 (case 0 reads
/// cos φ = 1 instead of 0) and the clamp of sin θr to 1.0 → 1.1 (case 2).
#[test]
fn marschner_hair_angles_are_exact_at_the_degenerate_azimuth_and_past_unit_dots() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/marschner_angles.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (4, 4)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let bytes = prepared.read_buffer("angles").expect("angles");
    let got: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let mut failures = Vec::new();
    for (k, want) in ANGLES.iter().enumerate() {
        let case = &got[4 * k..4 * k + 3];
        if case != want {
            failures.push(format!(
                "case {k}: (sin θi, sin θr, cos φ) {case:?}, exactly {want:?}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
