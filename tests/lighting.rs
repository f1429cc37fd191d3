//! Environment lighting (Xing et al. 2012 §3, §5): the GPU kernels against
//! plait_hair::environment's CPU references, the maps' error against brute
//! force, and the techniques rendered.

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_hair::environment::cube::EnvironmentCube;
use plait_hair::environment::irradiance::IrradianceMaps;
use plait_hair::environment::sh;
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
    prepared.renderer.render().expect("render");
    let texels = |name: &str| -> Vec<[f32; 4]> {
        let data = prepared.renderer.read_resource(name).expect(name);
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

    // The directly summed maps (rgba16float: 11-bit mantissa).
    let direct = IrradianceMaps::direct(&cube, MAP_SIZE, INTERVALS, exponent);
    let e = relative_error(&rgb(&texels("direct_maps")), &direct.texels);
    assert!(e < 4e-3, "direct maps: relative error {e}");

    // The SH coefficients and the maps rebuilt from them.
    let bytes = prepared
        .renderer
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
