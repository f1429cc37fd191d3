//! A long run in one process (issue 14): render N frames of a pipeline,
//! reading every frame back as a program showing it would, and sample the
//! process's resident memory and the GPU allocator's bytes and allocation
//! count. Memory must be flat: after a warm-up, the resident set may grow
//! by at most `--rss-bound-mib` (allocator noise, not per frame) and the
//! GPU allocations not at all. Exits 1 otherwise.
//!
//! `cargo run -p plait --example long_run -- [--frames 1000] [--size 64x48]
//!  [--scene examples/scenes/small.toml] [--pipeline pipelines/occupancy.toml]
//!  [--every 100] [--rss-bound-mib 4]`

use std::path::PathBuf;
use std::time::Instant;

use plait::gpu::Gpu;
use plait::session::{SceneData, prepare, repo_root};

/// Resident set size in bytes (Linux: `VmRSS` of /proc/self/status).
fn resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

struct Sample {
    frame: usize,
    rss: u64,
    gpu_bytes: u64,
    gpu_allocations: usize,
    gpu_blocks: usize,
}

fn sample(gpu: &Gpu, frame: usize) -> Sample {
    let report = gpu.device.generate_allocator_report();
    Sample {
        frame,
        rss: resident_bytes().unwrap_or(0),
        gpu_bytes: report.as_ref().map_or(0, |r| r.total_allocated_bytes),
        gpu_allocations: report.as_ref().map_or(0, |r| r.allocations.len()),
        gpu_blocks: report.as_ref().map_or(0, |r| r.blocks.len()),
    }
}

fn mib(b: u64) -> f64 {
    b as f64 / (1024.0 * 1024.0)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let number = |name: &str, default: usize| {
        arg(name).map_or(default, |v| {
            v.parse()
                .unwrap_or_else(|_| fail(&format!("{name} {v}: not a number")))
        })
    };
    let frames = number("--frames", 1000).max(2);
    let every = number("--every", 100).max(1);
    let bound = number("--rss-bound-mib", 4) as u64 * 1024 * 1024;
    let size = arg("--size").map_or((64, 48), |s| {
        s.split_once('x')
            .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
            .unwrap_or_else(|| fail(&format!("--size {s}: not WIDTHxHEIGHT")))
    });
    let root = repo_root();
    let path = |flag: &str, default: &str| arg(flag).map_or(root.join(default), PathBuf::from);
    let scene_path = path("--scene", "examples/scenes/small.toml");
    let pipeline = path("--pipeline", "pipelines/occupancy.toml");

    let gpu = Gpu::new().unwrap_or_else(|e| fail(&e.to_string()));
    let scene = SceneData::load(Some(&scene_path)).unwrap_or_else(|e| fail(&e.to_string()));
    let mut prepared =
        prepare(&gpu, &pipeline, &[], &scene, size).unwrap_or_else(|e| fail(&e.to_string()));
    println!(
        "{} on {}, {}x{}, {frames} frames, each read back, on {} ({})",
        pipeline.display(),
        scene_path.display(),
        size.0,
        size.1,
        gpu.adapter_name(),
        gpu.backend_name()
    );
    println!("| frame | resident MiB | GPU allocated MiB | GPU allocations | GPU blocks |");
    println!("|---:|---:|---:|---:|---:|");
    let start = Instant::now();
    let mut samples = Vec::new();
    for frame in 0..frames {
        // A new frame index each frame (it drives the jitter), as an animation would.
        prepared.set_frame(&scene.frame(size, frame as u32));
        prepared
            .render()
            .unwrap_or_else(|e| fail(&format!("frame {frame}: {e}")));
        let image = prepared
            .image()
            .unwrap_or_else(|e| fail(&format!("frame {frame}: {e}")));
        std::hint::black_box(image);
        if frame % every == 0 || frame + 1 == frames {
            let s = sample(&gpu, frame + 1);
            println!(
                "| {} | {:.2} | {:.2} | {} | {} |",
                s.frame,
                mib(s.rss),
                mib(s.gpu_bytes),
                s.gpu_allocations,
                s.gpu_blocks
            );
            samples.push(s);
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    // The first sample is after frame 1 (pipelines built, caches warm); the
    // warm-up ends at the second.
    let warm = &samples[1.min(samples.len() - 1)];
    let last = samples.last().expect("a sample");
    let rss_growth = last.rss as i64 - warm.rss as i64;
    let gpu_growth = last.gpu_bytes as i64 - warm.gpu_bytes as i64;
    let span = (last.frame - warm.frame).max(1);
    println!(
        "{frames} frames in {seconds:.1} s ({:.1} ms/frame). From frame {} to {}: resident {:+.2} MiB \
         ({:+.0} bytes/frame), GPU allocated {:+} bytes, allocations {} → {}",
        seconds * 1000.0 / frames as f64,
        warm.frame,
        last.frame,
        rss_growth as f64 / (1024.0 * 1024.0),
        rss_growth as f64 / span as f64,
        gpu_growth,
        warm.gpu_allocations,
        last.gpu_allocations,
    );
    if gpu_growth != 0 || last.gpu_allocations != warm.gpu_allocations {
        fail("GPU allocations grew: not flat");
    }
    if rss_growth > bound as i64 {
        fail(&format!(
            "resident memory grew by more than the bound of {:.0} MiB: not flat",
            mib(bound)
        ));
    }
    println!(
        "flat: GPU allocations unchanged, resident growth within {:.0} MiB",
        mib(bound)
    );
}

fn fail(message: &str) -> ! {
    eprintln!("error: {message}");
    std::process::exit(1);
}
