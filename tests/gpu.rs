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
use plait_tests::{bless, open_gpu, pipeline_files, rel, repo_root};

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

/// Per-pixel difference: the largest absolute difference over R, G, B, A.
fn pixel_diff(a: &image::Rgba<u8>, b: &image::Rgba<u8>) -> u8 {
    a.0.iter()
        .zip(b.0.iter())
        .map(|(x, y)| x.abs_diff(*y))
        .max()
        .unwrap_or(0)
}

struct Comparison {
    /// Fraction of pixels whose difference exceeds `OUTLIER`.
    outlier_fraction: f64,
    /// Mean of the per-pixel differences, in 0..=255.
    mean: f64,
    max: u8,
    difference: RgbaImage,
}

/// A pixel counts as different when some channel is off by more than 24/255.
const OUTLIER: u8 = 24;
/// At most 1% of pixels may be different…
const MAX_OUTLIER_FRACTION: f64 = 0.01;
/// …and the mean per-pixel difference must stay within 2/255.
const MAX_MEAN: f64 = 2.0;
// Why these numbers: the goldens were made on Mesa lavapipe (Vulkan, llvmpipe
// rasterizer). Hair is drawn as 1-pixel lines, and line rasterization rules
// (diamond-exit vs. Bresenham, which pixel a line end covers) differ between
// Vulkan and GL drivers and between Mesa versions; a strand that moves by one
// pixel makes a few pixels completely different while the image as a whole is
// unchanged. A mean alone would hide a thin strand that vanished (it touches
// few pixels) or fail on harmless line shifts, so we bound both the share of
// strongly different pixels (a percentile check: 99% of pixels within 24/255,
// enough for rounding, sRGB encoding and blending-order differences) and the
// mean (a global shift in shading or exposure of even 1% fails).
fn compare(actual: &RgbaImage, golden: &RgbaImage) -> Comparison {
    let mut difference = RgbaImage::new(actual.width(), actual.height());
    let (mut sum, mut outliers, mut max) = (0u64, 0u64, 0u8);
    for ((a, g), d) in actual
        .pixels()
        .zip(golden.pixels())
        .zip(difference.pixels_mut())
    {
        let diff = pixel_diff(a, g);
        sum += diff as u64;
        max = max.max(diff);
        if diff > OUTLIER {
            outliers += 1;
        }
        // Red where it differs, scaled ×4 so small differences are visible; grey background.
        let grey = (g.0[0] as u16 + g.0[1] as u16 + g.0[2] as u16) / 12;
        *d = image::Rgba([
            (diff as u16 * 4).min(255).max(grey) as u8,
            grey as u8,
            grey as u8,
            255,
        ]);
    }
    let n = (actual.width() as u64 * actual.height() as u64).max(1) as f64;
    Comparison {
        outlier_fraction: outliers as f64 / n,
        mean: sum as f64 / n,
        max,
        difference,
    }
}

/// Compare with `tests/golden/<stem>.png`, or write it with `PLAIT_BLESS=1`.
/// On failure writes `<stem>.actual.png` and `<stem>.difference.png` beside it.
fn check_golden(stem: &str, actual: &RgbaImage) -> Result<(), String> {
    let dir = repo_root().join("tests/golden");
    let golden_path = dir.join(format!("{stem}.png"));
    let actual_path = dir.join(format!("{stem}.actual.png"));
    let diff_path = dir.join(format!("{stem}.difference.png"));
    let _ = std::fs::remove_file(&actual_path);
    let _ = std::fs::remove_file(&diff_path);
    if bless() {
        actual
            .save(&golden_path)
            .map_err(|e| format!("writing {}: {e}", golden_path.display()))?;
        eprintln!("blessed {}", rel(&golden_path));
        return Ok(());
    }
    let save_actual = || {
        actual
            .save(&actual_path)
            .map(|_| rel(&actual_path))
            .unwrap_or_else(|e| format!("(could not write {}: {e})", actual_path.display()))
    };
    let golden = match image::open(&golden_path) {
        Ok(g) => g.to_rgba8(),
        Err(e) => {
            return Err(format!(
                "{stem}: no usable golden image {} ({e}); wrote {} — check it and rerun with PLAIT_BLESS=1 to commit it",
                rel(&golden_path),
                save_actual()
            ));
        }
    };
    if golden.dimensions() != actual.dimensions() {
        return Err(format!(
            "{stem}: golden {} is {:?}, render is {:?}; wrote {}",
            rel(&golden_path),
            golden.dimensions(),
            actual.dimensions(),
            save_actual()
        ));
    }
    let c = compare(actual, &golden);
    let ok = c.outlier_fraction <= MAX_OUTLIER_FRACTION && c.mean <= MAX_MEAN;
    eprintln!(
        "{stem}: {:.3}% of pixels differ by more than {OUTLIER}/255 (limit {:.1}%), mean {:.3}/255 (limit {MAX_MEAN}), max {}",
        c.outlier_fraction * 100.0,
        MAX_OUTLIER_FRACTION * 100.0,
        c.mean,
        c.max
    );
    if ok {
        return Ok(());
    }
    let actual_written = save_actual();
    let _ = c.difference.save(&diff_path);
    Err(format!(
        "{stem}: render differs from {}: {:.3}% of pixels differ by more than {OUTLIER}/255 (limit {:.1}%), \
         mean difference {:.3}/255 (limit {MAX_MEAN}), max {}; see {actual_written} and {}",
        rel(&golden_path),
        c.outlier_fraction * 100.0,
        MAX_OUTLIER_FRACTION * 100.0,
        c.mean,
        c.max,
        rel(&diff_path)
    ))
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

/// A variant reached with `--set` renders the same image as the variant's
/// file: the overrides and `extends` go through one merge.
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
    let by_file = image("pipelines/occupancy_no_slab.toml", &[]);
    let by_set = image("pipelines/occupancy.toml", &["params.slabs=1"]);
    assert!(
        by_file == by_set,
        "occupancy.toml --set params.slabs=1 differs from occupancy_no_slab.toml"
    );
    let unbind = [
        "passes.hair.params.visibility=none",
        "passes.hair.reads.vis_range=",
        "passes.hair.reads.vis_bits=",
        "passes.hair.reads.vis_slabs=",
        "passes.opaque.params.visibility=none",
        "passes.opaque.reads.vis_range=",
        "passes.opaque.reads.vis_bits=",
        "passes.opaque.reads.vis_slabs=",
    ];
    let by_file = image("pipelines/no_self_shadow.toml", &[]);
    let by_set = image("pipelines/occupancy.toml", &unbind);
    assert!(
        by_file == by_set,
        "occupancy.toml with the --set flags of no_self_shadow.toml's header differs from it"
    );
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

/// The comparison must be able to fail: a strand-sized change is caught even
/// though it barely moves the mean.
#[test]
fn golden_comparison_catches_a_missing_strand_and_a_shift() {
    let golden = RgbaImage::from_pixel(256, 192, image::Rgba([40, 40, 40, 255]));
    // A 3-pixel-wide bright band (a few strands) missing: 1.2% of pixels, small mean.
    let mut missing = golden.clone();
    for y in 0..192 {
        for x in 100..103 {
            missing.put_pixel(x, y, image::Rgba([200, 180, 120, 255]));
        }
    }
    let c = compare(&missing, &golden);
    assert!(
        c.outlier_fraction > MAX_OUTLIER_FRACTION,
        "a missing band must fail: {:.4}",
        c.outlier_fraction
    );
    // A global brightness shift of 3/255: no outliers, but the mean catches it.
    let mut shifted = golden.clone();
    for p in shifted.pixels_mut() {
        p.0[0] += 3;
    }
    let c = compare(&shifted, &golden);
    assert!(
        c.outlier_fraction == 0.0 && c.mean > MAX_MEAN,
        "a global shift must fail on the mean: {}",
        c.mean
    );
    // A one-pixel line shift of a single strand passes.
    let mut a = golden.clone();
    let mut b = golden.clone();
    for y in 0..192 {
        a.put_pixel(50, y, image::Rgba([200, 180, 120, 255]));
        b.put_pixel(51, y, image::Rgba([200, 180, 120, 255]));
    }
    let c = compare(&a, &b);
    assert!(
        c.outlier_fraction <= MAX_OUTLIER_FRACTION && c.mean <= MAX_MEAN,
        "a 1-px line shift must pass"
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
