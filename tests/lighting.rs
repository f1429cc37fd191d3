//! Environment lighting (Xing et al. 2012 §3, §5): the GPU kernels against
//! plait_hair::environment's CPU references, the maps' error against brute
//! force, and the techniques rendered.

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_hair::environment::cube::EnvironmentCube;
use plait_hair::environment::cube::texel_direction;
use plait_hair::environment::irradiance::{IrradianceMaps, brute_force, lookup_with, theta_of_map};
use plait_hair::environment::sh::{self, ShMaps};
use plait_tests::golden_images::{check_golden, check_no_hair};
use plait_tests::{open_gpu, repo_root};

const ENV_SIZE: u32 = 16;
const MAP_SIZE: u32 = 16;
const INTERVALS: u32 = 8;
const SH_BANDS: u32 = 8;

fn small_scene() -> SceneData {
    SceneData::load(Some(&repo_root().join("examples/scenes/small.toml"))).expect("small scene")
}

/// Largest |a − b| relative to the largest |b| of the set.
fn relative_error(gpu: &[Vec3], cpu: &[Vec3]) -> f32 {
    assert_eq!(gpu.len(), cpu.len());
    let scale = cpu
        .iter()
        .map(|v| v.abs().max_element())
        .fold(0.0f32, f32::max);
    let worst = gpu
        .iter()
        .zip(cpu)
        .map(|(a, b)| (*a - *b).abs().max_element())
        .fold(0.0f32, f32::max);
    worst / scale
}

#[test]
fn gpu_kernels_match_the_cpu_references() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    let pipeline = repo_root().join("tests/fixtures/lighting_maps.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (64, 48)).expect("prepare");
    prepared.render().expect("render");
    let texels = |name: &str| -> Vec<[f32; 4]> {
        let data = prepared.read_resource(name).expect(name);
        (0..(data.width * data.height) as usize)
            .map(|i| data.texel(i))
            .collect()
    };
    let exponent = scene.scene.material.specular_exponent;

    // The environment cube: mean radiance and solid angle of each texel.
    let cube = EnvironmentCube::new(&scene.environment, ENV_SIZE, 8, 0.0);
    let env = texels("environment");
    let rgb = |t: &[[f32; 4]]| {
        t.iter()
            .map(|t| Vec3::new(t[0], t[1], t[2]))
            .collect::<Vec<_>>()
    };
    let e = relative_error(&rgb(&env), &cube.radiance);
    assert!(e < 1e-3, "environment cube: relative error {e}");
    for (g, c) in env.iter().zip(&cube.solid_angle) {
        assert!(
            (g[3] - c).abs() < 1e-5 * c.max(1e-3) * 100.0,
            "solid angle {} vs {c}",
            g[3]
        );
    }

    // Turning the environment is a param of the cube pass.
    let turned = prepare(
        &gpu,
        &pipeline,
        &["passes.environment.params.rotate=75".to_string()],
        &scene,
        (64, 48),
    )
    .expect("prepare turned");
    turned.render().expect("render turned");
    let data = turned.read_resource("environment").expect("turned cube");
    let turned_gpu: Vec<Vec3> = (0..(data.width * data.height) as usize)
        .map(|i| Vec3::from_slice(&data.texel(i)[..3]))
        .collect();
    let turned_cpu = EnvironmentCube::new(&scene.environment, ENV_SIZE, 8, 75.0);
    let e = relative_error(&turned_gpu, &turned_cpu.radiance);
    assert!(e < 1e-3, "turned environment cube: relative error {e}");
    assert!(
        relative_error(&turned_gpu, &cube.radiance) > 0.05,
        "rotate changed nothing"
    );

    // The directly summed maps (rgba16float: 11-bit mantissa).
    let direct = IrradianceMaps::direct(&cube, MAP_SIZE, INTERVALS, exponent);
    let e = relative_error(&rgb(&texels("direct_maps")), &direct.texels);
    assert!(e < 4e-3, "direct maps: relative error {e}");

    // The SH coefficients and the maps rebuilt from them.
    let bytes = prepared
        .read_buffer("sh_coefficients")
        .expect("coefficients");
    let floats: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let gpu_w: Vec<Vec3> = floats
        .chunks_exact(4)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect();
    let cpu_w = sh::project(&cube, SH_BANDS);
    let e = relative_error(&gpu_w, &cpu_w);
    assert!(e < 1e-3, "SH coefficients: relative error {e}");
    let from_sh = sh::maps(&cube, MAP_SIZE, INTERVALS, exponent, 3, SH_BANDS);
    let e = relative_error(&rgb(&texels("sh_maps")), &from_sh.texels);
    assert!(e < 5e-3, "SH maps: relative error {e}");
}

/// The environment scene cut to a third of its strands: a frame of the
/// brute-force reference takes about a second at this size.
const IMAGE_SIZE: (u32, u32) = (128, 96);

fn env_scene() -> SceneData {
    let path = repo_root().join("examples/scenes/env.toml");
    let mut data = SceneData::load(Some(&path)).expect("env scene");
    data.strands = plait_tests::strands_subset(&data.strands, |s| s % 3 == 0);
    data
}

fn render_lighting(gpu: &plait_gpu::Gpu, scene: &SceneData, lighting: &str) -> image::RgbaImage {
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    // Strand coverage off: at this size it makes the 0.01-thick strands
    // nearly transparent, and the test is about the light on the hair.
    let sets = [
        format!("techniques.lighting={lighting}"),
        "params.strand_coverage=false".to_string(),
    ];
    let prepared = prepare(gpu, &pipeline, &sets, scene, IMAGE_SIZE)
        .unwrap_or_else(|e| panic!("{lighting}: {e}"));
    prepared
        .render_unchecked()
        .unwrap_or_else(|e| panic!("{lighting}: {e}"));
    prepared
        .image()
        .unwrap_or_else(|e| panic!("{lighting}: {e}"))
}

// Image RMSE (8-bit sRGB, 0..1) against the brute-force reference on
// env.toml at 128×96 (a third of its strands, strand coverage off),
// measured on lavapipe (Mesa 25.0.7):
// irradiance maps 0.0055, SH maps 0.0059, the constant ambient light 0.0496
// (most pixels are background, equal in all). Since issue 47 the reference
// sums the shading point's own Kajiya-Kay (the key light's cone,
// cos^p(θ − θ′), and its exact cos θi per light) and the maps are read at
// π − θ′ to match it; against the old reference (the paper's mirror cone)
// they were 0.0063, 0.0065 and 0.0368. Before the environment's
// specular was put in the units of the key light's energy-normalized cone
// (plait::kajiya_kay::kk_environment_specular_units, π/(2∫cos^p)·sin θ′ ≈
// 4.9·sin θ′ at p = 60) they were 0.0020, 0.0020 and 0.0280: the maps'
// interpolation error over θ′ grew with the specular it interpolates. The
// bounds leave 1.6× headroom; ambient must stay far outside them, so the
// test fails if the maps stop following the environment.
const MAPS_RMSE_BOUND: f64 = 0.010;
const SH_RMSE_BOUND: f64 = 0.010;

#[test]
fn maps_render_close_to_brute_force_and_match_their_goldens() {
    let (_lock, gpu) = open_gpu();
    let scene = env_scene();
    let reference = render_lighting(&gpu, &scene, "environment_reference");
    let maps = render_lighting(&gpu, &scene, "irradiance_maps");
    let from_sh = render_lighting(&gpu, &scene, "sh_irradiance_maps");
    let ambient = render_lighting(&gpu, &scene, "ambient");
    let rmse = |img: &image::RgbaImage| plait_compare::rmse(img, &reference).expect("same size");
    let (e_maps, e_sh, e_ambient) = (rmse(&maps), rmse(&from_sh), rmse(&ambient));
    eprintln!("RMSE against brute force: maps {e_maps:.4}, SH {e_sh:.4}, ambient {e_ambient:.4}");
    assert!(e_maps < MAPS_RMSE_BOUND, "irradiance maps: RMSE {e_maps}");
    assert!(e_sh < SH_RMSE_BOUND, "SH maps: RMSE {e_sh}");
    assert!(
        e_ambient > 3.0 * SH_RMSE_BOUND,
        "ambient light is as close as the maps: {e_ambient}"
    );
    // The frame without hair masks the goldens' comparison (tests/golden_images.rs).
    let mut bare = env_scene();
    bare.strands = plait_tests::hair_taken_away(&bare.strands);
    bare.guides = plait_hair::guides::Guides::default();
    let mask = render_lighting(&gpu, &bare, "environment_reference");
    check_no_hair("env_no_hair", &mask).unwrap_or_else(|e| panic!("{e}"));
    let mut failures = Vec::new();
    for (stem, image) in [
        ("env_environment_reference", &reference),
        ("env_irradiance_maps", &maps),
        ("env_sh_irradiance_maps", &from_sh),
    ] {
        if let Err(e) = check_golden(stem, image, &mask) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Deterministic pseudo-random unit vectors and angles (no RNG crate).
fn samples(count: usize) -> Vec<(Vec3, f32)> {
    let mut state = 0x2545_f491_u64;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 33) as f32) / (1u64 << 31) as f32
    };
    (0..count)
        .map(|_| {
            let (z, phi) = (2.0 * next() - 1.0, std::f32::consts::TAU * next());
            let r = (1.0 - z * z).max(0.0).sqrt();
            (
                Vec3::new(r * phi.cos(), z, r * phi.sin()),
                std::f32::consts::PI * next(),
            )
        })
        .collect()
}

/// Largest diffuse error, largest and mean specular error of lookups at
/// `points` against `truth`, relative to the largest true value of each term.
fn lookup_errors(
    points: &[(Vec3, f32)],
    truth: &[(Vec3, Vec3)],
    lookup: impl Fn(Vec3, f32) -> (Vec3, Vec3),
) -> (f32, f32, f32) {
    let scale_d = truth
        .iter()
        .map(|t| t.0.max_element())
        .fold(0.0f32, f32::max);
    let scale_s = truth
        .iter()
        .map(|t| t.1.max_element())
        .fold(0.0f32, f32::max);
    let (mut max_d, mut max_s, mut sum_s) = (0.0f32, 0.0f32, 0.0f32);
    for (&(t, theta), &(d, s)) in points.iter().zip(truth) {
        let (ld, ls) = lookup(t, theta);
        max_d = max_d.max((ld - d).abs().max_element() / scale_d);
        let es = (ls - s).abs().max_element() / scale_s;
        max_s = max_s.max(es);
        sum_s += es;
    }
    (max_d, max_s, sum_s / points.len() as f32)
}

// Map lookups against the brute-force sums at 200 random (tangent, θ′) on
// studio.hdr (p = 60), errors relative to the largest true value of each
// term, measured for M = 4, 8, 16 (16×16×6 maps, 8 SH bands):
//   direct: diffuse max 0.0058; specular max 0.71 / 0.31 / 0.10, mean 0.130 / 0.049 / 0.016
//   SH:     diffuse max 0.082;  specular max 0.65 / 0.29 / 0.22, mean 0.135 / 0.061 / 0.041
// The specular error is mostly the paper's linear interpolation between maps
// 180°/M apart, wider than the p = 60 lobe at M = 8 (Xing et al. 2012
// Fig. 3d/3e: nine maps catch the ring five miss): it falls about 3× per
// doubling of M, down to SH's floor of 8 bands (√p) at M = 16. SH's diffuse
// error is the 9 coefficients' smoothing of the studio's softbox. The
// bounds leave 1.5× headroom.
#[test]
fn map_lookups_are_within_measured_bounds_of_brute_force() {
    let scene = env_scene();
    let exponent = scene.scene.material.specular_exponent;
    let cube = EnvironmentCube::new(&scene.environment, ENV_SIZE, 8, 0.0);
    let points = samples(200);
    let truth: Vec<(Vec3, Vec3)> = points
        .iter()
        .map(|&(t, theta)| brute_force(&cube, t, theta, exponent))
        .collect();
    let mut mean_specular = Vec::new();
    // (M, direct specular (max, mean) bounds, SH specular (max, mean) bounds)
    let bounds = [
        (4, (1.07, 0.2), (0.98, 0.2)),
        (8, (0.47, 0.074), (0.44, 0.092)),
        (16, (0.15, 0.024), (0.33, 0.062)),
    ];
    for (intervals, direct_bound, sh_bound) in bounds {
        let theta_of = |map: u32| theta_of_map(map, intervals);
        let direct = lookup_errors(&points, &truth, |t, theta| {
            lookup_with(MAP_SIZE, intervals, t, theta, |map, face, x, y| {
                let d = texel_direction(face as usize, MAP_SIZE, x, y);
                let (diffuse, specular) = brute_force(&cube, d, theta_of(map), exponent);
                if map == 0 { diffuse } else { specular }
            })
        });
        let sh = ShMaps::new(&cube, intervals, exponent, 3, SH_BANDS);
        let from_sh = lookup_errors(&points, &truth, |t, theta| {
            lookup_with(MAP_SIZE, intervals, t, theta, |map, face, x, y| {
                sh.value(map, texel_direction(face as usize, MAP_SIZE, x, y))
            })
        });
        eprintln!(
            "M = {intervals}: direct {direct:.4?}, SH {from_sh:.4?} (diffuse max, specular max, specular mean)"
        );
        assert!(
            direct.0 < 0.01,
            "M = {intervals}: direct diffuse {}",
            direct.0
        );
        assert!(
            from_sh.0 < 0.12,
            "M = {intervals}: SH diffuse {}",
            from_sh.0
        );
        for (name, e, (max, mean)) in [("direct", direct, direct_bound), ("SH", from_sh, sh_bound)]
        {
            assert!(
                e.1 < max && e.2 < mean,
                "M = {intervals}: {name} specular {e:?}"
            );
        }
        mean_specular.push(direct.2);
    }
    assert!(
        mean_specular.windows(2).all(|w| w[1] < 0.5 * w[0]),
        "the specular error should fall as M grows: {mean_specular:?}"
    );
}

/// The environment sums run past lavapipe's loop budget (65,535 iterations
/// per group of 8 invocations) for large params, and the frame then fails
/// instead of showing cut maps: sh_project at 14 bands (its texel laps with
/// sh_basis's loops: ~67,600 passes at environment_size 16), the direct maps
/// at 32 intervals and environment_size 18 (~68,100). The defaults count
/// nothing. A driver without the limit counts nothing either.
#[test]
fn environment_sums_past_the_loop_budget_fail_the_frame() {
    let (_lock, gpu) = open_gpu();
    let scene = small_scene();
    let pipeline = repo_root().join("tests/fixtures/lighting_maps.toml");
    let incomplete = |sets: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let prepared = prepare(&gpu, &pipeline, &sets, &scene, (64, 48)).expect("prepare");
        let report = prepared.render_unchecked().expect("render");
        let count = |counter: &str| {
            report
                .overflow
                .iter()
                .find(|o| o.counter == counter)
                .unwrap_or_else(|| panic!("{counter} is read back: {:?}", report.overflow))
                .incomplete
        };
        let check = plait::overflow::check_frame(&report).map_err(|e| e.to_string());
        (count("sh_project_status"), count("direct_status"), check)
    };
    let (sh, direct, check) = incomplete(&[]);
    assert_eq!((sh, direct), (0, 0), "the defaults fit the budget");
    check.expect("a complete frame passes");
    // Measured (Mesa 22.3's lavapipe cuts, Mesa 25's does not).
    let cuts = gpu
        .loop_budget()
        .expect("the loop-budget probe runs")
        .is_some();

    let (sh, direct, check) = incomplete(&["params.sh_bands=14"]);
    eprintln!("14 bands: {sh} sh_project threads cut, {direct} direct");
    assert_eq!(direct, 0);
    if cuts {
        assert!(sh > 0, "14 bands are past the budget on lavapipe");
        let e = check.expect_err("a cut frame fails");
        assert!(e.contains("pass `sh_project` could not finish"), "{e}");
    } else {
        assert_eq!(sh, 0, "no loop budget: 14 bands finish");
        check.expect("a complete frame passes");
    }
    let (sh, direct, check) = incomplete(&[
        "params.environment_size=18",
        "params.intervals=32",
        "params.map_size=4",
    ]);
    eprintln!("size 18, 32 intervals: {direct} irradiance_maps threads cut, {sh} sh_project");
    if cuts {
        assert!(direct > 0, "past the budget on lavapipe");
        let e = check.expect_err("a cut frame fails");
        assert!(e.contains("pass `direct` could not finish"), "{e}");
    } else {
        assert_eq!((sh, direct), (0, 0), "no loop budget: the maps finish");
        check.expect("a complete frame passes");
    }
}
