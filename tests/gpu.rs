//! GPU tier: real renders on whatever adapter exists (Mesa's lavapipe in CI).
//!
//! No adapter is a FAILURE whose message says how to install one, never a
//! skip. GPU tests in this binary take a lock so they run one at a time:
//! lavapipe already uses every core for one device, and each test opens its
//! own device so uncaptured GPU errors cannot be blamed on another test.

use std::path::{Path, PathBuf};
use std::sync::MutexGuard;

use image::RgbaImage;
use plait::session::{SceneData, compile_checked, prepare};
use plait_gpu::Gpu;
use plait_graph::CompileOptions;
use plait_tests::{open_gpu, pipeline_files, rel, repo_root};

/// A small size and scene: seconds on a software rasterizer. (The golden
/// images are tests/goldens.rs.)
const SIZE: (u32, u32) = (256, 192);
const SCENE: &str = "examples/scenes/small.toml";

fn gpu() -> (MutexGuard<'static, ()>, Gpu) {
    open_gpu()
}

fn scene() -> SceneData {
    load_scene(SCENE)
}

fn load_scene(relative: &str) -> SceneData {
    let path = repo_root().join(relative);
    SceneData::load(Some(&path)).unwrap_or_else(|e| panic!("loading {relative}: {e}"))
}

fn render(gpu: &Gpu, pipeline: &Path, scene: &SceneData) -> (RgbaImage, plait_gpu::FrameReport) {
    render_set(gpu, pipeline, &[], scene)
}

fn render_set(
    gpu: &Gpu,
    pipeline: &Path,
    sets: &[String],
    scene: &SceneData,
) -> (RgbaImage, plait_gpu::FrameReport) {
    let name = rel(pipeline);
    let prepared = prepare(gpu, pipeline, sets, scene, SIZE)
        .unwrap_or_else(|e| panic!("preparing {name}: {e}"));
    let report = prepared
        .render_unchecked()
        .unwrap_or_else(|e| panic!("rendering {name}: {e}"));
    let image = prepared
        .image()
        .unwrap_or_else(|e| panic!("reading back {name}: {e}"));
    (image, report)
}

/// A gallery variant is one key: its file renders the same image as the
/// default pipeline with that key set on the command line (the overrides and
/// `extends` go through one merge, techniques through one loader).
#[test]
fn set_reaches_a_variant_with_the_same_image() {
    let (_lock, gpu) = gpu();
    let scene = scene();
    let image = |pipeline: &str, sets: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let path = repo_root().join(pipeline);
        let prepared = prepare(&gpu, &path, &sets, &scene, SIZE)
            .unwrap_or_else(|e| panic!("{pipeline} {sets:?}: {e}"));
        prepared
            .render_unchecked()
            .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
        prepared
            .image()
            .unwrap_or_else(|e| panic!("{pipeline}: {e}"))
    };
    for (file, sets) in [
        (
            "occupancy_no_slab",
            &["techniques.self_shadow=occupancy_no_slab"][..],
        ),
        ("no_self_shadow", &["techniques.self_shadow=none"][..]),
        (
            "weighted_average",
            &["techniques.transparency=weighted_average"][..],
        ),
        (
            "reference",
            &[
                "techniques.self_shadow=exact",
                "techniques.transparency=depth_peeling",
            ][..],
        ),
    ] {
        let by_file = image(&format!("pipelines/{file}.toml"), &[]);
        let by_set = image("pipelines/occupancy.toml", sets);
        assert!(
            by_file == by_set,
            "occupancy.toml --set {sets:?} differs from {file}.toml"
        );
    }
}

/// A scene's background image shows where nothing covers it, stretched over
/// the frame: its left half orange, its right half blue.
#[test]
fn background_image_fills_the_uncovered_pixels() {
    let (_lock, gpu) = gpu();
    let scene = load_scene("tests/fixtures/background.toml");
    // `clip` shows radiance in [0, 1] as it is, so the image's own colours
    // are the screen's (a tone mapper would rightly change them).
    let clip = ["techniques.tone_mapping=clip".to_owned()];
    let forward = repo_root().join("pipelines/forward.toml");
    let (image, _) = render_set(&gpu, &forward, &clip, &scene);
    let near = |p: &image::Rgba<u8>, want: [u8; 3]| (0..3).all(|c| p[c].abs_diff(want[c]) <= 6);
    let (w, _) = image.dimensions();
    assert!(
        near(image.get_pixel(2, 2), [230, 120, 30]),
        "top-left pixel {:?} is not the image's left half",
        image.get_pixel(2, 2)
    );
    assert!(
        near(image.get_pixel(w - 3, 2), [30, 90, 200]),
        "top-right pixel {:?} is not the image's right half",
        image.get_pixel(w - 3, 2)
    );
}

fn sharing_fixture() -> PathBuf {
    repo_root().join("tests/fixtures/sharing.toml")
}

#[test]
fn same_descriptor_disjoint_lifetimes_share_memory_without_corruption() {
    let path = sharing_fixture();
    let opts = CompileOptions {
        screen: SIZE,
        ..Default::default()
    };
    let schedule = compile_checked(&path, &[], &opts)
        .unwrap_or_else(|e| panic!("compiling {}: {e}", rel(&path)));
    let id = |n: &str| {
        schedule
            .resource(n)
            .unwrap_or_else(|| panic!("no resource `{n}` in the schedule"))
    };
    let table = plait_graph::schedule_text(&schedule);
    assert_eq!(
        schedule.shares_memory_with(id("a")),
        vec!["c"],
        "`a` and `c` must share memory:\n{table}"
    );
    assert_eq!(
        schedule.shares_memory_with(id("c")),
        vec!["a"],
        "`c` and `a` must share memory:\n{table}"
    );
    assert!(
        schedule.shares_memory_with(id("b")).is_empty(),
        "`b` overlaps both and must not share:\n{table}"
    );
    let m = schedule.memory;
    assert!(
        m.peak_bytes < m.unpooled_bytes,
        "peak {} B must be below unpooled {} B:\n{table}",
        m.peak_bytes,
        m.unpooled_bytes
    );
    let texture = 256 * 192 * 8;
    assert_eq!(
        m.unpooled_bytes - m.peak_bytes,
        texture,
        "sharing saves exactly one rgba16float texture:\n{table}"
    );

    // The same pipeline on the GPU: a and c really live in one texture, and
    // the result is still exactly the closed-form image.
    let (_lock, gpu) = gpu();
    let scene = scene();
    let (image, _) = render(&gpu, &path, &scene);
    let (w, h) = SIZE;
    let mut bad = Vec::new();
    for (x, y, px) in image.enumerate_pixels() {
        // fill: (u, v, 0.25) → swap: (v, u, 0.75) → halve: (v/2, u, 0.475) → copy, stored as rgba8unorm.
        let u = (x as f32 + 0.5) / w as f32;
        let v = (y as f32 + 0.5) / h as f32;
        let want = [0.5 * v, u, 0.475, 1.0].map(|c| (c * 255.0).round());
        // rgba16float intermediates round to ~11 bits; allow 2/255.
        if px
            .0
            .iter()
            .zip(want)
            .any(|(&got, want)| (got as f32 - want).abs() > 2.0)
        {
            bad.push(format!("({x},{y}) = {:?}, expected {want:?}", px.0));
        }
    }
    assert!(
        bad.is_empty(),
        "{} of {} pixels are wrong with shared memory, e.g. {}",
        bad.len(),
        w * h,
        bad[..bad.len().min(5)].join("; ")
    );
}

#[test]
fn timestamps_time_every_pass() {
    let (_lock, gpu) = gpu();
    // Either way of timing (inside encoders, or through the passes'
    // descriptors as in a browser: plait_gpu::timing) times every pass;
    // without either the renderer reports `gpu_ms: None` (checked here).
    let timed = gpu.timestamp_way().is_some();
    if !timed {
        eprintln!(
            "adapter {} has no timestamp queries; checking that gpu_ms is None",
            gpu.adapter_name()
        );
    }
    let scene = scene();
    for pipeline in pipeline_files() {
        let (_, report) = render(&gpu, &pipeline, &scene);
        let name = rel(&pipeline);
        assert!(
            !report.passes.is_empty(),
            "{name}: the report lists no passes"
        );
        for p in &report.passes {
            match (timed, p.gpu_ms) {
                (true, Some(ms)) => assert!(
                    ms >= 0.0 && ms.is_finite(),
                    "{name}: pass `{}` has gpu_ms {ms}",
                    p.name
                ),
                (true, None) => panic!(
                    "{name}: pass `{}` has no gpu_ms although the adapter has timestamps",
                    p.name
                ),
                (false, Some(ms)) => panic!(
                    "{name}: pass `{}` has gpu_ms {ms} without timestamp queries",
                    p.name
                ),
                (false, None) => {}
            }
        }
        if timed {
            let total = report
                .total_gpu_ms
                .unwrap_or_else(|| panic!("{name}: no total_gpu_ms"));
            assert!(total >= 0.0, "{name}: total_gpu_ms {total}");
        }
    }
}

#[test]
fn a_loaded_target_starts_from_its_clear_value() {
    // `mark` loads `revealage` (clear = [1, 1, 1, 1]) and draws 0.25 with
    // `min` on the right half only: the left half must read 1, the right
    // 0.25. Without the clear value both halves would be 0 (zeros, min).
    let path = repo_root().join("tests/fixtures/clear_revealage.toml");
    let (_lock, gpu) = gpu();
    let (image, _) = render(&gpu, &path, &scene());
    let (w, h) = SIZE;
    let mut bad = Vec::new();
    for (x, y, px) in image.enumerate_pixels() {
        let left = (x as f32 + 0.5) / (w as f32) < 0.5;
        let want = if left { 255 } else { 64 };
        // RGB only: the read-back image is opaque.
        if px.0[..3].iter().any(|&c| c.abs_diff(want) > 1) {
            bad.push(format!("({x},{y}) = {:?}, expected {want}", px.0));
        }
    }
    assert!(
        bad.is_empty(),
        "{} of {} pixels are wrong, e.g. {}",
        bad.len(),
        w * h,
        bad[..bad.len().min(5)].join("; ")
    );
}
