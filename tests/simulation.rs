//! Simulation and GPU guide interpolation (issue 12; Halén & Wester 2007 §4,
//! §4.4, §5.4–5.5): the default pipeline with `techniques.simulation=verlet`
//! on tiny grooms (a few strands, 8 segments, 16² light maps, 32×24), each
//! frame a few milliseconds on lavapipe. Positions are read back from the
//! scene resources `guide_positions` and `hair_vertices`.

use std::path::Path;

use glam::Vec3;
use plait::session::{Prepared, SceneData, compile_checked, prepare};
use plait_graph::CompileOptions;
use plait_hair::scene::Scene;
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (32, 24);

/// A small straight groom on the default head; `guides` guide strands when set.
fn groom(strands: u32, guides: Option<u32>) -> SceneData {
    groom_on(strands, guides, ELLIPSOID_HEAD)
}

const ELLIPSOID_HEAD: &str = "[head]\ncenter = [0.0, 0.0, 0.0]\nradii = [0.9, 1.05, 1.0]\n";

/// The same head as a mesh: `examples/scenes/head.glb` (the ellipsoid, 32 × 64
/// quads, written by `cargo run --example make_assets`), colliding through
/// its signed distance field only (the scene has no ellipsoid).
fn mesh_head() -> String {
    let file = repo_root().join("examples/scenes/head.glb");
    format!(
        "[[meshes]]\nfile = {:?}\nrole = \"head\"\n",
        file.display().to_string()
    )
}

fn groom_on(strands: u32, guides: Option<u32>, head: &str) -> SceneData {
    let guides = guides.map_or(String::new(), |g| format!("guides = {g}\n"));
    let text = format!(
        r#"
[hair.procedural]
style = "straight"
strands = {strands}
segments = 8
seed = 5
length = 1.5
{guides}
{head}
[camera]
eye = [0.0, 0.0, 7.0]
target = [0.0, -0.5, 0.0]
fov_y_degrees = 40.0

[light]
type = "directional"
direction = [-0.5, -1.0, -0.6]
"#
    );
    let scene = Scene::from_toml_str(&text, Path::new("sim_test.toml")).expect("test scene parses");
    SceneData::new(scene).expect("test scene loads")
}

fn sets(extra: &[&str]) -> Vec<String> {
    let mut s = vec![
        "techniques.simulation=verlet".to_owned(),
        "params.light_size=16".to_owned(),
    ];
    s.extend(extra.iter().map(|e| e.to_string()));
    s
}

fn pipeline() -> std::path::PathBuf {
    repo_root().join("pipelines/occupancy.toml")
}

fn vec4s(bytes: &[u8]) -> Vec<Vec3> {
    bytemuck::cast_slice::<u8, [f32; 4]>(bytes)
        .iter()
        .map(|v| Vec3::new(v[0], v[1], v[2]))
        .collect()
}

fn guide_positions(p: &Prepared<'_>, count: usize) -> Vec<Vec3> {
    let bytes = p
        .read_buffer("guide_positions")
        .expect("guide_positions reads back");
    vec4s(&bytes)[..count].to_vec()
}

fn guide_previous(p: &Prepared<'_>, count: usize) -> Vec<Vec3> {
    let bytes = p
        .read_buffer("guide_previous")
        .expect("guide_previous reads back");
    vec4s(&bytes)[..count].to_vec()
}

fn render(p: &Prepared<'_>, frames: usize) {
    for _ in 0..frames {
        p.render_unchecked().expect("frame renders");
    }
}

/// Σ |x − x_prev|² over the nodes: twice the kinetic energy × Δt² (unit mass).
fn kinetic(p: &Prepared<'_>, count: usize) -> f64 {
    guide_positions(p, count)
        .iter()
        .zip(guide_previous(p, count))
        .map(|(a, b)| (*a - b).length_squared() as f64)
        .sum()
}

#[test]
fn a_strand_at_rest_stays_at_rest() {
    let (_lock, gpu) = open_gpu();
    let scene = groom(12, None);
    let p = prepare(&gpu, &pipeline(), &sets(&[]), &scene, SIZE).expect("pipeline builds");
    let rest = &scene.guides.strands.points;
    let n = rest.len();
    render(&p, 2);
    let early = kinetic(&p, n);
    render(&p, 40);
    let late = kinetic(&p, n);
    let drift = guide_positions(&p, n)
        .iter()
        .zip(rest)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0f32, f32::max);
    eprintln!("at rest: drift {drift:e}, energy {early:e} → {late:e}");
    // Gravity is balanced by the springs' displaced references (§4.4) and the
    // rest lengths are met: only rounding moves a node (1e-4 = 5e4 ulp of 2).
    assert!(drift < 1e-4, "a node drifted {drift} from rest");
    assert!(
        late <= early.max(1e-12),
        "energy grew at rest: {early:e} → {late:e}"
    );
}

/// Mechanical energy per unit mass: Σ ½|v|² + g·y, v = (x − x_prev) / Δt.
fn energy(p: &Prepared<'_>, count: usize, dt: f64, g: f64) -> f64 {
    guide_positions(p, count)
        .iter()
        .zip(guide_previous(p, count))
        .map(|(a, b)| 0.5 * ((*a - b).length_squared() as f64) / (dt * dt) + g * a.y as f64)
        .sum()
}

#[test]
fn a_falling_strand_loses_energy() {
    let (_lock, gpu) = open_gpu();
    let scene = groom(12, None);
    let n = scene.guides.strands.points.len();
    // No spring: chains released from their groomed shape swing down under
    // gravity. Damping (k = 0.97 of 4.1), the length projection and the
    // collisions only take energy out; Verlet must not put any in.
    let falling = sets(&["params.sim_spring=0.0"]);
    let p = prepare(&gpu, &pipeline(), &falling, &scene, SIZE).expect("pipeline builds");
    let (dt, g) = (0.008333, 9.8);
    render(&p, 1);
    let start = energy(&p, n, dt, g);
    let mut last = start;
    let mut moved = 0.0f32;
    for frame in 2..=60 {
        render(&p, 1);
        let e = energy(&p, n, dt, g);
        // 1e-3 of the start: per-frame rounding of f32 positions ~2 units.
        assert!(
            e <= last + 1e-3 * start.abs().max(1.0),
            "energy grew in frame {frame}: {last} → {e}"
        );
        last = e;
        if frame == 60 {
            moved = guide_positions(&p, n)
                .iter()
                .zip(&scene.guides.strands.points)
                .map(|(a, b)| (*a - *b).length())
                .fold(0.0f32, f32::max);
        }
    }
    eprintln!("falling: energy {start:.4} → {last:.4} over 60 frames, moved {moved}");
    assert!(
        moved > 0.05,
        "without springs the strands should fall (moved {moved})"
    );
    assert!(last < start, "energy should drop: {start} → {last}");
}

/// Segment lengths of guide strands over their rest lengths, worst |ratio − 1|.
fn worst_length_error(scene: &SceneData, points: &[Vec3]) -> f32 {
    let g = &scene.guides.strands;
    let mut worst = 0.0f32;
    for r in g.ranges() {
        for i in r.start + 1..r.end {
            let rest = (g.points[i] - g.points[i - 1]).length();
            let now = (points[i] - points[i - 1]).length();
            worst = worst.max((now / rest - 1.0).abs());
        }
    }
    worst
}

#[test]
fn length_constraints_hold_in_wind() {
    let (_lock, gpu) = open_gpu();
    let scene = groom(12, None);
    let n = scene.guides.strands.points.len();
    let windy = sets(&[
        "params.sim_wind=[6.0, 0.0, 4.0]",
        "params.sim_turbulence=0.5",
        "params.sim_spring=5.0",
    ]);
    let p = prepare(&gpu, &pipeline(), &windy, &scene, SIZE).expect("pipeline builds");
    render(&p, 30);
    let now = guide_positions(&p, n);
    let moved = now
        .iter()
        .zip(&scene.guides.strands.points)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0f32, f32::max);
    assert!(
        moved > 0.05,
        "the wind should move the hair (moved {moved})"
    );
    // 4 sweeps of (4.2) per step keep every segment within 2% of its rest
    // length under this wind (measured: see the message on failure).
    let worst = worst_length_error(&scene, &now);
    eprintln!(
        "in wind: moved {moved}, worst segment length error {:.3}%",
        worst * 100.0
    );
    assert!(
        worst < 0.02,
        "a segment is {:.2}% off its rest length",
        worst * 100.0
    );
}

#[test]
fn collisions_keep_the_hair_outside_the_head() {
    let (_lock, gpu) = open_gpu();
    // 1 − 1e-5: the node is moved onto the ellipsoid, up to rounding.
    let deepest = pressed_onto(&gpu, &groom(16, None));
    assert!(
        deepest >= 1.0 - 1e-5,
        "a node is inside the head: |q| = {deepest}"
    );
}

/// The same test against the head as a mesh. Its surface lies inside the
/// ellipsoid by up to 1 − cos(π/32) ≈ 0.5% of the radius between vertices
/// (the mesh is inscribed), and the 32³ field interpolates trilinearly:
/// 1% is allowed (measured on lavapipe: 0.9965).
#[test]
fn collisions_keep_the_hair_outside_a_mesh_head() {
    let (_lock, gpu) = open_gpu();
    let scene = groom_on(16, None, &mesh_head());
    assert!(scene.colliders.is_empty() && scene.head_sdf.is_some());
    let deepest = pressed_onto(&gpu, &scene);
    assert!(
        deepest >= 0.99,
        "a node is inside the mesh head: |q| = {deepest}"
    );
    // Without the field the same wind pushes the hair deep into the head:
    // the test above fails when the mesh does not collide.
    let mut without = groom_on(16, None, &mesh_head());
    without.head_sdf = None;
    let deepest = pressed_onto(&gpu, &without);
    assert!(
        deepest < 0.95,
        "with no collider the hair enters the head: |q| = {deepest}"
    );
}

/// The deepest node (in ellipsoid units, 1 on the surface) after 30 frames
/// of wind pressing the hair onto the default head, with no spring.
fn pressed_onto(gpu: &plait_gpu::Gpu, scene: &SceneData) -> f32 {
    let n = scene.guides.strands.points.len();
    // No spring, wind blowing into the head from behind and above: without
    // collisions the hair would pass through it.
    let push = sets(&[
        "params.sim_spring=0.0",
        "params.sim_wind=[0.0, -10.0, 20.0]",
    ]);
    let p = prepare(gpu, &pipeline(), &push, scene, SIZE).expect("pipeline builds");
    render(&p, 30);
    let (c, r) = (Vec3::ZERO, Vec3::new(0.9, 1.05, 1.0));
    let now = guide_positions(&p, n);
    let deepest = now
        .iter()
        .map(|x| ((*x - c) / r).length())
        .fold(f32::INFINITY, f32::min);
    eprintln!("collisions: deepest node at |q| = {deepest}");
    let moved = now
        .iter()
        .zip(&scene.guides.strands.points)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0f32, f32::max);
    assert!(
        moved > 0.1,
        "the wind should press the hair onto the head (moved {moved})"
    );
    deepest
}

#[test]
fn gpu_interpolation_matches_the_cpu() {
    let (_lock, gpu) = open_gpu();
    let scene = groom(200, Some(24));
    assert!(!scene.guides.is_identity(), "the groom has guides");
    let guide_points = scene.guides.strands.points.len();
    let windy = sets(&[
        "params.sim_wind=[5.0, 0.0, 3.0]",
        "params.sim_turbulence=0.3",
    ]);
    let p = prepare(&gpu, &pipeline(), &windy, &scene, SIZE).expect("pipeline builds");
    render(&p, 10);
    let guides_now = guide_positions(&p, guide_points);
    let expected = scene.guides.interpolate(&scene.strands, &guides_now);
    let bytes = p
        .read_buffer("hair_vertices")
        .expect("hair_vertices reads back");
    let drawn: &[plait_hair::StrandVertex] = bytemuck::cast_slice(&bytes);
    // The per-point GPU pass writes central differences of the moved points.
    let tangents = expected.central_tangents();
    let mut worst_position = 0.0f32;
    let mut worst_tangent = 0.0f32;
    for (i, v) in drawn.iter().enumerate().take(expected.points.len()) {
        worst_position = worst_position.max((Vec3::from(v.position) - expected.points[i]).length());
        worst_tangent = worst_tangent.max((Vec3::from(v.tangent) - tangents[i]).length());
    }
    let moved = guides_now
        .iter()
        .zip(&scene.guides.strands.points)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0f32, f32::max);
    assert!(moved > 0.02, "the guides should move (moved {moved})");
    eprintln!(
        "interpolation: guides moved {moved}, GPU − CPU position {worst_position:e}, tangent {worst_tangent:e}"
    );
    // Same operations in f32, in a different order (FMA on the GPU): a few
    // ulp of coordinates ≈ 2, so 1e-5; tangents are unit vectors, 1e-4.
    assert!(
        worst_position < 1e-5,
        "GPU vs CPU position differs by {worst_position}"
    );
    assert!(
        worst_tangent < 1e-4,
        "GPU vs CPU tangent differs by {worst_tangent}"
    );
}

#[test]
fn unstable_params_are_rejected_at_load() {
    let err = compile_checked(
        &pipeline(),
        &sets(&["params.sim_time_step=0.5"]),
        &CompileOptions::default(),
    )
    .expect_err("time_step 0.5 with spring 40 cannot be stable");
    let text = err.to_string();
    assert!(text.contains("cannot be stable"), "{text}");
    assert!(
        text.contains("techniques/simulation/verlet/technique.toml:"),
        "names the pass's file: {text}"
    );
}

#[test]
fn writing_a_read_only_scene_resource_is_a_load_error() {
    let err = compile_checked(
        &pipeline(),
        &sets(&["passes.interpolate.writes.vertices=\"hair_indices\""]),
        &CompileOptions::default(),
    )
    .expect_err("hair_indices is read-only");
    let text = err.to_string();
    assert!(
        text.contains("scene resource `hair_indices` is read-only"),
        "{text}"
    );
}

#[test]
fn a_nan_is_reported_with_the_pass_and_strand() {
    let (_lock, gpu) = open_gpu();
    let mut scene = groom(6, None);
    // A non-finite rest point in strand 2 (9 points a strand): its segment's
    // constraint turns the strand's nodes NaN in the first frame.
    scene.guides.strands.points[2 * 9 + 4].x = f32::NAN;
    let p = prepare(&gpu, &pipeline(), &sets(&[]), &scene, SIZE).expect("pipeline builds");
    let err = p
        .render_unchecked()
        .expect_err("a NaN must fail the frame")
        .to_string();
    assert!(err.contains("pass `simulate`"), "{err}");
    assert!(
        err.contains("guide strand 2 has a non-finite position"),
        "{err}"
    );
    assert!(err.contains("frame 1"), "{err}");
}

#[test]
fn runaway_lengths_are_reported() {
    let (_lock, gpu) = open_gpu();
    let scene = groom(6, None);
    // No constraints and a huge pull: strands stretch in the first frame.
    let wild = sets(&[
        "params.sim_iterations=0",
        "params.sim_spring=0.0",
        "params.sim_gravity=1000.0",
        "params.sim_time_step=0.05",
    ]);
    let p = prepare(&gpu, &pipeline(), &wild, &scene, SIZE).expect("pipeline builds");
    let err = p
        .render_unchecked()
        .expect_err("stretching must fail the frame")
        .to_string();
    assert!(err.contains("its rest length"), "{err}");
    assert!(err.contains("frame 1"), "{err}");
}

/// 64 substeps of 64 constraint sweeps over 9-point guides run ~150,000 loop
/// iterations per guide, past lavapipe's 65,535 per group of 8 invocations:
/// the kernel's loops stop early, silently, unless the kernel tells — and it
/// does (the canary loop of `plait::loop_budget`), so the frame fails.
/// The defaults (~3,500) finish. A driver without the limit finishes both.
#[test]
fn a_simulation_cut_short_by_the_loop_budget_fails_the_frame() {
    let (_lock, gpu) = open_gpu();
    let scene = groom(6, None);
    let p = prepare(&gpu, &pipeline(), &sets(&[]), &scene, SIZE).expect("pipeline builds");
    p.render_unchecked().expect("the defaults finish");
    let long = sets(&["params.sim_substeps=64", "params.sim_iterations=64"]);
    let p = prepare(&gpu, &pipeline(), &long, &scene, SIZE).expect("pipeline builds");
    let result = p.render_unchecked();
    if gpu
        .loop_budget()
        .expect("the loop-budget probe runs")
        .is_some()
    {
        let err = result.expect_err("a cut frame must fail").to_string();
        assert!(err.contains("pass `simulate`"), "{err}");
        assert!(err.contains("could not finish frame 1"), "{err}");
        assert!(err.contains("65,535"), "{err}");
    } else {
        result.expect("no loop budget: the frame finishes");
    }
}

#[test]
fn a_head_turn_renders_60_frames_with_the_hair_outside_the_turning_head() {
    // The issue's Done line on examples/scenes/head_turn.toml (400 strands,
    // 45° and back in 2 s), at 32×24 with 16² light maps.
    let (_lock, gpu) = open_gpu();
    let path = repo_root().join("examples/scenes/head_turn.toml");
    let scene = SceneData::load(Some(&path)).expect("head_turn scene");
    head_turn(&gpu, &scene, 1.0 - 1e-4);
}

/// The same turn with the head read from `examples/scenes/head.glb` in place
/// of `[head]`: roots ride the mesh head's pose, the hair lags and settles
/// as on the ellipsoid. (In this turn no node reaches the head — the deepest
/// sits at 1.008 with either head — so pressing hair onto the mesh is
/// `collisions_keep_the_hair_outside_a_mesh_head`'s job.)
#[test]
fn a_mesh_head_turn_keeps_the_hair_outside() {
    let (_lock, gpu) = open_gpu();
    let path = repo_root().join("examples/scenes/head_turn.toml");
    let text = std::fs::read_to_string(&path).expect("head_turn.toml");
    let text = text.replace(ELLIPSOID_HEAD, &mesh_head());
    let scene = Scene::from_toml_str(&text, &path).expect("the mesh head turn parses");
    assert!(
        scene.head.is_none(),
        "head_turn.toml's [head] is the default ellipsoid"
    );
    let scene = SceneData::new(scene).expect("loads");
    head_turn(&gpu, &scene, 0.99);
}

/// 60 frames of the scene's head turn then 60 at rest: roots ride the head,
/// no node deeper than `surface` (in units of the default head ellipsoid)
/// in the head, the hair lags and settles.
fn head_turn(gpu: &plait_gpu::Gpu, scene: &SceneData, surface: f32) {
    let mut p = prepare(gpu, &pipeline(), &sets(&[]), scene, SIZE).expect("pipeline builds");
    assert!(!p.hair_follows_head, "the simulation moves the hair itself");
    let n = scene.guides.strands.points.len();
    let roots: Vec<usize> = scene.guides.strands.ranges().map(|r| r.start).collect();
    let (c, r) = (Vec3::ZERO, Vec3::new(0.9, 1.05, 1.0));
    let mut deepest = f32::INFINITY;
    let mut root_error = 0.0f32;
    let mut lag = 0.0f32;
    for index in 0..60 {
        p.render_frame(scene, SIZE, index, 30.0)
            .unwrap_or_else(|e| panic!("frame {index}: {e}"));
        let head = scene.scene.head_model(index as f32 / 30.0);
        let to_rest = head.inverse();
        let now = guide_positions(&p, n);
        for (i, x) in now.iter().enumerate() {
            let rest = scene.guides.strands.points[i];
            if roots.contains(&i) {
                root_error = root_error.max((*x - head.transform_point3(rest)).length());
                continue;
            }
            deepest = deepest.min(((to_rest.transform_point3(*x) - c) / r).length());
            lag = lag.max((*x - head.transform_point3(rest)).length());
        }
    }
    eprintln!(
        "head turn: deepest |q| {deepest}, root error {root_error:e}, largest lag behind rigid {lag}"
    );
    // Roots ride the head (f32 matrix products: 1e-5); the rest stays out of
    // it (1e-4: the collision is resolved in the substep's pose, checked
    // here against the frame's); the hair lags behind a rigid turn.
    assert!(root_error < 1e-5, "a root left the head by {root_error}");
    assert!(
        deepest >= surface,
        "a node is inside the turning head: |q| = {deepest}"
    );
    assert!(
        lag > 0.05,
        "the hair should lag behind the head (lag {lag})"
    );
    // §4 criterion 1: back at rest, the hair returns to its groomed shape
    // (the head holds still after 2 s; 2 s more at 30 fps).
    for index in 60..120 {
        p.render_frame(scene, SIZE, index, 30.0)
            .unwrap_or_else(|e| panic!("frame {index}: {e}"));
    }
    let settled = guide_positions(&p, n)
        .iter()
        .zip(&scene.guides.strands.points)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0f32, f32::max);
    eprintln!("head turn: 2 s after the turn the farthest node is {settled} from rest");
    // Measured 0.053 on lavapipe, against a lag of 1.07 at the turn (strands
    // 1.5–2.5 long, damping 0.97 a step, still decaying): 0.1 tells settling
    // from hair stuck on the wrong side of the head.
    assert!(settled < 0.1, "the hair did not return to rest: {settled}");
}

#[test]
fn hair_without_colliders_falls_freely() {
    // No head to collide with (the scene's colliders removed): the binding
    // gets a placeholder collider of radii 0 and the hair falls through.
    let (_lock, gpu) = open_gpu();
    let mut scene = groom(8, None);
    scene.colliders.clear();
    let n = scene.guides.strands.points.len();
    let p = prepare(
        &gpu,
        &pipeline(),
        &sets(&["params.sim_spring=0.0"]),
        &scene,
        SIZE,
    )
    .expect("pipeline builds");
    render(&p, 20);
    let (c, r) = (Vec3::ZERO, Vec3::new(0.9, 1.05, 1.0));
    let deepest = guide_positions(&p, n)
        .iter()
        .map(|x| ((*x - c) / r).length())
        .fold(f32::INFINITY, f32::min);
    eprintln!("no colliders: deepest |q| = {deepest}");
    assert!(
        deepest < 0.99,
        "with nothing to stop it some hair enters the head's space"
    );
}
