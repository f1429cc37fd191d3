//! `ambient_occlusion/cylinders`: the scalp discs of
//! `shaders/passes/occlusion_cylinders.wgsl`.

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_hair::mesh::Mesh;
use plait_tests::{open_gpu, repo_root};

/// Per-vertex ambient visibility by `cylinders` (the fixture
/// `tests/fixtures/ambient_occlusion.toml`), one value per hair vertex.
fn cylinders_ao(gpu: &Gpu, scene: &SceneData) -> Vec<f32> {
    let pipeline = repo_root().join("tests/fixtures/ambient_occlusion.toml");
    let sets = ["techniques.ambient_occlusion=cylinders".to_string()];
    let prepared = prepare(gpu, &pipeline, &sets, scene, (64, 48)).expect("prepares");
    let report = prepared.render_unchecked().expect("renders");
    plait::overflow::check_frame(&report).expect("no overflow");
    let bytes = prepared.read_buffer("ao_vertex").expect("ao_vertex");
    bytes
        .chunks_exact(4)
        .take(scene.strands.points.len())
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// The scalp is the opaque triangles whose centroid lies in the hair's
/// bounding box (the head under the hair, not the ground): a small quad
/// facing up 0.1 below the lowest hair vertex, centred under the hair —
/// both its triangles' centroids below the box and inside its x and z
/// extent — leaves every vertex's visibility unchanged (within 1e-5: the
/// extra triangles may move a chunk boundary of the sum). Kills, in
/// `shaders/passes/occlusion_cylinders.wgsl`, `any(m < lo) || any(m > hi)`
/// → `&&` (a centroid outside the box on its low side only is counted: the
/// quad darkens the tips). The small scene's own ground is large, so each
/// of its centroids lies both below some bound and above another, and the
/// gallery's tests could not see it.
#[test]
fn cylinders_ignore_a_triangle_below_the_hair_box() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let points = &scene.strands.points;
    let lo = points
        .iter()
        .fold(glam::Vec3::splat(f32::MAX), |a, &p| a.min(p));
    let hi = points
        .iter()
        .fold(glam::Vec3::splat(f32::MIN), |a, &p| a.max(p));
    let centre = (lo + hi) / 2.0;
    let half = 0.25 * (hi.x - lo.x).min(hi.z - lo.z);
    let quad = Mesh::ground_plane(glam::Vec3::new(centre.x, lo.y - 0.1, centre.z), half);
    let mut with_quad = scene.clone();
    with_quad.meshes.push(quad);
    let (without, with) = (cylinders_ao(&gpu, &scene), cylinders_ao(&gpu, &with_quad));
    let worst = without
        .iter()
        .zip(&with)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    eprintln!("largest change of a vertex's visibility by the quad: {worst:e}");
    assert!(
        worst <= 1e-5,
        "a quad outside the hair box changed a vertex's visibility by {worst}"
    );
}
