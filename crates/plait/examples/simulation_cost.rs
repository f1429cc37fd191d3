//! What simulation and guide interpolation cost on this machine, in the
//! layouts of Halén & Wester 2007 §6.1.2 (Fig. 6.1.1: simulation time per
//! frame against simulated strands, one row per nodes per strand) and §6.1.3
//! (Fig. 6.1.3: the GPU update pass against the amount of drawn geometry):
//!
//! `cargo run --release -p plait --example simulation_cost [-- --frames N]`
//!
//! Each cell is the median GPU time (timestamps) of the `simulate` or
//! `interpolate` pass over N frames after one warm-up, with the `verlet`
//! technique's defaults (4 substeps × 4 constraint sweeps a frame). The
//! pipeline is only the simulation and one 16² hair draw that needs it. A
//! measurement, not a test: nothing here fails on a slow machine.

use std::path::{Path, PathBuf};

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

/// Median GPU ms of pass `name` over `frames` frames after a warm-up.
fn pass_ms(gpu: &Gpu, pipeline: &Path, scene: &SceneData, name: &str, frames: usize) -> f64 {
    let prepared = prepare(gpu, pipeline, &[], scene, (16, 16)).unwrap_or_else(|e| panic!("{e}"));
    prepared.renderer.render().unwrap_or_else(|e| panic!("{e}"));
    let index = prepared
        .schedule()
        .passes
        .iter()
        .position(|p| p.name == name)
        .unwrap_or_else(|| panic!("no pass `{name}`"));
    let times = (0..frames)
        .map(|_| {
            let report = prepared.renderer.render().unwrap_or_else(|e| panic!("{e}"));
            report.passes[index].gpu_ms.unwrap_or(f64::NAN)
        })
        .collect();
    median(times)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let frames: usize = args
        .iter()
        .position(|a| a == "--frames")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(10)
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
    println!("\nsimulate (ms per frame), Halén & Wester 2007 §6.1.2 layout");
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
            print!(
                " {:.3} |",
                pass_ms(&gpu, &pipeline, &scene, "simulate", frames)
            );
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
    print!("| ms |");
    for d in drawn {
        let scene = groom(d, 16, Some(64));
        print!(
            " {:.3} |",
            pass_ms(&gpu, &pipeline, &scene, "interpolate", frames)
        );
    }
    println!();
    let _ = std::fs::remove_file(&pipeline);
}
