//! Transparency methods against the ground truth (issue 5;
//! Sintorn & Assarsson 2009 §2.2, §3.4, Fig. 2), on the GPU at a small size:
//!
//! - `linked_list.toml` (fragment lists sorted exactly) equals
//!   `depth_peeling.toml` within the agreement measured on the 8-bit sRGB
//!   output (mean absolute error, values that differ, p99 ≤ 1/255), which
//!   occupancy-order blending must not reach — differences come only from
//!   16-bit colours in the list nodes vs. the rgba16float layer target, and
//!   from fragments at exactly equal depth (peeling keeps one);
//! - occupancy-order blending (`occupancy.toml`) is closer to depth peeling
//!   than weighted average and no transparency (`opaque.toml`) — Fig. 2's
//!   ordering — for translucent strands (strand alpha 0.4; `tests/claims.rs`
//!   checks the scene's own 0.8), with strand coverage and without;
//! - depth peeling stops on its occlusion query before the layer cap, and
//!   reports the layers it used.

use std::path::{Path, PathBuf};

use plait_gpu::geometry::SceneGeometry;
use plait_gpu::{FrameReport, Gpu, Renderer};
use plait_graph::CompileOptions;
use plait_hair::scene::Scene;

const SIZE: (u32, u32) = (160, 120);

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

struct Render {
    pixels: Vec<u8>,
    report: FrameReport,
}

/// `material_alpha` multiplies every strand's alpha (the small scene's strands
/// have 0.8); `coverage`: strand coverage (the default) or the papers' strands.
fn render(gpu: &Gpu, pipeline: &str, material_alpha: f32, coverage: bool) -> Render {
    render_with(gpu, pipeline, &[], material_alpha, coverage)
}

fn render_with(
    gpu: &Gpu,
    pipeline: &str,
    sets: &[String],
    material_alpha: f32,
    coverage: bool,
) -> Render {
    let path = root().join("pipelines").join(pipeline);
    let mut scene = Scene::load(root().join("examples/scenes/small.toml")).expect("small scene");
    scene.material.alpha = material_alpha;
    let strands = scene.strands().expect("strands");
    let meshes = scene.opaque_meshes();
    let library = plait_passes::library();
    let loaded = plait_graph::load(&path, sets).unwrap_or_else(|e| panic!("{pipeline}: {e}"));
    let opts = CompileOptions {
        screen: SIZE,
        max_texture_dimension: gpu.capabilities.max_texture_dimension,
        ..Default::default()
    };
    let schedule = plait_passes::compile_in(&library, &loaded, &opts)
        .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
    let output = schedule.resources[schedule.outputs[0]].name.clone();
    let bounds = scene.opaque_bounds().union(&strands.bounds());
    // Without coverage, the papers' strands: one alpha per strand. With it,
    // alphas differ along and between strands; occupancy order measures its
    // ᾱ per pixel (the alpha_sum pass), so the ordering holds for both.
    let frame = plait_gpu::frame::FrameUniforms::new(&scene, &strands, bounds, SIZE, 0)
        .with_strand_coverage(coverage);
    let geometry = SceneGeometry::upload(&gpu.device, &strands, &meshes);
    let renderer = Renderer::new(
        gpu,
        schedule,
        &library,
        geometry,
        &frame,
        path.parent().unwrap(),
    )
    .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
    let report = renderer
        .render()
        .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
    // This renderer is built without the session, which would grow a
    // bounded buffer that drops data: hold the lists to losing nothing.
    let dropped: Vec<String> = report.dropped().map(|o| o.to_string()).collect();
    assert!(dropped.is_empty(), "{pipeline} dropped data: {dropped:?}");
    let image = renderer
        .read_resource(&output)
        .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
    Render {
        pixels: image.bytes,
        report,
    }
}

/// How closely the fragment lists sorted exactly match depth peeling, as
/// measured on lavapipe (8-bit sRGB, 160×120, strand alpha 0.4): the mean
/// absolute difference (of 255) and the number of channel values that
/// differ at all; and p99 ≤ 1. They differ only in 16-bit list colours and
/// fragments at exactly equal depth (peeling keeps one).
struct Agreement {
    mean: f64,
    differing: usize,
}

impl Agreement {
    /// Each limit reaches from the lists' measured value a third of the way
    /// to occupancy-order blending's, the nearest other method — with
    /// coverage the alphas are ~0.05 and order barely matters, so the two
    /// are close: lists mean 0.0047 with 232 values differing, occupancy
    /// 0.0072 with 375; without coverage lists 0.0093 / 402, occupancy
    /// 0.0340 / 1505 (`cargo test -p plait-passes --test transparency --
    /// --nocapture`). lavapipe renders bit for bit the same every run.
    fn exact_blend(coverage: bool) -> Agreement {
        if coverage {
            Agreement {
                mean: 0.0055,
                differing: 280,
            }
        } else {
            Agreement {
                mean: 0.0175,
                differing: 770,
            }
        }
    }

    fn holds(&self, d: &[u8]) -> bool {
        mean(d) <= self.mean && differing(d) <= self.differing && percentile(d, 0.99) <= 1
    }
}

fn differing(d: &[u8]) -> usize {
    d.iter().filter(|&&x| x > 0).count()
}

/// Per-channel absolute differences of the RGB channels, sorted.
fn differences(a: &Render, b: &Render) -> Vec<u8> {
    assert_eq!(a.pixels.len(), b.pixels.len());
    let mut d: Vec<u8> = a
        .pixels
        .chunks(4)
        .zip(b.pixels.chunks(4))
        .flat_map(|(p, q)| (0..3).map(move |c| p[c].abs_diff(q[c])))
        .collect();
    d.sort_unstable();
    d
}

fn mean(d: &[u8]) -> f64 {
    d.iter().map(|&x| x as f64).sum::<f64>() / d.len() as f64
}

fn percentile(d: &[u8], p: f64) -> u8 {
    d[((d.len() - 1) as f64 * p) as usize]
}

fn stat(report: &FrameReport, pass: &str, name: &str) -> f64 {
    let p = report
        .passes
        .iter()
        .find(|p| p.name == pass)
        .unwrap_or_else(|| panic!("no pass {pass}"));
    p.stats
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, v)| *v)
        .unwrap_or_else(|| panic!("{pass} reports no `{name}`"))
}

#[test]
fn transparency_methods_against_depth_peeling() {
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("GPU tests need an adapter: {e}"));
    // Translucent strands (0.8 × 0.5 = 0.4), the regime the paper renders hair
    // in (§2.2: "a very low alpha value"); `tests/claims.rs` covers the small
    // scene's own alpha 0.8.
    let alpha = 0.5;
    for coverage in [false, true] {
        methods_against_depth_peeling(&gpu, alpha, coverage);
    }
}

fn methods_against_depth_peeling(gpu: &Gpu, alpha: f32, coverage: bool) {
    let peeled = render(gpu, "depth_peeling.toml", alpha, coverage);
    let layers = stat(&peeled.report, "hair_peel", "layers");
    eprintln!("coverage {coverage}: depth peeling: {layers} layers");
    assert!(
        layers >= 2.0,
        "the small scene has overlapping strands, got {layers} layers"
    );
    assert_eq!(
        stat(&peeled.report, "hair_peel", "capped"),
        0.0,
        "the occlusion query should stop peeling before the cap"
    );

    let lists = differences(&render(gpu, "linked_list.toml", alpha, coverage), &peeled);
    let occupancy = differences(&render(gpu, "occupancy.toml", alpha, coverage), &peeled);
    // The lists match peeling: within the measured agreement, which
    // occupancy-order blending (the nearest other method) must not reach.
    let same = Agreement::exact_blend(coverage);
    for (name, d) in [("linked_list", &lists), ("occupancy", &occupancy)] {
        eprintln!(
            "coverage {coverage}: {name} vs depth_peeling: mean {:.4}, {} of {} channel values differ, p99 {}, max {} (of 255); as the lists: {}",
            mean(d),
            differing(d),
            d.len(),
            percentile(d, 0.99),
            d[d.len() - 1],
            same.holds(d)
        );
    }
    assert!(
        same.holds(&lists),
        "fragment lists must match depth peeling (coverage {coverage}): mean {:.4} (≤ {}), {} values differ (≤ {}), p99 {}",
        mean(&lists),
        same.mean,
        differing(&lists),
        same.differing,
        percentile(&lists, 0.99)
    );
    assert!(
        !same.holds(&occupancy),
        "occupancy-order blending passes as the fragment lists (coverage {coverage}): mean {:.4}, {} values differ",
        mean(&occupancy),
        differing(&occupancy)
    );

    let opaque = differences(&render(gpu, "opaque.toml", alpha, coverage), &peeled);
    let weighted = differences(
        &render(gpu, "weighted_average.toml", alpha, coverage),
        &peeled,
    );
    let a2c = differences(
        &render(gpu, "alpha_to_coverage.toml", alpha, coverage),
        &peeled,
    );
    eprintln!(
        "coverage {coverage}: mean abs error vs depth peeling (of 255): occupancy {:.3}, weighted_average {:.3}, alpha_to_coverage(4x) {:.3}, opaque {:.3}",
        mean(&occupancy),
        mean(&weighted),
        mean(&a2c),
        mean(&opaque)
    );
    // Mean absolute error against depth peeling (of 255), measured on
    // lavapipe: (occupancy, weighted average, alpha to coverage 4×, opaque).
    // Occupancy-order blending must beat weighted average and no
    // transparency by at least the floors (measured ratio / 1.25, rounded
    // down), and each method stay in a band around its measured error that
    // admits no other method's error (measured or in this run).
    let (measured, floors): ([f64; 4], [f64; 2]) = if coverage {
        // 0.060 / 0.0072 = 8.3×, 11.602 / 0.0072 = 1611×.
        ([0.0072, 0.060, 2.613, 11.602], [6.6, 1288.0])
    } else {
        // 0.542 / 0.0340 = 15.9×, 6.765 / 0.0340 = 199×.
        // Alpha to coverage 4.249 with the hardware's mask (lavapipe: one
        // sample of four for any alpha above 0), 2.774 with the shader's
        // dithered mask since issue 47.
        ([0.0340, 0.542, 2.774, 6.765], [12.7, 159.0])
    };
    let got = [mean(&occupancy), mean(&weighted), mean(&a2c), mean(&opaque)];
    let names = [
        "occupancy",
        "weighted_average",
        "alpha_to_coverage",
        "opaque",
    ];
    let mut failures = Vec::new();
    for (i, name) in names.iter().enumerate() {
        let (lo, hi) = band(&measured, i);
        if !(lo..=hi).contains(&got[i]) {
            failures.push(format!(
                "{name}: mean abs error {:.4} outside [{lo:.4}, {hi:.4}] (coverage {coverage})",
                got[i]
            ));
        }
        for j in (0..names.len()).filter(|&j| j != i) {
            for x in [measured[j], got[j]] {
                if (lo..=hi).contains(&x) {
                    failures.push(format!(
                        "{name}'s band [{lo:.4}, {hi:.4}] admits {} ({x:.4}, coverage {coverage})",
                        names[j]
                    ));
                }
            }
        }
    }
    for (i, (other, floor)) in ["weighted_average", "opaque"]
        .iter()
        .zip(floors)
        .enumerate()
    {
        let ratio = got[if i == 0 { 1 } else { 3 }] / got[0].max(1e-9);
        if ratio < floor {
            failures.push(format!(
                "occupancy-order blending must beat {other} by ≥ {floor}× (coverage {coverage}): {ratio:.1}×"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The band of `measured[i]`: a quarter of the value either way, but at
/// most a third of the way to the nearest other value (so no band reaches
/// another's), and at least ±0.005 — the 8-bit image's resolution of a
/// mean, which occupancy's 0.007 is below.
fn band(measured: &[f64], i: usize) -> (f64, f64) {
    let want = measured[i];
    let gap = measured
        .iter()
        .enumerate()
        .filter(|&(j, _)| j != i)
        .map(|(_, x)| (x - want).abs())
        .fold(f64::INFINITY, f64::min);
    let slack = (0.25 * want).min(gap / 3.0).max(0.005);
    (want - slack, want + slack)
}

#[test]
fn depth_peeling_layer_cap() {
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("GPU tests need an adapter: {e}"));
    let capped = render_with(
        &gpu,
        "depth_peeling.toml",
        &["params.peel_layers=2".to_string()],
        1.0,
        false,
    );
    assert_eq!(stat(&capped.report, "hair_peel", "layers"), 2.0);
    assert_eq!(stat(&capped.report, "hair_peel", "capped"), 1.0);
}
