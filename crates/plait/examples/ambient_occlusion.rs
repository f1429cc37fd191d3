//! Per-vertex ambient occlusion measured (issue 11, item 4): the precompute
//! time of each `ambient_occlusion` technique, its memory, and the error of
//! deep opacity maps from 9, 25 and 64 directions against 100 — Xing et al.
//! 2012 Fig. 7's experiment as numbers (their Table 2 gives the offline times:
//! 5.5, 14.9, 39.3 and 63.4 min for 872,756 vertices).
//!
//! `cargo run -p plait --example ambient_occlusion -- [--scene FILE]
//!  [--strides 4,1]` (the built-in default scene unless `--scene`; cylinders
//! with each caster stride — the sum is O(n²): use 64 on the default scene).
//! Prints a Markdown table; "wall ms" is the first frame's wall-clock time
//! less the second's.

use std::path::PathBuf;

use plait::gpu::Gpu;
use plait::session::{SceneData, prepare, repo_root};

struct Run {
    label: String,
    ms: f64,
    wall_ms: f64,
    bytes: u64,
    ao: Vec<f32>,
}

fn run(gpu: &Gpu, scene: &SceneData, sets: &[String], label: String) -> Run {
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let prepared = prepare(gpu, &pipeline, sets, scene, (64, 48))
        .unwrap_or_else(|e| fail(&format!("{label}: {e}")));
    let timed = || {
        let start = std::time::Instant::now();
        let report = prepared
            .render()
            .unwrap_or_else(|e| fail(&format!("{label}: {e}")));
        (report, start.elapsed().as_secs_f64() * 1e3)
    };
    // The first frame runs the precompute; the second reuses it: the
    // difference of their wall-clock times is the precompute's.
    let (report, first) = timed();
    let (_, second) = timed();
    let ms = report
        .report
        .passes
        .iter()
        .find(|p| p.name == "ambient_occlusion")
        .and_then(|p| p.gpu_ms)
        .unwrap_or(f64::NAN);
    let schedule = prepared.schedule();
    let bytes = schedule
        .resources
        .iter()
        .filter(|r| r.name.starts_with("ao_"))
        .map(|r| r.desc.bytes())
        .sum();
    let raw = prepared
        .read_buffer("ao_vertex")
        .unwrap_or_else(|e| fail(&format!("{label}: {e}")));
    let ao = raw
        .chunks_exact(4)
        .take(scene.strands.points.len())
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    Run {
        label,
        ms,
        wall_ms: first - second,
        bytes,
        ao,
    }
}

fn fail(message: &str) -> ! {
    eprintln!("error: {message}");
    std::process::exit(1)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let scene_path = arg("--scene").map(PathBuf::from);
    let strides: Vec<u32> = arg("--strides")
        .unwrap_or_else(|| "4,1".into())
        .split(',')
        .map(|s| {
            s.parse()
                .unwrap_or_else(|_| fail(&format!("--strides {s}: not a number")))
        })
        .collect();
    let scene = SceneData::load(scene_path.as_deref()).unwrap_or_else(|e| fail(&e.to_string()));
    let gpu = Gpu::new().unwrap_or_else(|e| fail(&e.to_string()));
    let dod = |n: u32| {
        run(
            &gpu,
            &scene,
            &[
                "techniques.ambient_occlusion=deep_opacity_directions".into(),
                format!("params.ao_directions={n}"),
            ],
            format!("deep_opacity_directions, {n} directions"),
        )
    };
    let reference = dod(100);
    let mut runs: Vec<Run> = [9, 25, 64].into_iter().map(dod).collect();
    runs.push(reference);
    for k in strides {
        runs.push(run(
            &gpu,
            &scene,
            &[
                "techniques.ambient_occlusion=cylinders".into(),
                format!("params.ao_caster_stride={k}"),
            ],
            format!("cylinders, caster stride {k}"),
        ));
    }
    let truth = runs[3].ao.clone();
    println!(
        "{} hair vertices on {}, adapter {}",
        scene.strands.points.len(),
        scene_path
            .as_deref()
            .map_or("the built-in default scene".into(), |p| p
                .display()
                .to_string()),
        gpu.adapter_name()
    );
    println!();
    println!(
        "| technique | precompute GPU ms | wall ms | memory MiB | mean AO | mean / max \\|AO − AO₁₀₀\\| |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    for r in &runs {
        let n = r.ao.len() as f64;
        let mean = r.ao.iter().map(|&a| a as f64).sum::<f64>() / n;
        let diff: Vec<f64> =
            r.ao.iter()
                .zip(&truth)
                .map(|(a, b)| (a - b).abs() as f64)
                .collect();
        let mean_diff = diff.iter().sum::<f64>() / n;
        let max_diff = diff.iter().copied().fold(0.0, f64::max);
        println!(
            "| {} | {:.0} | {:.0} | {:.2} | {:.3} | {:.4} / {:.3} |",
            r.label,
            r.ms,
            r.wall_ms,
            r.bytes as f64 / (1024.0 * 1024.0),
            mean,
            mean_diff,
            max_diff
        );
    }
}
