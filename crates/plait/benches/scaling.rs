//! Frame time of the default pipeline against the hair's segment count:
//! `cargo bench -p plait --bench scaling [-- --size WxH --repeats N --segments 75000,150000,… --variant KEY=V,KEY=V … --largest]`.
//!
//! Generated grooms (the default scene's wavy groom, 32 segments per strand,
//! the strand count scaled) from 75,000 to 2,000,000 segments — the paper's
//! dog has 2M (Sintorn & Assarsson 2009 §4: 17 fps). Every groom is built
//! first and rendered in interleaved repeats, so all see the same machine
//! load. Prints the median frame GPU time per groom, a least-squares line
//! ms = a + b · segments with its R², the memory per segment (vertex and
//! index buffers; the schedule's maps do not grow with the hair) and the
//! largest groom the adapter's buffer limit allows; `--largest` doubles the
//! groom until a frame fails or takes longer than `--max-seconds` (120).
//! Each `--variant` is a column of `--set`s (e.g.
//! `--variant techniques.transparency=compute_raster,techniques.shading_space=strand`),
//! rendered interleaved with the others; with two or more, each further
//! column's frame over the first's is a column of its own. A benchmark, not
//! a test.

mod support;

use plait::gpu::Gpu;
use plait::hair::{HairSource, Scene, StrandVertex};
use plait::session::{Prepared, SceneData, prepare, repo_root};
use support::timing::{arg, median, size_arg};

const SEGMENTS_PER_STRAND: u32 = 32;

fn scene_with(segments: u64) -> SceneData {
    let mut scene = Scene::builtin_default();
    let HairSource::Procedural(spec) = &mut scene.hair.source else {
        panic!("the built-in scene's hair is procedural");
    };
    spec.segments = SEGMENTS_PER_STRAND;
    spec.strands = segments.div_ceil(SEGMENTS_PER_STRAND as u64) as u32;
    SceneData::new(scene).unwrap_or_else(|e| panic!("{e}"))
}

/// Bytes of hair geometry per segment: one vertex per point (segments + 1
/// per strand) and two u32 indices per segment (`plait_gpu::geometry`).
fn bytes_per_segment() -> f64 {
    let s = SEGMENTS_PER_STRAND as f64;
    std::mem::size_of::<StrandVertex>() as f64 * (s + 1.0) / s + 8.0
}

/// Least squares y = a + b·x, and R².
fn fit(points: &[(f64, f64)]) -> (f64, f64, f64) {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let b = sxy / sxx;
    let a = my - b * mx;
    let ss_res: f64 = points.iter().map(|p| (p.1 - a - b * p.0).powi(2)).sum();
    let ss_tot: f64 = points.iter().map(|p| (p.1 - my).powi(2)).sum();
    (a, b, 1.0 - ss_res / ss_tot)
}

/// Every `--name value` given (repeatable flags).
fn args(name: &str) -> Vec<String> {
    let all: Vec<String> = std::env::args().collect();
    all.windows(2)
        .filter(|w| w[0] == name)
        .map(|w| w[1].clone())
        .collect()
}

/// `--variant KEY=V,KEY=V` (repeatable): the `--set`s of each column; none
/// given, the pipeline as it is. Rendered interleaved in one run, so the
/// columns see the same machine load.
fn variants() -> Vec<Vec<String>> {
    let given: Vec<Vec<String>> = args("--variant")
        .iter()
        .map(|v| v.split(',').map(|s| s.trim().to_string()).collect())
        .collect();
    if given.is_empty() {
        vec![Vec::new()]
    } else {
        given
    }
}

fn main() {
    let repeats: usize = arg("--repeats")
        .and_then(|s| s.parse().ok())
        .unwrap_or(1)
        .max(1);
    let size = size_arg((320, 240));
    let counts: Vec<u64> = arg("--segments")
        .map(|s| s.split(',').filter_map(|n| n.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![75_000, 150_000, 300_000, 600_000, 1_200_000, 2_000_000]);
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    if !gpu.capabilities.timestamps {
        eprintln!("{} has no timestamp queries", gpu.adapter_name());
        return;
    }
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let variants = variants();
    let scenes: Vec<SceneData> = counts.iter().map(|&n| scene_with(n)).collect();
    // prepared[v][s]: variant v on groom s.
    let prepared: Vec<Vec<Prepared>> = variants
        .iter()
        .map(|sets| {
            scenes
                .iter()
                .map(|s| {
                    prepare(&gpu, &pipeline, sets, s, size)
                        .unwrap_or_else(|e| panic!("{sets:?}: {e}"))
                })
                .collect()
        })
        .collect();
    let mut times = vec![vec![Vec::new(); scenes.len()]; variants.len()];
    for repeat in 0..=repeats {
        for s in 0..scenes.len() {
            for (v, column) in prepared.iter().enumerate() {
                let report = column[s].render().unwrap_or_else(|e| panic!("{e}"));
                if repeat > 0 {
                    times[v][s].push(report.report.total_gpu_ms.unwrap_or(f64::NAN));
                }
            }
        }
    }
    println!(
        "occupancy.toml, default scene's groom scaled ({SEGMENTS_PER_STRAND} segments per strand), {}x{}, light maps 512², median of {repeats} interleaved repeats after one warm-up, on {} ({})",
        size.0,
        size.1,
        gpu.adapter_name(),
        gpu.backend_name()
    );
    println!();
    let name = |sets: &Vec<String>| {
        if sets.is_empty() {
            "as is".to_string()
        } else {
            sets.join(" ")
        }
    };
    let mut header = "| segments | strands |".to_string();
    let mut rule = "|---:|---:|".to_string();
    for sets in &variants {
        header += &format!(" {}: frame GPU ms | ms per million segments |", name(sets));
        rule += "---:|---:|";
    }
    // Each further column's frame over the first's, row by row: the columns
    // ran interleaved on the same groom, so this ratio is what a published
    // comparison re-checks (a `ratio` column), not their milliseconds.
    for v in 1..variants.len() {
        header += &format!(" column {} ÷ column 1 |", v + 1);
        rule += "---:|";
    }
    println!("{header}\n{rule}");
    let mut points = vec![Vec::new(); variants.len()];
    for (i, s) in scenes.iter().enumerate() {
        let segments = s.strands.segment_count() as f64;
        let mut row = format!(
            "| {} | {} |",
            s.strands.segment_count(),
            s.strands.strand_count()
        );
        for (v, column) in times.iter().enumerate() {
            let ms = median(&column[i]);
            points[v].push((segments, ms));
            row += &format!(" {ms:.0} | {:.0} |", ms / segments * 1e6);
        }
        let first = median(&times[0][i]);
        for column in times.iter().skip(1) {
            row += &format!(" {:.2} |", median(&column[i]) / first);
        }
        println!("{row}");
    }
    for (sets, points) in variants.iter().zip(&points) {
        if points.len() >= 2 {
            let (a, b, r2) = fit(points);
            println!();
            println!(
                "fit ({}): frame ms = {a:.1} + {:.1} per million segments, R² = {r2:.4}",
                name(sets),
                b * 1e6
            );
        }
    }
    let prepared = &prepared[0];
    let per_segment = bytes_per_segment();
    let fixed = prepared
        .first()
        .map(|p| p.schedule().memory.peak_bytes)
        .unwrap_or(0);
    println!(
        "memory: {per_segment:.1} bytes per segment of hair geometry ({} B per vertex), plus {:.1} MiB of pipeline resources at this size, whatever the hair",
        std::mem::size_of::<StrandVertex>(),
        fixed as f64 / (1 << 20) as f64
    );
    // The vertex buffer is the largest allocation that grows with the hair.
    let max_buffer = gpu.device.limits().max_buffer_size;
    let vertex_bytes_per_segment = std::mem::size_of::<StrandVertex>() as f64
        * (SEGMENTS_PER_STRAND as f64 + 1.0)
        / SEGMENTS_PER_STRAND as f64;
    let largest = (max_buffer as f64 / vertex_bytes_per_segment) as u64
        / SEGMENTS_PER_STRAND as u64
        * SEGMENTS_PER_STRAND as u64;
    println!(
        "the adapter's max_buffer_size ({} MiB) allows a vertex buffer of up to {largest} segments",
        max_buffer >> 20
    );
    if std::env::args().any(|a| a == "--largest") {
        // Doubling from the largest measured groom until a frame fails, the
        // buffer limit is reached or a frame takes longer than --max-seconds.
        let max_ms = arg("--max-seconds")
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(120.0)
            * 1e3;
        let mut segments = counts.iter().copied().max().unwrap_or(2_000_000) * 2;
        while segments <= largest {
            let scene = scene_with(segments);
            let result = prepare(&gpu, &pipeline, &variants[0], &scene, size)
                .map_err(|e| e.to_string())
                .and_then(|p| p.render().map_err(|e| e.to_string()));
            match result {
                Ok(r) => {
                    let ms = r.report.total_gpu_ms.unwrap_or(f64::NAN);
                    println!("rendered {segments} segments: {ms:.0} ms");
                    if ms > max_ms {
                        println!("stopping: a frame took more than {:.0} s", max_ms / 1e3);
                        break;
                    }
                }
                Err(e) => {
                    println!("{segments} segments did not render: {e}");
                    break;
                }
            }
            segments *= 2;
        }
    }
}
