//! `lighting/irradiance_maps`: the directly summed maps at the most specular
//! maps the pass type allows.

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_hair::environment::cube::EnvironmentCube;
use plait_hair::environment::irradiance::IrradianceMaps;
use plait_tests::{open_gpu, repo_root};

/// At `intervals` = 32, the pass type's largest (M + 1 = 33 specular maps at
/// θ′ = mπ/32, a thread's whole `MAX_MAPS`), the `irradiance_maps` pass
/// (`tests/fixtures/lighting_maps.toml`, environment 16, maps 16) equals
/// plait_hair's CPU sum within 4e-3 of the largest texel (rgba16float), as
/// tests/lighting.rs checks at the default 8. Kills, in
/// `shaders/passes/irradiance_maps.wgsl`, the cap `min(intervals,
/// MAX_MAPS - 1u)` → `MAX_MAPS - 2u` (41:58: 31 intervals, the last map
/// unwritten), which binds only at 32.
#[test]
fn irradiance_maps_at_the_most_intervals_match_the_cpu_sum() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("small scene");
    let pipeline = repo_root().join("tests/fixtures/lighting_maps.toml");
    let sets = ["params.intervals=32".to_string()];
    let prepared = prepare(&gpu, &pipeline, &sets, &scene, (64, 48)).expect("prepare");
    prepared.render().expect("render");
    let data = prepared.read_resource("direct_maps").expect("direct maps");
    let texels: Vec<Vec3> = (0..(data.width * data.height) as usize)
        .map(|i| Vec3::from_slice(&data.texel(i)[..3]))
        .collect();
    let cube = EnvironmentCube::new(&scene.environment, 16, 8, 0.0);
    let exponent = scene.scene.material.specular_exponent;
    let cpu = IrradianceMaps::direct(&cube, 16, 32, exponent);
    assert_eq!(texels.len(), cpu.texels.len(), "an atlas of 34 maps");
    let scale = cpu
        .texels
        .iter()
        .map(|v| v.abs().max_element())
        .fold(0.0f32, f32::max);
    let worst = texels
        .iter()
        .zip(&cpu.texels)
        .map(|(a, b)| (*a - *b).abs().max_element())
        .fold(0.0f32, f32::max);
    eprintln!(
        "intervals 32: largest texel {scale:e}, relative error {:e}",
        worst / scale
    );
    assert!(worst / scale < 4e-3, "relative error {}", worst / scale);
}

/// The ambient lighting's hair term as the tangent turns from along the eye
/// to away from it (`tests/fixtures/ambient_cases.wgsl`) is its closed form
/// L_a · (kd · base + ks · sin²(θ′)), θ′ the tangent-to-eye angle plus the
/// scene's shift, within 1e-4 of the largest term (measured: printed); the
/// angle comes from the dot product through acos only in the shader. The
/// gallery's strands rarely point within 26° of away from the eye. Kills,
/// in `techniques/lighting/ambient/lighting.wgsl`, the clamp of cos(T, E)
/// at −1.0 → −0.9 (15:66: it binds where cos < −0.9).
#[test]
fn ambient_matches_its_closed_form_as_the_tangent_turns_from_the_eye() {
    let read = plait_tests::fixture_texels("ambient_cases.toml", (64, 2), &["cases"]);
    let largest = read[0].iter().map(|t| t[1].abs()).fold(0.0f32, f32::max);
    let worst = read[0]
        .iter()
        .map(|t| (t[0] - t[1]).abs())
        .fold(0.0f32, f32::max);
    eprintln!("ambient: largest term {largest:e}, largest difference {worst:e}");
    assert!(largest > 1e-3, "the terms are empty ({largest})");
    assert!(
        worst <= 1e-4 * largest,
        "ambient differs from its closed form by {worst} (largest {largest})"
    );
}

/// The ambient term with the tangent along the eye and against it
/// (`tests/fixtures/ambient_rounding.wgsl`), where the dot of the two unit
/// vectors rounds past ±1 in f32 in some of 256 cases (counted, and
/// required): finite, and its closed form at θ = 0 and π within 1e-3 of
/// the largest term (acos of a clamped ±1). acos past ±1 is undefined
/// (NaN on lavapipe). Kills, in `techniques/lighting/ambient/lighting.wgsl`,
/// the clamp of cos(T, E) widened to 1.1 (15:71) and to −1.1 (15:66).
#[test]
fn ambient_is_finite_where_the_tangents_dot_with_the_eye_rounds_past_one() {
    let read = plait_tests::fixture_texels("ambient_rounding.toml", (256, 2), &["cases"]);
    let cases = &read[0];
    let (along, against) = cases.split_at(256);
    let past_one = along.iter().filter(|t| t[2] > 1.0).count();
    let past_minus_one = against.iter().filter(|t| t[2] < -1.0).count();
    let largest = cases.iter().map(|t| t[1].abs()).fold(0.0f32, f32::max);
    let not_finite = cases.iter().filter(|t| !t[0].is_finite()).count();
    let worst = cases
        .iter()
        .filter(|t| t[0].is_finite())
        .map(|t| (t[0] - t[1]).abs())
        .fold(0.0f32, f32::max);
    eprintln!(
        "ambient along/against the eye: dot > 1 in {past_one}, < −1 in {past_minus_one} of 256 each; \
         {not_finite} terms not finite; largest term {largest:e}, largest difference {worst:e}"
    );
    assert!(
        past_one > 0 && past_minus_one > 0,
        "no case rounds past ±1: the test tests nothing"
    );
    assert!(largest > 1e-3, "the terms are empty ({largest})");
    assert_eq!(not_finite, 0, "terms not finite");
    assert!(
        worst <= 1e-3 * largest,
        "ambient differs from its closed form by {worst} (largest {largest})"
    );
}

/// The brute-force environment term (`lighting/environment_reference`,
/// with the default shading, kajiya_kay) beside the same sum over the
/// cube's texels of Kajiya-Kay's response written out at the tangent-to-eye
/// angle as the case sets it (`tests/fixtures/env_reference_cases.wgsl`):
/// as the tangent turns from along the eye to away from it (row 0), and
/// along and against it where the dot of the two unit vectors rounds past
/// ±1 in f32 (rows 1, 2; counted, and required) — finite, within 1e-3 of
/// the largest term as it turns (measured 8.8e-5) and 2e-4 along and
/// against (measured 1.1e-4: the shading's acos of a dot one ulp inside 1
/// is 3.4e-4 rad, and the exact per-light cone moves with it). Since issue
/// 47 the technique sums the shading point's `shade_direct` per texel, so
/// its old angle clamps (19:55, 19:60) are gone; the test kills a sum that
/// drops a texel's radiance or solid angle, a loop bound cut by one, or a
/// response other than the fibre's.
#[test]
fn environment_reference_matches_its_sum_at_the_exact_eye_angle() {
    // The scene's default shift (−0.05) and its opposite: past −1 the
    // clamp to [0, π] after the shift hides a NaN only where π + shift ≥ π,
    // past +1 only where 0 + shift ≤ 0.
    for shift in [-0.05f32, 0.05] {
        env_reference_cases(shift);
    }
}

/// `environment_reference_matches_its_sum_at_the_exact_eye_angle` at one
/// specular shift.
fn env_reference_cases(shift: f32) {
    const WIDTH: usize = 256;
    let (_lock, gpu) = open_gpu();
    let mut scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    scene.scene.material.specular_shift = shift;
    let pipeline = repo_root().join("tests/fixtures/env_reference_cases.toml");
    let prepared =
        prepare(&gpu, &pipeline, &[], &scene, (WIDTH as u32, 3)).expect("the fixture prepares");
    prepared.render().expect("renders");
    let read = prepared.read_resource("cases").expect("cases");
    let cases: Vec<[f32; 4]> = read
        .bytes
        .chunks_exact(16)
        .map(|t| {
            std::array::from_fn(|c| {
                f32::from_le_bytes(t[4 * c..4 * c + 4].try_into().expect("4 bytes"))
            })
        })
        .collect();
    let along = &cases[WIDTH..2 * WIDTH];
    let against = &cases[2 * WIDTH..];
    let past_one = along.iter().filter(|t| t[2] > 1.0).count();
    let past_minus_one = against.iter().filter(|t| t[2] < -1.0).count();
    let largest = cases.iter().map(|t| t[1].abs()).fold(0.0f32, f32::max);
    let not_finite = cases.iter().filter(|t| !t[0].is_finite()).count();
    let worst_of = |rows: &[[f32; 4]]| {
        rows.iter()
            .filter(|t| t[0].is_finite())
            .map(|t| (t[0] - t[1]).abs())
            .fold(0.0f32, f32::max)
    };
    let (turning, rounding) = (worst_of(&cases[..WIDTH]), worst_of(&cases[WIDTH..]));
    eprintln!(
        "environment_reference, shift {shift}: dot > 1 in {past_one}, < −1 in {past_minus_one} of {WIDTH} each; \
         {not_finite} terms not finite; largest term {largest:e}, largest difference turning \
         {turning:e}, along/against {rounding:e}"
    );
    assert!(
        past_one > 0 && past_minus_one > 0,
        "no case rounds past ±1: the test tests nothing"
    );
    assert!(largest > 1e-3, "the terms are empty ({largest})");
    assert_eq!(not_finite, 0, "terms not finite");
    assert!(
        turning <= 1e-3 * largest,
        "environment_reference differs from its sum at the exact angle by {turning} as the \
         tangent turns (largest {largest})"
    );
    // Along and against the eye the angle is exact up to the shading's acos
    // of a dot one ulp from ±1: measured 1.1e-4 of the largest term.
    assert!(
        rounding <= 2e-4 * largest,
        "environment_reference differs from its sum at θ = 0 and π by {rounding} (largest {largest})"
    );
}
