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
use plait_tests::golden_images::{MAX_MEAN, MAX_OUTLIERS, check_golden, compare};
use plait_tests::{open_gpu, pipeline_files, rel, repo_root, strands_subset};

/// Golden-image size and scene: small enough for a software rasterizer.
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
    let name = rel(pipeline);
    let prepared = prepare(gpu, pipeline, &[], scene, SIZE)
        .unwrap_or_else(|e| panic!("preparing {name}: {e}"));
    let report = prepared
        .renderer
        .render()
        .unwrap_or_else(|e| panic!("rendering {name}: {e}"));
    let image = prepared
        .image()
        .unwrap_or_else(|e| panic!("reading back {name}: {e}"));
    (image, report)
}

#[test]
fn every_pipeline_matches_its_golden_image() {
    let (_lock, gpu) = gpu();
    let scene = scene();
    let mut failures = Vec::new();
    for pipeline in pipeline_files() {
        let stem = pipeline
            .file_stem()
            .expect("stem")
            .to_string_lossy()
            .into_owned();
        let (image, _) = render(&gpu, &pipeline, &scene);
        if let Err(e) = check_golden(&stem, &image) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The stray strands lifted off the head (Sintorn & Assarsson 2009 Fig. 4–5)
/// are the case where self-shadowing methods differ most: the default
/// pipeline on the stray-strand scene has a golden image of its own.
#[test]
fn occupancy_on_stray_strands_matches_its_golden_image() {
    let (_lock, gpu) = gpu();
    let scene = load_scene("examples/scenes/stray.toml");
    let (image, _) = render(&gpu, &repo_root().join("pipelines/occupancy.toml"), &scene);
    check_golden("occupancy_stray", &image).unwrap_or_else(|e| panic!("{e}"));
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
            .renderer
            .render()
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
    let (image, _) = render(&gpu, &repo_root().join("pipelines/forward.toml"), &scene);
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

/// The comparison must be able to fail: a single strand that disappears from
/// the small scene's golden image is caught, while a one-pixel shift of a
/// line and tiny rounding differences pass.
#[test]
fn golden_comparison_catches_a_single_missing_strand() {
    let (_lock, gpu) = gpu();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    // The stray-strand scene: its last 12 strands arc up and out of the
    // volume, each a 1-pixel line against the background.
    let full = load_scene("examples/scenes/stray.toml");
    let (golden, _) = render(&gpu, &pipeline, &full);
    let all = &full.strands;
    let count = all.strand_count();
    let mut report = Vec::new();
    for missing in count - 12..count {
        let mut one_less = load_scene("examples/scenes/stray.toml");
        let strands = strands_subset(all, |s| s != missing);
        // Same framing: the light frustum follows the hair's bounds.
        if strands.bounds() != all.bounds() {
            continue;
        }
        one_less.strands = strands;
        let (image, _) = render(&gpu, &pipeline, &one_less);
        let c = compare(&image, &golden);
        report.push(format!("stray strand {missing}: {} outliers", c.outliers));
        assert!(
            c.outliers > MAX_OUTLIERS,
            "the golden comparison must fail when stray strand {missing} is missing: {} outliers, mean {:.3}",
            c.outliers,
            c.mean
        );
    }
    assert!(
        report.len() >= 6,
        "too few strays keep the framing: {report:?}"
    );
    eprintln!("{}", report.join("\n"));

    // A one-pixel line shift of a single strand passes.
    let background = RgbaImage::from_pixel(256, 192, image::Rgba([40, 40, 40, 255]));
    let mut a = background.clone();
    let mut b = background.clone();
    for y in 0..192 {
        a.put_pixel(50, y, image::Rgba([200, 180, 120, 255]));
        b.put_pixel(51, y, image::Rgba([200, 180, 120, 255]));
    }
    let c = compare(&a, &b);
    assert!(
        c.outliers == 0 && c.mean <= MAX_MEAN,
        "a 1-px line shift must pass"
    );
    // A global brightness shift of 3/255: no outliers, but the mean catches it.
    let mut shifted = background.clone();
    for p in shifted.pixels_mut() {
        p.0[0] += 3;
    }
    let c = compare(&shifted, &background);
    assert!(
        c.outliers == 0 && c.mean > MAX_MEAN,
        "a global shift must fail on the mean: {}",
        c.mean
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
    if !gpu.capabilities.timestamps {
        // Not a skip of the test's subject: the adapter has no timestamp queries,
        // which the renderer reports as `gpu_ms: None` (checked here).
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
            match (gpu.capabilities.timestamps, p.gpu_ms) {
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
        if gpu.capabilities.timestamps {
            let total = report
                .total_gpu_ms
                .unwrap_or_else(|| panic!("{name}: no total_gpu_ms"));
            assert!(total >= 0.0, "{name}: total_gpu_ms {total}");
        }
    }
}

/// The small scene lit mostly by its ambient light (the key light dimmed),
/// so the environment term the `ambient_occlusion` techniques darken shows.
fn ambient_scene() -> SceneData {
    let mut scene = scene();
    scene.scene.ambient = 1.2;
    scene.scene.light.intensity = 0.6;
    scene
}

/// Both per-vertex ambient occlusion techniques (Xing et al. 2012 §4; Halén &
/// Wester 2007 §3.3.1) on the default pipeline: a golden image each, and each
/// darker than the same render without occlusion.
#[test]
fn ambient_occlusion_techniques_match_their_golden_images() {
    let (_lock, gpu) = gpu();
    let scene = ambient_scene();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let render_with = |technique: &str| {
        let sets = [format!("techniques.ambient_occlusion={technique}")];
        let prepared = prepare(&gpu, &pipeline, &sets, &scene, SIZE)
            .unwrap_or_else(|e| panic!("preparing {technique}: {e}"));
        prepared.renderer.render().expect("renders");
        prepared.image().expect("reads back")
    };
    let brightness = |image: &RgbaImage| -> u64 {
        image
            .pixels()
            .map(|p| p.0[..3].iter().map(|&c| c as u64).sum::<u64>())
            .sum()
    };
    let open = brightness(&render_with("none"));
    let mut failures = Vec::new();
    for technique in ["deep_opacity_directions", "cylinders"] {
        let image = render_with(technique);
        let darker = brightness(&image);
        eprintln!("{technique}: brightness {darker} of {open} without occlusion");
        if darker >= open {
            failures.push(format!(
                "{technique}: not darker than no occlusion ({darker} ≥ {open})"
            ));
        }
        if let Err(e) = check_golden(&format!("ao_{technique}"), &image) {
            failures.push(e);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
