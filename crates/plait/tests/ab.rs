//! `plait::ab` in-process, without the binary: a tiny run (two variants,
//! the small scene at 64×48, one repeat) gives a complete report and its
//! files with progress for every step; two sweeps give a grid; a failing
//! progress callback stops the run. GPU tests: they run on lavapipe (no
//! adapter is a failure, never a skip).

use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};

use plait::ab::{AbError, AbOptions, Plan, SweepSpec, run};
use plait::gpu::Gpu;
use plait_compare::report::Report;

/// One GPU test at a time: lavapipe already uses every core for one device.
static GPU_LOCK: Mutex<()> = Mutex::new(());

fn open_gpu() -> (MutexGuard<'static, ()>, Gpu) {
    let guard = GPU_LOCK.lock().unwrap_or_else(|p| p.into_inner());
    match Gpu::new() {
        Ok(gpu) => (guard, gpu),
        Err(e) => panic!("GPU tests need an adapter and none could be opened: {e}"),
    }
}

fn repo(path: &str) -> PathBuf {
    plait::session::repo_root().join(path)
}

fn tiny(pipelines: &[&str], reference: &str) -> AbOptions {
    let mut o = AbOptions::new(pipelines.iter().map(|p| repo(p)).collect(), repo(reference));
    o.scenes = vec![repo("examples/scenes/small.toml")];
    o.size = (64, 48);
    o.repeats = 1;
    o.command = vec!["test".into(), "a b".into()];
    o
}

fn run_of<'r>(report: &'r Report, id: &str) -> &'r plait_compare::report::Run {
    report.scenes[0]
        .runs
        .iter()
        .find(|r| r.variant == id)
        .unwrap_or_else(|| panic!("no run of {id}"))
}

#[test]
fn a_tiny_run_reports_every_variant_and_writes_its_files() {
    let plan = Plan::new(tiny(
        &["pipelines/forward.toml", "pipelines/occupancy.toml"],
        "pipelines/forward.toml",
    ))
    .expect("plan");
    let dir = tempfile::tempdir().expect("tempdir");
    let (_lock, gpu) = open_gpu();
    let mut steps = Vec::new();
    let report = run(&plan, &gpu, dir.path(), &mut |step| {
        steps.push((step.done, step.total, step.message.to_string()));
        Ok(())
    })
    .expect("run");

    // Progress: every step once, in order, the count known up front.
    let total = plan.step_count();
    assert_eq!(total, 3 * (4 + 1));
    assert_eq!(steps.len() as u64, total);
    for (i, (done, t, _)) in steps.iter().enumerate() {
        assert_eq!((*done, *t), (i as u64 + 1, total));
    }
    let messages: Vec<&str> = steps.iter().map(|s| s.2.as_str()).collect();
    for expected in [
        "small: built forward",
        "small: warm-up occupancy",
        "small: repeat 1/1 occupancy",
        "small: compared forward (reference)",
        "small: probed forward (reference)",
    ] {
        assert!(messages.contains(&expected), "{expected} in {messages:?}");
    }

    // The variants, the reference last.
    let ids: Vec<&str> = report.variants.iter().map(|v| v.id.as_str()).collect();
    assert_eq!(ids, ["forward", "occupancy", "reference"]);
    assert!(report.sweeps.is_empty());
    assert!(report.variants.iter().all(|v| v.memory.peak_bytes > 0));
    // The same pipeline as the reference renders the same image; another does not.
    let same = run_of(&report, "forward");
    assert_eq!(same.metrics.rmse, 0.0);
    assert_eq!(same.metrics.psnr_db, None);
    let other = run_of(&report, "occupancy");
    assert!(other.metrics.rmse > 0.0 && other.metrics.ssim < 1.0);
    // Self-shadowing probed against the reference's provider.
    let vis = other.visibility.as_ref().expect("occupancy has a provider");
    assert_eq!(
        (vis.provider.as_str(), vis.reference_provider.as_str()),
        ("occupancy", "modified_shadow_map")
    );
    assert!(vis.rays_through_hair > 0 && vis.mean_abs_error > 0.0);
    assert_eq!(
        same.visibility.as_ref().map(|v| v.mean_abs_error),
        Some(0.0)
    );
    assert_eq!(same.timing.wall_ms.samples.len(), 1);

    // Every file the report names is in the directory.
    let scene = &report.scenes[0];
    let mut named = vec![scene.reference_image.clone()];
    for r in &scene.runs {
        named.extend([r.image.clone(), r.diff_image.clone(), r.flip_image.clone()]);
    }
    named.extend(report.variants.iter().filter_map(|v| v.graph_svg.clone()));
    for name in &named {
        assert!(dir.path().join(name).is_file(), "{name}");
    }
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("report.json")).expect("json"))
            .expect("valid JSON");
    assert_eq!(json["schema"], "plait-ab/2");
    assert_eq!(json["provenance"]["command_line"], "test 'a b'");
    let html = std::fs::read_to_string(dir.path().join("report.html")).expect("html");
    assert!(html.contains("occupancy") && html.contains("Provenance"));
    // The Markdown tables the book's gallery page is made from: a row per variant.
    let md = std::fs::read_to_string(dir.path().join("report.md")).expect("report.md");
    for v in &report.variants {
        assert!(
            md.contains(&format!("| {}", v.label)),
            "{} not in report.md:\n{md}",
            v.label
        );
    }
    // forward.toml is both a variant and the reference: its files once.
    assert_eq!(report.provenance.pipelines.len(), 2);
}

/// Two sweeps: every combination, the first sweep's values outermost, in
/// one report; the grid point with the reference's values renders it.
#[test]
fn two_sweeps_give_every_combination_in_one_report() {
    let mut options = tiny(&["pipelines/forward.toml"], "pipelines/forward.toml");
    // The reference at one of the sweep's points (forward.toml's own density is 264.2).
    options.sets = vec![
        "params.light_size=256".into(),
        "params.hair_density=40".into(),
    ];
    options.sweeps = vec![
        SweepSpec::parse("params.hair_density=10,40").expect("sweep"),
        SweepSpec::parse("params.light_size=128,256").expect("sweep"),
    ];
    let plan = Plan::new(options).expect("plan");
    let dir = tempfile::tempdir().expect("tempdir");
    let (_lock, gpu) = open_gpu();
    let report = run(&plan, &gpu, dir.path(), &mut |_| Ok(())).expect("run");
    assert_eq!(report.sweeps.len(), 2);
    let points: Vec<Vec<&str>> = report
        .variants
        .iter()
        .filter(|v| !v.is_reference)
        .map(|v| v.sweep_values.values().map(String::as_str).collect())
        .collect();
    assert_eq!(
        points,
        [["10", "128"], ["10", "256"], ["40", "128"], ["40", "256"]]
    );
    assert_eq!(run_of(&report, "forward@40@256").metrics.rmse, 0.0);
    for id in ["forward@10@128", "forward@10@256", "forward@40@128"] {
        assert!(run_of(&report, id).metrics.rmse > 0.0, "{id}");
    }
    // A larger light map costs more memory, whatever the density.
    let peak = |id: &str| report.variant(id).expect(id).memory.peak_bytes;
    assert!(peak("forward@10@256") > peak("forward@10@128"));
    assert_eq!(peak("forward@10@256"), peak("forward@40@256"));
    let html = std::fs::read_to_string(dir.path().join("report.html")).expect("html");
    assert!(html.contains("params.hair_density (rows) × params.light_size (columns)"));
}

/// `--hair-color`: the reference is rendered once per colour (the same
/// pipeline as variant and reference: no error in either colour — a
/// reference left in the scene's own colours would differ), and the colours
/// reach the pixels (blond hair brighter than black) and the report.
#[test]
fn hair_colours_render_every_scene_and_its_reference_in_each_colour() {
    let mut options = tiny(&["pipelines/forward.toml"], "pipelines/forward.toml");
    options.hair_colors = vec![
        plait::ab::HairColor::parse("blond=0.85,0.65,0.40").expect("colour"),
        plait::ab::HairColor::parse("black=0.02,0.02,0.02").expect("colour"),
    ];
    let plan = Plan::new(options).expect("plan");
    let dir = tempfile::tempdir().expect("tempdir");
    let (_lock, gpu) = open_gpu();
    let report = run(&plan, &gpu, dir.path(), &mut |_| Ok(())).expect("run");
    let names: Vec<&str> = report.scenes.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["small@blond", "small@black"]);
    let mut means = Vec::new();
    for scene in &report.scenes {
        for r in &scene.runs {
            assert_eq!(r.metrics.rmse, 0.0, "{} {}", scene.name, r.variant);
        }
        assert!(scene.hair_color.is_some(), "{}", scene.name);
        let image = image::open(dir.path().join(&scene.reference_image))
            .expect("reference image")
            .to_rgb8();
        let sum: f64 = image.pixels().map(|p| f64::from(p.0[0])).sum();
        means.push(sum / f64::from(image.width() * image.height()));
    }
    assert!(
        means[0] > means[1] + 1.0,
        "blond {} not brighter than black {}",
        means[0],
        means[1]
    );
    let md = std::fs::read_to_string(dir.path().join("report.md")).expect("md");
    assert!(
        md.contains("**small@blond**\n\nEvery strand's colour [0.85, 0.65, 0.4]. "),
        "{md}"
    );
}

/// A progress display whose output went away (`| head`) stops the run with
/// that error, so the CLI can end quietly.
#[test]
fn a_failing_progress_callback_stops_the_run() {
    let plan =
        Plan::new(tiny(&["pipelines/forward.toml"], "pipelines/forward.toml")).expect("plan");
    let dir = tempfile::tempdir().expect("tempdir");
    let (_lock, gpu) = open_gpu();
    let mut calls = 0;
    let result = run(&plan, &gpu, dir.path(), &mut |_| {
        calls += 1;
        Err(std::io::Error::from(std::io::ErrorKind::BrokenPipe))
    });
    match result {
        Err(AbError::Progress(e)) => assert_eq!(e.kind(), std::io::ErrorKind::BrokenPipe),
        other => panic!("expected a progress error, got {:?}", other.map(|_| ())),
    }
    assert_eq!(calls, 1, "nothing runs after the callback fails");
    assert!(!dir.path().join("report.json").exists());
}

/// `--frames`: on a still scene, a variant that renders the same image every
/// frame has no flicker whatever its error; one brightened on odd frames
/// flickers by about that much; visibility is as stable as the reference's.
#[test]
fn the_temporal_metric_is_zero_when_still_and_positive_for_flicker() {
    let (_lock, gpu) = open_gpu();
    let mut o = tiny(
        &[
            "pipelines/deep_opacity.toml",
            "tests/fixtures/flicker/flicker.toml",
        ],
        "pipelines/occupancy.toml",
    );
    o.sequence = Some(plait::ab::Sequence {
        frames: 3,
        fps: 30.0,
    });
    let plan = Plan::new(o).expect("plan");
    let dir = tempfile::tempdir().expect("tempdir");
    let report = run(&plan, &gpu, dir.path(), &mut |_| Ok(())).expect("runs");
    let temporal = |id: &str| {
        run_of(&report, id)
            .temporal
            .clone()
            .unwrap_or_else(|| panic!("{id}: no temporal measure"))
    };
    let still = temporal("deep_opacity");
    assert_eq!(still.frames, 3);
    assert_eq!(still.image_flicker, [0.0, 0.0]);
    assert_eq!(still.image_change_mean, 0.0);
    let flicker = temporal("flicker");
    assert!(
        flicker.image_flicker.iter().all(|&f| f > 0.02),
        "{:?}",
        flicker.image_flicker
    );
    // The same provider as the reference's, on a still scene.
    assert_eq!(flicker.visibility_flicker.as_deref(), Some(&[0.0, 0.0][..]));
    assert!(still.visibility_flicker.is_some(), "deep opacity is probed");
    let markdown = std::fs::read_to_string(dir.path().join("report.md")).expect("report.md");
    assert!(markdown.contains("image flicker"), "{markdown}");
    let html = std::fs::read_to_string(dir.path().join("report.html")).expect("report.html");
    assert!(html.contains("image flicker over time"));
    assert!(html.contains("Temporal stability"));
}
