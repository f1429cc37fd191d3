//! `ambient_occlusion = ray_traced` (issue 48): rays over the sphere from
//! every hair vertex through the strands' acceleration structure, each
//! vertex's visibility the mean of exp(−w · strands crossed).
//!
//! - Against geometry: beside a long straight strand of radius r at distance
//!   d, an opaque one hides the share of the sphere an infinite cylinder
//!   does, asin(r/d)/π, cut where the rays pass its ends; the vertex's own
//!   strand hides nothing.
//! - On every other strand of the small scene: in [0, 1], inner hair darker
//!   than outer, the error against 256 rays falling as the rays grow, and
//!   darkening the vertices deep opacity maps from 100 directions darken
//!   (Xing et al. 2012 §4, the estimator it traces). Half the strands: the
//!   rays cost ~40 µs each on lavapipe (32 rays from the whole small scene's
//!   6,800 vertices took 9.0 s).
//! - A groom larger than its per-vertex buffer is reported naming
//!   `ao_max_vertices`.

use glam::Vec3;
use plait::session::SceneData;
use plait_gpu::Gpu;
use plait_tests::vertex_ao::{correlation, inner_outer, mean_abs_diff, vertex_ao_report};
use plait_tests::{open_gpu, repo_root, strands_subset};

const SIZE: (u32, u32) = (64, 48);

fn small_scene() -> SceneData {
    SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads")
}

fn require_ray_queries(gpu: &Gpu) {
    assert!(
        gpu.capabilities.ray_query,
        "adapter {} has no ray queries: the test command runs on Mesa 25's lavapipe (bash scripts/ensure-vulkan.sh installs it)",
        gpu.support.describe()
    );
}

fn vertex_ao(
    gpu: &Gpu,
    scene: &SceneData,
    technique: &str,
    sets: &[String],
) -> (Vec<f32>, plait_gpu::FrameReport) {
    vertex_ao_report(gpu, scene, technique, sets, SIZE)
}

fn traced(gpu: &Gpu, scene: &SceneData, sets: &[&str]) -> Vec<f32> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let (ao, report) = vertex_ao(gpu, scene, "ray_traced", &sets);
    plait::overflow::check_frame(&report).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
    ao
}

/// Two vertical strands 21 units long, `d` apart: `a` thin, `b` of radius
/// `r`. Vertex 10 is `a`'s middle.
fn two_strands(d: f32, r: f32) -> SceneData {
    two_strands_at(d, r, 0.0)
}

/// [`two_strands`] with `b` at `azimuth` radians from +x about the strands'
/// axis (y), toward +z.
fn two_strands_at(d: f32, r: f32, azimuth: f32) -> SceneData {
    let mut scene = small_scene();
    let mut strands = plait_hair::Strands::new();
    let line = |x: f32, z: f32| -> Vec<Vec3> {
        (0..21).map(|k| Vec3::new(x, k as f32 - 10.0, z)).collect()
    };
    let (sin, cos) = azimuth.sin_cos();
    strands.push_strand(&line(0.0, 0.0), |_| 0.01, |_| 1.0, Vec3::splat(0.5));
    strands.push_strand(
        &line(d * cos, d * sin),
        |_| 2.0 * r,
        |_| 1.0,
        Vec3::splat(0.5),
    );
    scene.strands = strands;
    // The strands run through the small scene's head and ground, which
    // the structure holds too (tests/ray_traced_meshes.rs): strands alone.
    scene.meshes.clear();
    scene
}

/// The share of uniform directions from the axis of `a` whose ray crosses a
/// cylinder of radius r at distance d, 10 units up and down: asin(r/d)/π of
/// the azimuths, at elevations whose rays reach it within its ends
/// (|z| < 10 / √(d² + 100), the near side's distance ≈ d).
fn cylinder_share(d: f64, r: f64) -> f64 {
    (r / d).asin() / std::f64::consts::PI * (10.0 / (d * d + 100.0).sqrt())
}

#[test]
fn an_opaque_strand_beside_hides_the_share_of_the_sphere_a_cylinder_does() {
    let (_lock, gpu) = open_gpu();
    require_ray_queries(&gpu);
    let sets = ["params.ao_rays=1024", "params.ao_shadow_weight=10"];
    let opaque = 1.0 - (-10.0f64).exp();
    for (d, r) in [(1.0f32, 0.5f32), (1.0, 0.25), (2.0, 0.5)] {
        let ao = traced(&gpu, &two_strands(d, r), &sets);
        let expected = 1.0 - opaque * cylinder_share(d as f64, r as f64);
        let got = ao[10] as f64;
        eprintln!("d {d}, r {r}: visibility {got:.4}, cylinder {expected:.4}");
        // 1024 lattice directions: the lattice's own error on a share of
        // ~0.17 is below 0.005; the cylinder's ends add < 0.002.
        assert!(
            (got - expected).abs() < 0.01,
            "d {d}, r {r}: visibility {got:.4}, the cylinder's share gives {expected:.4}"
        );
    }
    // The strands' far ends see the other strand over half the heights only.
    let ao = traced(&gpu, &two_strands(1.0, 0.5), &sets);
    assert!(
        ao[0] > ao[10] + 0.05,
        "an end {:.4}, the middle {:.4}",
        ao[0],
        ao[10]
    );
}

/// The same strand half opaque (w = 0.5): a ray crosses the cylinder once,
/// so the vertex keeps 1 − share · (1 − e^−w), 0.9348 at d 1, r 0.5 — where
/// a crossing counted twice gives 1 − share · (1 − e^−2w), 0.8952, which
/// the opaque strand above (e^−10 ≈ e^−20 ≈ 0) cannot tell apart.
#[test]
fn a_half_opaque_strand_beside_is_crossed_once_per_ray() {
    let (_lock, gpu) = open_gpu();
    require_ray_queries(&gpu);
    let w = 0.5f64;
    let sets = ["params.ao_rays=1024", "params.ao_shadow_weight=0.5"];
    for (d, r) in [(1.0f32, 0.5f32), (2.0, 0.5)] {
        let ao = traced(&gpu, &two_strands(d, r), &sets);
        let share = cylinder_share(d as f64, r as f64);
        let expected = 1.0 - (1.0 - (-w).exp()) * share;
        let got = ao[10] as f64;
        eprintln!("d {d}, r {r}, w {w}: visibility {got:.4}, once per ray {expected:.4}");
        assert!(
            (got - expected).abs() < 0.006,
            "d {d}, r {r}, w {w}: visibility {got:.4}, one crossing per ray gives {expected:.4}"
        );
    }
}

/// The strand beside as DOTS (`ao_strand_primitive = "dots"`, two crossed
/// quads, four triangles a segment; issue 48). The same 1024 lattice rays
/// meet it whatever its opacity, so a ray that counts the segment once
/// keeps 1 − share · (1 − e^−w) for every w: the half-opaque strand's loss
/// over the opaque one's is (1 − e^−0.5)/(1 − e^−10) = 0.3935, for any
/// share. A ray counted once per quad crossed (up to twice) gives between
/// that and (1 − e^−1)/(1 − e^−10) = 0.632. The strand beside stands at 45°
/// from the quads' planes (a vertical segment's quads span x and z): from
/// +x, the vertex would lie in one quad's plane, and no ray could cross
/// both. Its share is the crossed quads', not the cylinder's: held only to
/// lie near it (they stand for it).
#[test]
fn dots_beside_are_crossed_once_per_ray() {
    let (_lock, gpu) = open_gpu();
    require_ray_queries(&gpu);
    let dots = "params.ao_strand_primitive=dots";
    // r ≠ 0.5: half the width is then not its reciprocal too.
    let (d, r) = (0.8f32, 0.4f32);
    let loss = |weight: &str| {
        let scene = two_strands_at(d, r, std::f32::consts::FRAC_PI_4);
        let ao = traced(&gpu, &scene, &["params.ao_rays=1024", weight, dots]);
        1.0 - ao[10] as f64
    };
    let opaque = loss("params.ao_shadow_weight=10");
    let half = loss("params.ao_shadow_weight=0.5");
    let once = (1.0 - (-0.5f64).exp()) / (1.0 - (-10.0f64).exp());
    let cylinder = cylinder_share(d as f64, r as f64);
    eprintln!(
        "DOTS beside: loss {opaque:.4} opaque, {half:.4} half; ratio {:.4} (once {once:.4}); cylinder share {cylinder:.4}",
        half / opaque
    );
    assert!(
        (half / opaque - once).abs() < 0.005,
        "half-opaque loss {half:.4} over opaque {opaque:.4} = {:.4}: one crossing per ray gives {once:.4}",
        half / opaque
    );
    assert!(
        (opaque / cylinder - 1.0).abs() < 0.25,
        "DOTS hide {opaque:.4} of the sphere, the cylinder {cylinder:.4}"
    );
}

/// Share of uniform directions from the origin whose ray crosses the axis
/// of a strand along z at height 0.1 (radius 0.1: the ray always passes
/// within it) farther than `near` along the ray: the closest approach is
/// at t = 0.1 · sin φ / ρ (ρ = √(1 − z²) the direction's distance from the
/// z axis, φ its azimuth from x), so the share is that of sin φ > 10 ρ near
/// at uniform z — integrated over z here.
fn touching_share(near: f64) -> f64 {
    let steps = 200_000;
    let pi = std::f64::consts::PI;
    (0..steps)
        .map(|i| {
            let z = -1.0 + 2.0 * (i as f64 + 0.5) / steps as f64;
            let rho = (1.0 - z * z).sqrt();
            let k = 10.0 * rho * near;
            // P(sin φ > k) for φ uniform.
            if k >= 1.0 {
                0.0
            } else {
                (pi - 2.0 * k.asin()) / (2.0 * pi)
            }
        })
        .sum::<f64>()
        / steps as f64
}

/// A strand touching the vertex (across it, its axis 0.1 above the vertex,
/// radius 0.1; the vertex's own strand 0.2 wide): every ray into it passes
/// within its radius, but the vertex's own width is the cutoff — crossings
/// nearer than it are taken for its own strand — so only the rays whose
/// closest approach lies beyond 0.2 count: 0.040 of the sphere, where a
/// cutoff of 0 counts half the sphere's rays (0.5 of it).
#[test]
fn a_strand_within_the_vertex_width_is_cut_off() {
    let (_lock, gpu) = open_gpu();
    require_ray_queries(&gpu);
    let mut scene = small_scene();
    let mut strands = plait_hair::Strands::new();
    let along = |axis: Vec3, at: Vec3| -> Vec<Vec3> {
        (0..21).map(|k| at + (k as f32 - 10.0) * axis).collect()
    };
    strands.push_strand(
        &along(Vec3::X, Vec3::ZERO),
        |_| 0.2,
        |_| 1.0,
        Vec3::splat(0.5),
    );
    strands.push_strand(
        &along(Vec3::Z, Vec3::new(0.0, 0.1, 0.0)),
        |_| 0.2,
        |_| 1.0,
        Vec3::splat(0.5),
    );
    scene.strands = strands;
    scene.meshes.clear();
    let ao = traced(
        &gpu,
        &scene,
        &["params.ao_rays=1024", "params.ao_shadow_weight=10"],
    );
    let opaque = 1.0 - (-10.0f64).exp();
    let (share, none) = (touching_share(0.2), touching_share(0.0));
    let expected = 1.0 - opaque * share;
    let got = ao[10] as f64;
    eprintln!(
        "touching strand: visibility {got:.4}, beyond the cutoff {expected:.4} (share {share:.4}; with no cutoff {:.4})",
        1.0 - opaque * none
    );
    assert!(
        (got - expected).abs() < 0.01,
        "visibility {got:.4}, the crossings beyond the vertex's width give {expected:.4}"
    );
}

#[test]
fn a_lone_straight_strand_does_not_hide_its_own_sphere() {
    let (_lock, gpu) = open_gpu();
    require_ray_queries(&gpu);
    let mut scene = small_scene();
    let mut strands = plait_hair::Strands::new();
    let points: Vec<Vec3> = (0..21)
        .map(|k| Vec3::new(0.3 * k as f32, 0.1 * k as f32, 0.0))
        .collect();
    strands.push_strand(&points, |_| 0.2, |_| 1.0, Vec3::splat(0.5));
    scene.strands = strands;
    scene.meshes.clear();
    let ao = traced(
        &gpu,
        &scene,
        &["params.ao_rays=256", "params.ao_shadow_weight=10"],
    );
    let least = ao.iter().cloned().fold(f32::INFINITY, f32::min);
    assert!(
        least > 0.999,
        "a straight strand's own vertices should see the whole sphere: least {least}"
    );
}

/// Every other strand of the small scene.
fn half_scene() -> SceneData {
    let mut scene = small_scene();
    scene.strands = strands_subset(&scene.strands, |s| s % 2 == 0);
    scene
}

#[test]
fn on_the_small_scene_it_converges_and_darkens_what_deep_opacity_maps_darken() {
    let (_lock, gpu) = open_gpu();
    require_ray_queries(&gpu);
    let scene = half_scene();
    // Hair alone, as deep opacity maps see it ("only hair occludes"): the
    // head's and the ground's share is tests/ray_traced_meshes.rs'.
    let alone = "params.ao_mesh_distance=0";
    let reference = traced(&gpu, &scene, &["params.ao_rays=256", alone]);
    assert!(
        reference.iter().all(|v| (0.0..=1.0).contains(v)),
        "visibility outside [0, 1]"
    );
    let (inner, outer) = inner_outer(&scene, &reference);
    eprintln!("ray_traced (256 rays): inner {inner:.3}, outer {outer:.3}");
    // Measured on the whole small scene at 1024 rays: inner 0.940, outer
    // 0.967 (the density volume's 0.945 / 0.963 in tests/occlusion.rs).
    assert!(
        outer > inner + 0.01,
        "inner hair should be darker: inner {inner:.3}, outer {outer:.3}"
    );
    let errors: Vec<f64> = [4, 16, 64]
        .iter()
        .map(|n| {
            mean_abs_diff(
                &traced(&gpu, &scene, &[&format!("params.ao_rays={n}"), alone]),
                &reference,
            )
        })
        .collect();
    eprintln!("mean |Δ| against 256 rays at 4, 16, 64 rays: {errors:.4?}");
    assert!(
        errors[0] > errors[1] && errors[1] > errors[2],
        "the error should fall as the rays grow: {errors:?}"
    );
    let (maps, report) = vertex_ao(
        &gpu,
        &scene,
        "deep_opacity_directions",
        &["params.ao_directions=100".into()],
    );
    plait::overflow::check_frame(&report).expect("deep opacity directions");
    let r = correlation(&reference, &maps);
    eprintln!(
        "against deep opacity maps from 100 directions: mean |Δ| {:.4}, correlation {r:.3}",
        mean_abs_diff(&reference, &maps)
    );
    assert!(
        r > 0.7,
        "the two estimators should darken the same vertices: correlation {r:.3}"
    );
}

#[test]
fn a_groom_larger_than_its_vertex_buffer_is_reported_naming_the_param() {
    let (_lock, gpu) = open_gpu();
    require_ray_queries(&gpu);
    let mut scene = small_scene();
    scene.strands = strands_subset(&scene.strands, |s| s % 20 == 0);
    let vertices = scene.strands.points.len();
    let (_, report) = vertex_ao(
        &gpu,
        &scene,
        "ray_traced",
        &["params.ao_max_vertices=100".into()],
    );
    let dropped: Vec<String> = report.dropped().map(|o| o.to_string()).collect();
    eprintln!("{dropped:?}");
    assert!(
        dropped.iter().any(|m| m.contains("ao_max_vertices")
            && m.contains(&format!("dropped {}", vertices - 100))
            && m.contains(&format!("needs {vertices}"))),
        "the frame should report the vertices left out, naming the param: {dropped:?}"
    );
}
