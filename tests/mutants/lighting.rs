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
