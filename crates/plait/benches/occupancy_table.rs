//! The timing table of Sintorn & Assarsson 2009 §4, measured on this machine:
//! `cargo bench -p plait --bench occupancy_table [-- --repeats N --size WxH]`.
//!
//! Renders `pipelines/occupancy.toml` on the default scene (10,000 strands) and
//! the dense scene (24,000 strands, interpolated from guides) and prints the
//! median GPU time of each pass, grouped as the paper groups them, next to
//! the paper's GTX 280 figures (800x600, 512² maps, 20,000 strands).
//! A benchmark, not a test: nothing here can fail on a slow machine.

use std::path::Path;
use std::time::Instant;

use plait::gpu::Gpu;
use plait::session::{SceneData, prepare, repo_root};

/// (paper row, plait pass name, paper ms)
const ROWS: &[(&str, &str, Option<f64>)] = &[
    ("Self-shadowing", "", None),
    ("  Find depth range", "light_range", Some(2.54)),
    ("  Render occupancy map", "light_occupancy", Some(2.56)),
    ("  Render slab-size map", "light_slabs", Some(2.89)),
    ("Alpha approximation", "", None),
    ("  Find depth range", "camera_range", Some(2.63)),
    ("  Render occupancy map", "camera_occupancy", Some(1.8)),
    ("  Render slab-size map", "camera_slabs", Some(1.88)),
    ("Final image", "", None),
    ("  Render BG shadow map", "opaque_shadow", Some(0.5)),
    ("  Render background", "opaque", Some(1.0)),
    ("  Render hair", "hair", Some(12.8)),
    ("  Compose BG and Hair", "compose", Some(0.1)),
];

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let repeats: usize = arg("--repeats")
        .and_then(|s| s.parse().ok())
        .unwrap_or(3)
        .max(1);
    let size = arg("--size")
        .and_then(|s| {
            s.split_once('x')
                .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        })
        .unwrap_or((800, 600));
    let root = repo_root();
    let pipeline = root.join("pipelines/occupancy.toml");
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    if !gpu.capabilities.timestamps {
        eprintln!(
            "{} has no timestamp queries: no GPU times to report",
            gpu.adapter_name()
        );
        return;
    }
    println!(
        "occupancy.toml, {}x{}, median of {repeats} frames after one warm-up, on {} ({})",
        size.0,
        size.1,
        gpu.adapter_name(),
        gpu.backend_name()
    );
    let scenes = [
        ("default", root.join("examples/scenes/default.toml")),
        ("dense", root.join("examples/scenes/dense.toml")),
    ];
    let mut columns = Vec::new();
    for (name, path) in &scenes {
        let started = Instant::now();
        let data = SceneData::load(Some(Path::new(path))).unwrap_or_else(|e| panic!("{e}"));
        let groom_ms = started.elapsed().as_secs_f64() * 1e3;
        let prepared = prepare(&gpu, &pipeline, &[], &data, size).unwrap_or_else(|e| panic!("{e}"));
        prepared.render().unwrap_or_else(|e| panic!("{e}"));
        let mut per_pass: Vec<Vec<f64>> = vec![Vec::new(); prepared.schedule().passes.len()];
        let mut frame = Vec::new();
        for _ in 0..repeats {
            let report = prepared.render().unwrap_or_else(|e| panic!("{e}")).report;
            for (i, p) in report.passes.iter().enumerate() {
                per_pass[i].push(p.gpu_ms.unwrap_or(f64::NAN));
            }
            frame.push(report.total_gpu_ms.unwrap_or(f64::NAN));
        }
        let names: Vec<String> = prepared
            .schedule()
            .passes
            .iter()
            .map(|p| p.name.clone())
            .collect();
        let medians: Vec<(String, f64)> = names
            .into_iter()
            .zip(per_pass.into_iter().map(median))
            .collect();
        columns.push((
            *name,
            data.strands.strand_count(),
            data.strands.segment_count(),
            groom_ms,
            medians,
            median(frame),
        ));
    }
    print!("{:<28} {:>12}", "Algorithm step", "paper ms");
    for (name, strands, segments, ..) in &columns {
        print!(
            " {:>22}",
            format!("{name} ({strands}×{})", segments / strands.max(&1))
        );
    }
    println!();
    print!("{:<28} {:>12}", "Generate hair (CPU)", "2.9");
    for c in &columns {
        print!(" {:>22.1}", c.3);
    }
    println!();
    for (row, pass, paper) in ROWS {
        print!(
            "{row:<28} {:>12}",
            paper.map(|p| format!("{p:.2}")).unwrap_or_default()
        );
        if !pass.is_empty() {
            for c in &columns {
                let ms = c.4.iter().find(|(n, _)| n == pass).map(|(_, ms)| *ms);
                print!(
                    " {:>22}",
                    ms.map(|m| format!("{m:.1}")).unwrap_or_else(|| "—".into())
                );
            }
        }
        println!();
    }
    print!("{:<28} {:>12}", "Frame (GPU)", "");
    for c in &columns {
        print!(" {:>22.1}", c.5);
    }
    println!();
}
