//! The path tracer's camera rays meet strands (`shaders/lib/strand_rays.wgsl`,
//! `nearest_hit`, the walk `plait::strand_rays` shares with
//! `self_shadow = ray_traced`). The path tracer's own noiseless test keeps
//! its hair out of reach, so a walk that never finds a strand passes it.

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::strand_trace::{blocked, strand};
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

/// One straight strand of radius 0.1 along x before a camera on z (each
/// image row one offset h across it, as `tests/path_traced_one_strand.rs`'
/// scene), lit from the camera's side and a little above (the light
/// travelling along (0, −0.3, −1)), no ambient, nothing else in the scene;
/// path traced at max depth 2, so a pixel holds the key light's next-event
/// estimate at the camera ray's strand hit and nothing else. A path's
/// shadow ray leaves from the camera ray's closest approach to the axis,
/// inside the strand, and skips its own segment and neighbours: a lone
/// strand never shadows itself. Below the axis (image rows 24 on), where
/// the shadow ray's closest approach to the axis lies ahead of it, every
/// fully covered row reads more than a tenth of the brightest row.
/// Measured (lavapipe, Mesa 25.0.7, 8 samples a pixel): rows 24–29 read
/// 0.12–0.29, the brightest 0.30 (row 23). Kills, in
/// `shaders/lib/strand_rays.wgsl`, `skipped_strand`'s test inverted
/// (169:14: a path's rays then skip no segment, each shadow ray from below
/// the axis meets its own strand, and those rows read 0).
#[test]
fn a_lone_strand_never_shadows_itself_below_its_axis() {
    const SIDE: &str = r#"
ambient = 0.0
[hair.procedural]
strands = 1
segments = 1
[camera]
eye = [0.0, 0.0, 4.0]
target = [0.0, 0.0, 0.0]
fov_y_degrees = 10.0
near = 0.1
far = 100.0
[light]
type = "directional"
direction = [0.0, -0.3, -1.0]
intensity = 3.0
[background]
color = [0.0, 0.0, 0.0]
"#;
    let points: Vec<Vec3> = (0..=8)
        .map(|i| Vec3::new(-2.0 + 0.5 * i as f32, 0.0, 0.0))
        .collect();
    let scene = plait_tests::one_strand_scene("pt_lone_strand.toml", SIDE, &points, 0.2, 0.8);
    let (_lock, gpu) = open_gpu();
    let sets = vec!["params.max_depth=2".to_owned(), "params.spp=8".to_owned()];
    let pipeline = repo_root().join("pipelines/physical/path_traced.toml");
    let prepared = prepare(&gpu, &pipeline, &sets, &scene, SIZE).expect("prepares");
    prepared.render().expect("renders, no invocation cut short");
    let image = prepared.radiance().expect("reads the radiance");
    let sums: Vec<f32> =
        bytemuck::cast_slice(&prepared.read_buffer("pt_sum").expect("pt_sum")).to_vec();
    // Per pixel: the part of its camera rays whose first hit is the strand.
    let covered: Vec<f32> = sums.chunks(8).map(|s| s[5] / s[4].max(1.0)).collect();
    let w = SIZE.0 as usize;
    let rows: Vec<(u32, f64)> = (0..SIZE.1)
        .filter(|&y| {
            let r = y as usize * w;
            covered[r..r + w].iter().all(|&c| c >= 1.0)
        })
        .map(|y| {
            let sum: f64 = (0..SIZE.0)
                .map(|x| {
                    let p = image.get_pixel(x, y).0;
                    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
                })
                .sum();
            (y, sum / f64::from(SIZE.0))
        })
        .collect();
    let brightest = rows.iter().map(|r| r.1).fold(0.0, f64::max);
    eprintln!("fully covered rows (row, mean luminance): {rows:.4?}");
    // About 2 × 0.1 / 0.7 of the image's 48 rows: 13, less its edges.
    assert!(rows.len() >= 10, "{} fully covered rows", rows.len());
    let dark: Vec<_> = rows
        .iter()
        .filter(|r| r.0 >= SIZE.1 / 2 && r.1 < 0.1 * brightest)
        .collect();
    assert!(
        dark.is_empty(),
        "rows below the axis under a tenth of the brightest ({brightest:.4}): {dark:.4?}"
    );
}

/// A straight strand along x (half-width 0.005, five segments 0.1 long from
/// x = −0.3) and two rays leaving segment 2 (x from −0.1 to 0) from inside
/// it, as a path's rays leave the segment they hit: from 0.0025 below the
/// axis at x = −0.095 along (−4, 1, 0), and at x = −0.005 along (4, 1, 0).
/// Each meets the axis 0.01 along x further on, past the segment's ends:
/// in segment 1 (x = −0.105) and in segment 3 (x = 0.005). A path's rays
/// skip the segment they leave and both its neighbours
/// (`plait::strand_rays::box_crossing`), so leaving segment 2 neither is
/// blocked; leaving no segment both are (the strand is in their way).
/// Kills, in `shaders/lib/strand_rays.wgsl`, the skip's first bound
/// `i + 1u >= skip` → `i >= skip` (198:62: segment 1, the previous
/// neighbour, no longer skipped: the first ray is blocked).
#[test]
fn a_paths_ray_skips_both_neighbours_of_the_segment_it_leaves() {
    let points: Vec<Vec3> = (0..6)
        .map(|i| Vec3::new(-0.3 + 0.1 * i as f32, 0.0, 0.0))
        .collect();
    let vertices = strand(&points, 0.01, 0);
    let rays = [
        (Vec3::new(-0.095, -0.0025, 0.0), Vec3::new(-4.0, 1.0, 0.0)),
        (Vec3::new(-0.005, -0.0025, 0.0), Vec3::new(4.0, 1.0, 0.0)),
    ];
    let mut wrong = Vec::new();
    for (skip, want) in [(2u32, false), (u32::MAX, true)] {
        for (origin, dir) in rays {
            let found = blocked(&vertices, &[origin], dir.normalize(), skip)[0];
            if found != want {
                wrong.push(format!(
                    "leaving segment {skip:#x} from {origin} along {dir}: blocked {found}"
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}
