//! The path tracer's camera rays meet strands (`shaders/lib/strand_rays.wgsl`,
//! `nearest_hit`, the walk `plait::strand_rays` shares with
//! `self_shadow = ray_traced`). The path tracer's own noiseless test keeps
//! its hair out of reach, so a walk that never finds a strand passes it.

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (64, 48);

/// The luminance of the 3×3 pixels about the image's centre, path traced at
/// max depth 2 (2 samples per pixel).
fn centre(gpu: &Gpu, scene: &SceneData) -> f64 {
    let sets = vec!["params.max_depth=2".to_owned(), "params.spp=2".to_owned()];
    let pipeline = repo_root().join("pipelines/physical/path_traced.toml");
    let prepared = prepare(gpu, &pipeline, &sets, scene, SIZE).expect("prepares");
    prepared.render().expect("renders, no invocation cut short");
    let image = prepared.radiance().expect("reads the radiance");
    let (cx, cy) = (SIZE.0 / 2, SIZE.1 / 2);
    let mut sum = 0.0;
    for y in cy - 1..=cy + 1 {
        for x in cx - 1..=cx + 1 {
            let p = image.get_pixel(x, y).0;
            sum += 0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2]);
        }
    }
    sum / 9.0
}

/// The measurement scene (`tests/scenes/ms_blond.toml`: the head at the
/// view's centre, lit) with its hair replaced by one black strand 0.4 thick
/// (about 8 px here) across the view halfway between the eye and the
/// target, so it covers the centre pixels. Black fibres absorb what enters
/// them, so those pixels keep only the surface's reflection. They read
/// less than a third of the same pixels without the strand (measured 0.0070
/// against 0.0809; at 0.2 thick, 0.041, the strand's edges in the 3×3).
/// Under the mutant the two read the same, 0.0809. Kills, in
/// `shaders/lib/strand_rays.wgsl`, `nearest_hit`'s box test `!=` → `==`
/// (149:20): the walk then skips every strand, and the head shows through.
#[test]
fn a_black_strand_before_the_eye_hides_the_head_behind_it() {
    let (_lock, gpu) = open_gpu();
    let path = repo_root().join("tests/scenes/ms_blond.toml");
    let mut scene = SceneData::load(Some(&path)).expect("the scene loads");
    scene.guides = plait_hair::guides::Guides::default();
    let (eye, target) = (Vec3::new(2.0, 0.5, 7.6), Vec3::new(0.0, -0.6, 0.0));
    let middle = eye + 0.5 * (target - eye);
    let across = (target - eye).cross(Vec3::Y).normalize() * 0.6;
    scene.strands = plait_hair::Strands::new();
    // Far below the ground: no camera or light ray reaches it.
    let below = Vec3::new(0.0, -50.0, 0.0);
    scene.strands.push_strand(
        &[below, below + Vec3::X * 0.1],
        |_| 0.01,
        |_| 1.0,
        Vec3::splat(0.0),
    );
    let without = centre(&gpu, &scene);
    scene.strands = plait_hair::Strands::new();
    scene.strands.push_strand(
        &[middle - across, middle + across],
        |_| 0.4,
        |_| 1.0,
        Vec3::splat(0.0),
    );
    let with = centre(&gpu, &scene);
    eprintln!("centre luminance: {without:.4} without the strand, {with:.4} behind it");
    assert!(without > 0.05, "the head is lit at the centre: {without}");
    assert!(
        with < without / 3.0,
        "the strand must hide the head: {with} behind it, {without} without"
    );
}
