//! Every self-shadowing method against a scene whose visibility is known
//! analytically: four layers of parallel straight strands, one strand on every
//! light texel row of a square region, between a straight-down directional
//! light and a ground plane. Every texel of the region holds exactly one
//! fragment per layer, so a point between layers k-1 and k has exactly k hair
//! fragments in front of it (Sintorn & Assarsson 2009 §3, Fig. 5) and
//! visibility exp(-w·k), w = shadow_weight.
//!
//! Each variant file in `pipelines/` is extended by a probe pipeline (light
//! maps at 64², a compute pass `tests/fixtures/visibility_probe.wgsl` that
//! calls the variant's own `hair_visibility` WGSL at light texel centres ×
//! depths between the layers), rendered on the adapter, and read back.
//! Asserted: `exact_shadow` matches the analytic count (and its lists did not
//! overflow), and its error is ≤ every approximation's.

use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3};
use plait_gpu::frame::FrameUniforms;
use plait_gpu::geometry::SceneGeometry;
use plait_gpu::{Gpu, Renderer};
use plait_graph::{CompileOptions, Value};
use plait_hair::Strands;
use plait_hair::scene::Scene;

const MAP: u32 = 64;
/// Strands run along texel rows ROWS, from column STRAND_COLS.0 to .1 (centres).
const ROWS: (u32, u32) = (8, 56);
const STRAND_COLS: (u32, u32) = (6, 58);
/// Probes: texel rows/columns PROBE.0..PROBE.1 (inside, away from strand ends).
const PROBE: (u32, u32) = (10, 54);
/// Layer heights (the light looks down), on multiples of 0.05 in (0, 1):
/// evenly spread, and clumped (4 + 1 + 3 layers) as hair is.
const UNIFORM: &[f32] = &[0.8, 0.6, 0.4, 0.2];
const CLUMPED: &[f32] = &[0.9, 0.85, 0.8, 0.75, 0.5, 0.3, 0.25, 0.2];
/// Probe heights 0.975, 0.925, …, 0.025: 0.025 from the nearest layer,
/// above, between and below the layers (the ground is at -1).
const PROBE_DEPTHS: u32 = 20;
fn probe_height(h: u32) -> f32 {
    0.975 - 0.05 * h as f32
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn scene() -> Scene {
    let text = r#"
ambient = 0.2
[hair.procedural]
strands = 1
[ground]
height = -1.0
half_size = 3.0
[camera]
eye = [0.0, 2.0, 6.0]
target = [0.0, 0.0, 0.0]
fov_y_degrees = 35.0
[light]
type = "directional"
direction = [0.0, -1.0, 0.0]
"#;
    Scene::from_toml_str(text, Path::new("analytic_layers.toml")).expect("test scene parses")
}

fn frame_for(scene: &Scene, strands: &Strands) -> FrameUniforms {
    let bounds = scene.opaque_bounds().union(&strands.bounds());
    // Whole strands: the layers are counted in strands, not in shares of a
    // light texel (shares have their own test, tests/shadow_coverage.rs).
    FrameUniforms::new(scene, strands, bounds, (MAP, MAP), 0).with_strand_coverage(false)
}

fn push(strands: &mut Strands, a: Vec3, b: Vec3) {
    strands.push_strand(&[a, b], |_| 0.01, |_| 1.0, Vec3::splat(0.5));
}

/// Two tiny strands at opposite corners fix the hair bounds, hence the light
/// frustum; the layer strands are then laid on texel-row centres inside it.
fn build(layers: &[f32]) -> (Scene, Strands, FrameUniforms, Mat4) {
    let scene = scene();
    let mut strands = Strands::new();
    push(
        &mut strands,
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(-0.98, 1.0, -1.0),
    );
    push(
        &mut strands,
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(0.98, 0.0, 1.0),
    );
    let frame = frame_for(&scene, &strands);
    let m = Mat4::from_cols_array_2d(&frame.light_view_proj);
    let inv = m.inverse();
    let ndc_z = |y: f32| m.project_point3(Vec3::new(0.0, y, 0.0)).z;
    let at = |col: u32, row: u32, z: f32| {
        let u = (col as f32 + 0.5) / MAP as f32;
        let v = (row as f32 + 0.5) / MAP as f32;
        inv.project_point3(Vec3::new(2.0 * u - 1.0, 1.0 - 2.0 * v, z))
    };
    for &y in layers {
        for row in ROWS.0..ROWS.1 {
            push(
                &mut strands,
                at(STRAND_COLS.0, row, ndc_z(y)),
                at(STRAND_COLS.1, row, ndc_z(y)),
            );
        }
    }
    let check = frame_for(&scene, &strands);
    let m2 = Mat4::from_cols_array_2d(&check.light_view_proj);
    assert!(
        m.abs_diff_eq(m2, 1e-5),
        "layer strands moved the light frustum"
    );
    (scene, strands, check, m)
}

fn literal(v: &Value) -> String {
    match v {
        Value::Float(f) => format!("{f:?}"),
        Value::Int(i) => i.to_string(),
        Value::Bool(b) => b.to_string(),
        Value::Str(s) => format!("{s:?}"),
        other => panic!("unexpected param value {other:?}"),
    }
}

/// The params each provider's `VisibilityParams` has.
fn provider_params(visibility: &str) -> &'static [&'static str] {
    match visibility {
        "occupancy" | "opacity_shadow_maps" | "density_clustering" => &["shadow_weight"],
        "deep_opacity" => &["shadow_weight", "layer_size"],
        "exact" => &["shadow_weight", "shadow_opaque"],
        "modified_shadow_map" => &["shadow_weight", "density"],
        _ => &[],
    }
}

struct Probed {
    visibility: Vec<f32>,
    overflow: Option<Vec<u32>>,
}

fn probe(
    gpu: &Gpu,
    variant: &str,
    scene: &Scene,
    strands: &Strands,
    frame: &FrameUniforms,
    depth0: f32,
    depth_step: f32,
) -> Probed {
    let opts = CompileOptions {
        screen: (MAP, MAP),
        max_texture_dimension: gpu.capabilities.max_texture_dimension,
        ..Default::default()
    };
    let library = plait_passes::read_library(&[]);
    let sets = [format!("params.light_size={MAP}")];
    let variant_path = repo().join("pipelines").join(format!("{variant}.toml"));
    // The variant's own hair pass says which provider, maps and params it uses.
    let base = plait_graph::load(&variant_path, &sets).unwrap_or_else(|e| panic!("{variant}: {e}"));
    let base = plait_graph::compile(&base, &library.registry(), &opts)
        .unwrap_or_else(|e| panic!("{variant}: {e}"));
    let hair = base
        .passes
        .iter()
        .find(|p| p.name == "hair")
        .expect("variant has a hair pass");
    let visibility = hair
        .params
        .get("self_shadow")
        .and_then(|v| v.as_str())
        .unwrap_or("none")
        .to_string();
    let reads: Vec<String> = hair
        .reads
        .iter()
        .filter(|b| b.slot.starts_with("vis_"))
        .map(|b| format!("{} = {:?}", b.slot, b.resource_name))
        .collect();
    let mut params = vec![format!("self_shadow = {visibility:?}")];
    for name in provider_params(&visibility) {
        params.push(format!("{name} = {}", literal(&hair.params[*name])));
    }
    let probes = (PROBE.1 - PROBE.0) * (PROBE.1 - PROBE.0) * PROBE_DEPTHS;
    params.extend([
        format!("probe_col0 = {:?}", PROBE.0 as f32),
        format!("probe_cols = {:?}", (PROBE.1 - PROBE.0) as f32),
        format!("probe_row0 = {:?}", PROBE.0 as f32),
        format!("probe_depths = {:?}", PROBE_DEPTHS as f32),
        format!("probe_depth0 = {depth0:?}"),
        format!("probe_depth_step = {depth_step:?}"),
        format!("probe_map_size = {:?}", MAP as f32),
    ]);
    let shader = repo().join("crates/plait-passes/tests/fixtures/visibility_probe.wgsl");
    let text = format!(
        r#"[pipeline]
name = "probe_{variant}"
extends = "{variant}.toml"
outputs = ["probe_out"]

[resources.probe_out]
kind = "buffer"
size = "{bytes}"

[passes.probe]
type = "compute"
shader = {shader:?}
reads = {{ {reads} }}
writes = {{ probe_out = "probe_out" }}
params = {{ {params} }}
"#,
        bytes = probes * 4,
        shader = shader.display().to_string(),
        reads = reads.join(", "),
        params = params.join(", "),
    );
    let path = repo()
        .join("pipelines")
        .join(format!("probe_{variant}.toml"));
    let pipeline = plait_graph::load_str(&path, &text, &sets)
        .unwrap_or_else(|e| panic!("probe_{variant}: {e}\n{text}"));
    let schedule = plait_passes::compile_in(&library, &pipeline, &opts)
        .unwrap_or_else(|e| panic!("probe_{variant}: {e}\n{text}"));
    let has_overflow = schedule.resource("light_overflow").is_some();
    let geometry = SceneGeometry::upload(&gpu.device, strands, &scene.opaque_meshes());
    let renderer = Renderer::new(
        gpu,
        schedule,
        &library,
        geometry,
        frame,
        &repo().join("pipelines"),
    )
    .unwrap_or_else(|e| panic!("probe_{variant}: {e}"));
    renderer
        .render()
        .unwrap_or_else(|e| panic!("probe_{variant}: {e}"));
    let words = |name: &str| -> Vec<u8> {
        renderer
            .read_buffer(name)
            .unwrap_or_else(|e| panic!("{variant} {name}: {e}"))
    };
    let visibility = words("probe_out")
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let overflow = has_overflow.then(|| {
        words("light_overflow")
            .chunks_exact(4)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect()
    });
    Probed {
        visibility,
        overflow,
    }
}

/// Mean and max |V - exp(-w·n)| and the max error in the count n, per variant.
fn run(layers: &[f32], name: &str) -> Vec<(&'static str, f64, f32, f32)> {
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("GPU tests need an adapter: {e}"));
    let (scene, strands, frame, m) = build(layers);
    let ndc_z = |y: f32| m.project_point3(Vec3::new(0.0, y, 0.0)).z;
    let depth0 = ndc_z(probe_height(0));
    let depth_step = ndc_z(probe_height(1)) - depth0;
    // Same w as the pipelines (occupancy.toml's shadow_weight): every method
    // estimates exp(-w·n).
    let w = 0.15f32;
    let variants = [
        "exact_shadow",
        "occupancy",
        "occupancy_no_slab",
        "deep_opacity",
        "opacity_shadow_maps",
        "density_clustering",
        "modified_shadow_map",
        "no_self_shadow",
    ];
    let mut errors = Vec::new();
    eprintln!("-- {name}: layers at heights {layers:?}");
    for variant in variants {
        let got = probe(&gpu, variant, &scene, &strands, &frame, depth0, depth_step);
        let (mut sum, mut max, mut count_err) = (0.0f64, 0.0f32, 0.0f32);
        for (i, v) in got.visibility.iter().enumerate() {
            let y = probe_height(i as u32 % PROBE_DEPTHS);
            let n = layers.iter().filter(|&&l| l > y).count() as f32;
            let want = (-w * n).exp();
            let e = (v - want).abs();
            sum += e as f64;
            max = max.max(e);
            count_err = count_err.max((-(v.max(1e-30)).ln() / w - n).abs());
        }
        let mean = sum / got.visibility.len() as f64;
        eprintln!(
            "{variant:22} mean |V - exp(-w n)| = {mean:.5}  max = {max:.5}  max count error = {count_err:.3}"
        );
        if let Some(o) = &got.overflow {
            assert_eq!(
                o[0], 0,
                "{variant}: {} fragments dropped from the light lists",
                o[0]
            );
        }
        errors.push((variant, mean, max, count_err));
    }
    let (_, exact_mean, exact_max, exact_count) = errors[0];
    assert!(
        exact_count < 1e-3,
        "{name}: exact_shadow must count exactly: max count error {exact_count}"
    );
    assert!(
        exact_max < 1e-4,
        "{name}: exact_shadow visibility off by {exact_max}"
    );
    for &(variant, mean, max, _) in &errors[1..] {
        assert!(
            // 1e-6: float rounding of exp() between equally exact methods.
            exact_mean <= mean + 1e-6 && exact_max <= max + 1e-6,
            "{name}: {variant} (mean {mean}, max {max}) beats exact_shadow (mean {exact_mean}, max {exact_max})"
        );
    }
    errors
}

#[test]
fn exact_shadow_is_the_ground_truth_on_evenly_spread_layers() {
    let errors = run(UNIFORM, "uniform");
    // Layers on slice boundaries: the sliced methods are exact here too; the
    // method without self-shadowing is not.
    assert!(errors.iter().find(|e| e.0 == "no_self_shadow").unwrap().2 > 0.3);
}

#[test]
fn exact_shadow_is_the_ground_truth_on_clumped_layers() {
    let errors = run(CLUMPED, "clumped");
    // Clumps defeat uniform slicing: some approximation must err visibly, or
    // the scene tests nothing.
    assert!(
        errors
            .iter()
            .filter(|e| e.0 != "no_self_shadow" && e.0 != "exact_shadow")
            .any(|e| e.2 > 0.02)
    );
}
