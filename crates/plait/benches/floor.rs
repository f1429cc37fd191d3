//! Each gallery pipeline against its raster floor, side by side in one process:
//! `cargo bench -p plait --bench floor [-- --size WxH --repeats N --scene FILE --only a,b --save DIR --one-draw --side plait|floor]`.
//!
//! For every `pipelines/*.toml` it renders, in interleaved repeats, (a) the
//! pipeline through plait, (b) its floor — the same passes, targets, clears
//! and draw calls over the same geometry with trivial shaders
//! (`support/floor.rs`) — and, for the default pipeline, (c) the same passes
//! written by hand against wgpu without plait's executor
//! (`support/handwritten/`, whose image must equal plait's). It prints the
//! median frame GPU time of each, the ratios, and the default pipeline pass
//! by pass. `--one-draw` adds the default pipeline with occupancy bits and
//! slab counts built in one draw per view (`occupancy_slabs`). Depth peeling (`depth_peeling.toml`, `reference.toml`) is left
//! out: its work depends on the layers it finds, so it has no fixed floor.
//! `--side plait` or `--side floor` renders only that side (no hand-written
//! program): one process per side, to profile each under `perf record`
//! (the book's Performance page, "where the time goes").
//! A benchmark, not a test: nothing here fails on a slow machine.

mod support;

use std::path::{Path, PathBuf};

use plait::gpu::Gpu;
use plait::gpu::geometry::SceneGeometry;
use plait::session::{Prepared, SceneData, prepare, repo_root};
use support::floor::Floor;
use support::handwritten::HandWritten;
use support::timing::{arg, median, size_arg};

struct Entry<'g> {
    name: String,
    prepared: Prepared<'g>,
    floor: Floor<'g>,
    plait_ms: Vec<f64>,
    floor_ms: Vec<f64>,
    plait_passes: Vec<Vec<f64>>,
    floor_passes: Vec<Vec<f64>>,
}

fn gallery(root: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root.join("pipelines"))
        .unwrap_or_else(|e| panic!("pipelines/: {e}"))
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

fn main() {
    let repeats: usize = arg("--repeats")
        .and_then(|s| s.parse().ok())
        .unwrap_or(3)
        .max(1);
    // Small by default (14 pipelines, each with its floor); the book's figures use 320x240.
    let size = size_arg((160, 120));
    let only: Option<Vec<String>> =
        arg("--only").map(|s| s.split(',').map(|n| n.trim().to_owned()).collect());
    let side = arg("--side");
    let (render_plait, render_floor) = match side.as_deref() {
        None => (true, true),
        Some("plait") => (true, false),
        Some("floor") => (false, true),
        Some(other) => panic!("--side {other}: expected `plait` or `floor`"),
    };
    let root = repo_root();
    let scene_path = arg("--scene").map(PathBuf::from);
    let scene = SceneData::load(scene_path.as_deref()).unwrap_or_else(|e| panic!("{e}"));
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    if !gpu.capabilities.timestamps {
        eprintln!(
            "{} has no timestamp queries: no GPU times to compare",
            gpu.adapter_name()
        );
        return;
    }
    let library = plait::passes::library();
    let mut entries = Vec::new();
    let mut variants: Vec<(String, PathBuf, Vec<String>)> = gallery(&root)
        .into_iter()
        .map(|path| {
            let name = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            (name, path, Vec::new())
        })
        .collect();
    if std::env::args().any(|a| a == "--one-draw") {
        // The default pipeline with occupancy bits and slab counts built in
        // one draw per view (`occupancy_slabs`): its image must not change.
        let mut sets = Vec::new();
        for view in ["light", "camera"] {
            sets.push(format!("passes.{view}_occupancy.type=occupancy_slabs"));
            sets.push(format!("passes.{view}_occupancy.writes.slabs={view}_slabs"));
            sets.push(format!("passes.{view}_slabs.enabled=false"));
        }
        variants.push((
            "occupancy_one_draw".into(),
            root.join("pipelines/occupancy.toml"),
            sets,
        ));
    }
    for (name, path, sets) in variants {
        if only.as_ref().is_some_and(|o| !o.contains(&name)) {
            continue;
        }
        let prepared = match prepare(&gpu, &path, &sets, &scene, size) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("{name}: not rendered: {e}");
                continue;
            }
        };
        let geometry = SceneGeometry::upload(&gpu.device, &scene.strands, &scene.meshes);
        let frame = scene.frame(size, 0);
        let floor = match Floor::new(&gpu, prepared.schedule(), &library, geometry, &frame) {
            Ok(f) => f,
            Err(e) => {
                eprintln!("{name}: left out: {e}");
                continue;
            }
        };
        let passes = prepared.schedule().passes.len();
        entries.push(Entry {
            name,
            prepared,
            floor,
            plait_ms: Vec::new(),
            floor_ms: Vec::new(),
            plait_passes: vec![Vec::new(); passes],
            floor_passes: vec![Vec::new(); passes],
        });
    }
    if let Some(dir) = arg("--save") {
        // Each pipeline's image, to compare shader changes bit for bit.
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{dir}: {e}"));
        for e in &entries {
            e.prepared
                .renderer
                .render()
                .unwrap_or_else(|err| panic!("{}: {err}", e.name));
            let image = e.prepared.image().unwrap_or_else(|err| panic!("{err}"));
            let path = Path::new(&dir).join(format!("{}.png", e.name));
            image
                .save(&path)
                .unwrap_or_else(|err| panic!("{}: {err}", path.display()));
        }
    }
    let default_index = entries.iter().position(|e| e.name == "occupancy");
    let one_draw_index = entries.iter().position(|e| e.name == "occupancy_one_draw");
    if let (Some(a), Some(b)) = (default_index, one_draw_index) {
        let image = |e: &Entry| {
            e.prepared
                .renderer
                .render()
                .unwrap_or_else(|err| panic!("{}: {err}", e.name));
            e.prepared.image().unwrap_or_else(|err| panic!("{err}"))
        };
        if image(&entries[a]) != image(&entries[b]) {
            panic!("building the maps in one draw changed the default pipeline's image");
        }
    }
    let handwritten = default_index.filter(|_| side.is_none()).map(|i| {
        let hw = HandWritten::new(&gpu, &scene, size).unwrap_or_else(|e| panic!("{e}"));
        // Same passes, same shaders: the same picture, or the comparison means nothing.
        entries[i]
            .prepared
            .renderer
            .render()
            .unwrap_or_else(|e| panic!("{e}"));
        hw.render();
        let ours = entries[i]
            .prepared
            .image()
            .unwrap_or_else(|e| panic!("{e}"));
        let theirs = hw.image().unwrap_or_else(|e| panic!("{e}"));
        let differing = ours
            .as_raw()
            .iter()
            .zip(theirs.as_raw())
            .filter(|(a, b)| a != b)
            .count();
        if differing > 0 {
            panic!(
                "the hand-written default pipeline's image differs from plait's in {differing} bytes"
            );
        }
        hw
    });
    let mut hw_ms = Vec::new();
    let mut hw_draws: Vec<Vec<f64>> = Vec::new();
    println!(
        "{} on the default scene ({} strands, {} segments) at {}x{}, median of {repeats} interleaved repeats after one warm-up, on {} ({})",
        if scene_path.is_some() {
            "gallery"
        } else {
            "gallery pipelines"
        },
        scene.strands.strand_count(),
        scene.strands.segment_count(),
        size.0,
        size.1,
        gpu.adapter_name(),
        gpu.backend_name()
    );
    for repeat in 0..=repeats {
        for (k, e) in entries.iter_mut().enumerate() {
            let report = render_plait.then(|| {
                e.prepared
                    .renderer
                    .render()
                    .unwrap_or_else(|err| panic!("{}: {err}", e.name))
            });
            let (floor_total, floor_passes) = if render_floor {
                e.floor.render().unwrap_or_default()
            } else {
                (f64::NAN, vec![f64::NAN; e.floor_passes.len()])
            };
            // The hand-written program right after the pipeline it copies.
            let hand = handwritten
                .as_ref()
                .filter(|_| Some(k) == default_index)
                .and_then(|hw| hw.render());
            if repeat == 0 {
                continue; // warm-up: pipelines compiled, caches filled
            }
            let plait_ms = report.as_ref().and_then(|r| r.total_gpu_ms);
            e.plait_ms.push(plait_ms.unwrap_or(f64::NAN));
            e.floor_ms.push(floor_total);
            for (i, times) in e.plait_passes.iter_mut().enumerate() {
                let pass = report.as_ref().and_then(|r| r.passes.get(i));
                times.push(pass.and_then(|p| p.gpu_ms).unwrap_or(f64::NAN));
            }
            for (i, ms) in floor_passes.into_iter().enumerate() {
                e.floor_passes[i].push(ms);
            }
            if let Some((total, draws)) = hand {
                hw_ms.push(total);
                hw_draws.resize(draws.len(), Vec::new());
                for (i, ms) in draws.into_iter().enumerate() {
                    hw_draws[i].push(ms);
                }
            }
        }
    }
    println!();
    println!(
        "| pipeline | plait ms | floor ms | plait / floor | hand-written wgpu ms | plait / hand-written |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    for e in &entries {
        let (p, f) = (median(&e.plait_ms), median(&e.floor_ms));
        let hw = (Some(e.name.as_str()) == default_index.map(|i| entries[i].name.as_str()))
            .then(|| median(&hw_ms));
        println!(
            "| {} | {p:.1} | {f:.1} | {:.2}× | {} | {} |",
            e.name,
            p / f,
            hw.map(|h| format!("{h:.1}")).unwrap_or_else(|| "".into()),
            hw.map(|h| format!("{:.3}×", p / h))
                .unwrap_or_else(|| "".into()),
        );
    }
    if let Some(i) = default_index {
        let e = &entries[i];
        let names = handwritten
            .as_ref()
            .map(|h| h.draw_names())
            .unwrap_or_default();
        println!();
        println!("occupancy.toml pass by pass (median GPU ms):");
        println!();
        println!("| pass | plait | floor | plait / floor | hand-written |");
        println!("|---|---:|---:|---:|---:|");
        for (k, pass) in e.prepared.schedule().passes.iter().enumerate() {
            let (p, f) = (median(&e.plait_passes[k]), median(&e.floor_passes[k]));
            // The hand-written program times each draw; a pass is the sum of its draws.
            let hw: f64 = names
                .iter()
                .zip(&hw_draws)
                .filter(|(n, _)| **n == pass.name)
                .map(|(_, v)| median(v))
                .sum();
            println!(
                "| {} | {p:.1} | {f:.1} | {:.2}× | {hw:.1} |",
                pass.name,
                p / f
            );
        }
    }
}
