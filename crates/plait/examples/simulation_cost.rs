//! What simulation and guide interpolation cost on this machine, in the
//! layouts of Halén & Wester 2007 §6.1.2 (Fig. 6.1.1: simulation time per
//! frame against simulated strands, one row per nodes per strand) and §6.1.3
//! (Fig. 6.1.3: the GPU update pass against the amount of drawn geometry):
//!
//! `cargo run --release -p plait --example simulation_cost [-- --frames N]`
//!
//! Each cell is the median GPU time (timestamps) of the `simulate` or
//! `interpolate` pass over N frames (default 20) after one warm-up, and the
//! median wall-clock time a frame takes more than with `simulation =
//! "none"`, with the `verlet` technique's defaults (4 substeps × 4
//! constraint sweeps a frame). The
//! pipeline is only the simulation and one 16² hair draw that needs it. A
//! measurement, not a test: nothing here fails on a slow machine.

use std::path::{Path, PathBuf};
use std::time::Instant;

use plait::gpu::Gpu;
use plait::session::{SceneData, prepare};
use plait_hair::scene::Scene;

const PIPELINE: &str = r#"
[pipeline]
name = "simulation_cost"
description = "The verlet simulation technique and one hair draw that needs it"
outputs = ["depth"]

[techniques]
simulation = "verlet"

[resources.depth]
kind = "texture"
format = "depth32float"
size = [16, 16]

[passes.draw]
type = "shadow_map"
view = "light"
draw = "hair"
writes = { depth = "depth" }
"#;

fn groom(strands: u32, segments: u32, guides: Option<u32>) -> SceneData {
    let guides = guides.map_or(String::new(), |g| format!("guides = {g}\n"));
    let text = format!(
        "[hair.procedural]\nstrands = {strands}\nsegments = {segments}\nseed = 2\n{guides}\n[head]\ncenter = [0.0, 0.0, 0.0]\nradii = [0.9, 1.05, 1.0]\n[camera]\neye = [0.0, 0.0, 7.0]\ntarget = [0.0, -0.5, 0.0]\nfov_y_degrees = 40.0\n[light]\ntype = \"directional\"\ndirection = [-0.5, -1.0, -0.6]\n"
    );
    let scene = Scene::from_toml_str(&text, Path::new("simulation_cost.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    SceneData::new(scene).unwrap_or_else(|e| panic!("{e}"))
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median GPU ms of pass `name` over `frames` frames after a warm-up, and
/// the median wall-clock ms a frame takes more than with `simulation =
/// "none"` (submit to finish: a check on the timestamps, which lavapipe
/// writes as it meets them).
fn pass_ms(gpu: &Gpu, pipeline: &Path, scene: &SceneData, name: &str, frames: usize) -> (f64, f64) {
    let wall = |sets: &[String]| {
        let prepared =
            prepare(gpu, pipeline, sets, scene, (16, 16)).unwrap_or_else(|e| panic!("{e}"));
        prepared.render().unwrap_or_else(|e| panic!("{e}"));
        let index = prepared
            .schedule()
            .passes
            .iter()
            .position(|p| p.name == name);
        let (mut gpu_ms, mut wall_ms) = (Vec::new(), Vec::new());
        for _ in 0..frames {
            let started = Instant::now();
            let report = prepared.render().unwrap_or_else(|e| panic!("{e}")).report;
            wall_ms.push(started.elapsed().as_secs_f64() * 1e3);
            if let Some(i) = index {
                gpu_ms.push(report.passes[i].gpu_ms.unwrap_or(f64::NAN));
            }
        }
        (gpu_ms, median(wall_ms))
    };
    let (gpu_ms, with) = wall(&[]);
    let (_, without) = wall(&["techniques.simulation=none".to_owned()]);
    (median(gpu_ms), with - without)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let frames: usize = args
        .iter()
        .position(|a| a == "--frames")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(20)
        .max(1);
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    if !gpu.capabilities.timestamps {
        eprintln!(
            "{} has no timestamp queries: no GPU times to report",
            gpu.adapter_name()
        );
        return;
    }
    let pipeline: PathBuf = std::env::temp_dir().join("plait_simulation_cost.toml");
    std::fs::write(&pipeline, PIPELINE).unwrap_or_else(|e| panic!("{e}"));
    println!(
        "median GPU ms of {frames} frames on {} ({}); verlet defaults: 4 substeps × 4 sweeps a frame",
        gpu.adapter_name(),
        gpu.backend_name()
    );

    // Fig. 6.1.1 layout: simulated strands across, nodes per strand down.
    let strands = [9u32, 25, 49, 121, 1000, 10000];
    println!(
        "\nsimulate: GPU ms per frame (wall ms over no simulation), Halén & Wester 2007 §6.1.2 layout"
    );
    print!("| nodes per strand |");
    for s in strands {
        print!(" {s} strands |");
    }
    println!();
    println!("|---:|{}", "---:|".repeat(strands.len()));
    for nodes in [4u32, 8, 32] {
        print!("| {nodes} |");
        for s in strands {
            let scene = groom(s, nodes - 1, None);
            let (gpu_ms, wall_ms) = pass_ms(&gpu, &pipeline, &scene, "simulate", frames);
            print!(" {gpu_ms:.3} ({wall_ms:.2}) |");
        }
        println!();
    }

    // Fig. 6.1.3 layout: drawn geometry across, the update pass's time.
    let drawn = [2000u32, 4000, 10000, 15000];
    println!(
        "\ninterpolate (ms per frame) from 64 guides, 16 segments a strand; Fig. 6.1.3 layout"
    );
    print!("| drawn strands |");
    for d in drawn {
        print!(" {d} |");
    }
    println!();
    println!("|---|{}", "---:|".repeat(drawn.len()));
    print!("| points |");
    for d in drawn {
        print!(" {} |", d * 17);
    }
    println!();
    let cells: Vec<(f64, f64)> = drawn
        .iter()
        .map(|&d| {
            pass_ms(
                &gpu,
                &pipeline,
                &groom(d, 16, Some(64)),
                "interpolate",
                frames,
            )
        })
        .collect();
    print!("| GPU ms (timestamps) |");
    for c in &cells {
        print!(" {:.3} |", c.0);
    }
    println!();
    print!("| wall ms over no simulation (simulate + interpolate) |");
    for c in &cells {
        print!(" {:.2} |", c.1);
    }
    println!();
    let _ = std::fs::remove_file(&pipeline);
}
