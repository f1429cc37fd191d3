//! Each gallery pipeline against its raster floor, side by side in one process:
//! `cargo bench -p plait --bench floor [-- --size WxH --repeats N --scene FILE --only a,b --set KEY=VALUE… --save DIR --one-draw --side plait|floor]`
//! (`-- --help` lists the flags; `support/floor_args.rs` reads them).
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
//! `--set KEY=VALUE` (repeatable, checked by the same loader as `plait
//! render --set`) adds, beside each pipeline chosen, a row of it rendered
//! with the sets against the floor of that row's own compiled schedule, so
//! `--only occupancy --set techniques.shading_space=strand` puts fragment-
//! and strand-space shading side by side in one run. The hand-written
//! program is the default pipeline as it is: it is compared with the
//! `occupancy` row only, and the output says so for a `--set` row.
//! A benchmark, not a test: nothing here fails on a slow machine.

mod support;

use std::path::{Path, PathBuf};

use plait::gpu::Gpu;
use plait::gpu::geometry::SceneGeometry;
use plait::session::{Prepared, SceneData, prepare, repo_root};
use support::floor::Floor;
use support::floor_args::{self, Side};
use support::handwritten::HandWritten;
use support::timing::median;

struct Entry<'g> {
    /// The row's label: the pipeline's name, then its `--set` flags.
    name: String,
    /// The pipeline (file stem, or `occupancy_one_draw`) the row renders.
    base: String,
    /// The user's `--set` flags applied to it (none for the plain row).
    sets: Vec<String>,
    prepared: Prepared<'g>,
    floor: Floor<'g>,
    plait_ms: Vec<f64>,
    floor_ms: Vec<f64>,
    plait_passes: Vec<Vec<f64>>,
    floor_passes: Vec<Vec<f64>>,
}

/// A row to render: a gallery pipeline, with the user's `--set`s or not.
struct Row {
    label: String,
    base: String,
    path: PathBuf,
    /// Every set the row applies (`--one-draw`'s, then the user's).
    sets: Vec<String>,
    user_sets: Vec<String>,
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

/// A bad flag or `--set`: the message, exit code 2 (as `plait`'s own).
fn usage_error(message: &str) -> ! {
    eprintln!("{message}");
    std::process::exit(2);
}

fn gallery_names(root: &Path) -> Vec<String> {
    gallery(root)
        .iter()
        .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .collect()
}

fn main() {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let args = floor_args::parse(&argv).unwrap_or_else(|e| usage_error(&format!("error: {e}")));
    if args.help {
        println!("{}", floor_args::USAGE);
        return;
    }
    let repeats = args.repeats;
    // Small by default (14 pipelines, each with its floor); the book's figures use 320x240.
    let size = args.size;
    let only = args.only.clone();
    let side = args.side;
    let (render_plait, render_floor) = match side {
        Side::Both => (true, true),
        Side::Plait => (true, false),
        Side::Floor => (false, true),
    };
    let root = repo_root();
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
    if args.one_draw {
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
    variants.retain(|(name, ..)| only.as_ref().is_none_or(|o| o.contains(name)));
    if let Some(o) = &only {
        // A name that matches no pipeline is a mistake, not an empty run.
        let known = gallery_names(&root);
        if let Some(name) = o.iter().find(|n| !variants.iter().any(|(v, ..)| v == *n)) {
            let hint = plait::graph::suggest::nearest(name, known.iter().map(String::as_str))
                .map(|n| format!("; did you mean `{n}`?"))
                .unwrap_or_default();
            usage_error(&format!(
                "error: --only {name}: no such pipeline in pipelines/ (or --one-draw's occupancy_one_draw){hint}"
            ));
        }
    }
    // Every chosen pipeline, then beside it the same with the user's sets,
    // checked first without a GPU by the loader `plait render` uses.
    let mut rows = Vec::new();
    for (name, path, sets) in variants {
        if !args.sets_only {
            rows.push(Row {
                label: name.clone(),
                base: name.clone(),
                path: path.clone(),
                sets: sets.clone(),
                user_sets: Vec::new(),
            });
        }
        if args.sets.is_empty() {
            continue;
        }
        let all = [sets.as_slice(), &args.sets].concat();
        if let Err(e) = floor_args::check_sets(&path, &all) {
            usage_error(&format!(
                "{e}\n(pipeline `{name}`, {}, with {})",
                path.strip_prefix(&root).unwrap_or(&path).display(),
                floor_args::label("", &args.sets).trim()
            ));
        }
        rows.push(Row {
            label: floor_args::label(&name, &args.sets),
            base: name,
            path,
            sets: all,
            user_sets: args.sets.clone(),
        });
    }
    let scene_path = args.scene.clone();
    let scene = SceneData::load(scene_path.as_deref())
        .unwrap_or_else(|e| usage_error(&format!("error: {e}")));
    let gpu = Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    if !gpu.capabilities.timestamps {
        eprintln!(
            "{} has no timestamp queries: no GPU times to compare",
            gpu.adapter_name()
        );
        return;
    }
    let library = plait::passes::read_library(&[]);
    let mut entries = Vec::new();
    for row in rows {
        let name = row.label;
        let prepared = match prepare(&gpu, &row.path, &row.sets, &scene, size) {
            Ok(p) => p,
            // A row the user asked for with --set cannot be left out quietly.
            Err(e) if !row.user_sets.is_empty() => {
                let e = e.to_string();
                let e = e.strip_prefix("error: ").unwrap_or(&e);
                usage_error(&format!("error: row `{name}`: {e}"))
            }
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
            base: row.base,
            sets: row.user_sets,
            prepared,
            floor,
            plait_ms: Vec::new(),
            floor_ms: Vec::new(),
            plait_passes: vec![Vec::new(); passes],
            floor_passes: vec![Vec::new(); passes],
        });
    }
    if let Some(dir) = &args.save {
        // Each pipeline's image, to compare shader changes bit for bit.
        std::fs::create_dir_all(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
        for e in &entries {
            e.prepared
                .render()
                .unwrap_or_else(|err| panic!("{}: {err}", e.name));
            let image = e.prepared.image().unwrap_or_else(|err| panic!("{err}"));
            let path = dir.join(format!("{}.png", floor_args::file_stem(&e.name)));
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
                .render()
                .unwrap_or_else(|err| panic!("{}: {err}", e.name));
            e.prepared.image().unwrap_or_else(|err| panic!("{err}"))
        };
        if image(&entries[a]) != image(&entries[b]) {
            panic!("building the maps in one draw changed the default pipeline's image");
        }
    }
    let handwritten = default_index.filter(|_| side == Side::Both).map(|i| {
        let hw = HandWritten::new(&gpu, &scene, size).unwrap_or_else(|e| panic!("{e}"));
        // Same passes, same shaders: the same picture, or the comparison means nothing.
        entries[i]
            .prepared
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
        "gallery pipelines on {} ({} strands, {} segments) at {}x{}, median of {repeats} interleaved repeats after one warm-up, on {} ({})",
        scene_path
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_else(|| "the default scene".into()),
        scene.strands.strand_count(),
        scene.strands.segment_count(),
        size.0,
        size.1,
        gpu.adapter_name(),
        gpu.backend_name()
    );
    for e in entries
        .iter()
        .filter(|e| e.base == "occupancy" && !e.sets.is_empty())
    {
        // Never silently: say which rows the hand-written program is not compared with.
        println!(
            "`{}`: no hand-written comparison — the hand-written program is the default pipeline as it is (its image is compared with the `occupancy` row's), and --set changes the schedule",
            e.name
        );
    }
    for repeat in 0..=repeats {
        for (k, e) in entries.iter_mut().enumerate() {
            let report = render_plait.then(|| {
                e.prepared
                    .render()
                    .unwrap_or_else(|err| panic!("{}: {err}", e.name))
                    .report
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
        // A --set row of the default pipeline: not compared (said above).
        let not_compared = e.base == "occupancy" && !e.sets.is_empty();
        let blank = if not_compared { "—" } else { "" };
        println!(
            "| {} | {p:.1} | {f:.1} | {:.2}× | {} | {} |",
            e.name,
            p / f,
            hw.map(|h| format!("{h:.1}"))
                .unwrap_or_else(|| blank.into()),
            hw.map(|h| format!("{:.3}×", p / h))
                .unwrap_or_else(|| blank.into()),
        );
    }
    let names = handwritten
        .as_ref()
        .map(|h| h.draw_names())
        .unwrap_or_default();
    // The default pipeline pass by pass, and each of its --set rows.
    for (i, e) in entries
        .iter()
        .enumerate()
        .filter(|(_, e)| e.base == "occupancy")
    {
        let hand = Some(i) == default_index;
        println!();
        println!("`{}` pass by pass (median GPU ms):", e.name);
        println!();
        if hand {
            println!("| pass | plait | floor | plait / floor | hand-written |");
            println!("|---|---:|---:|---:|---:|");
        } else {
            println!("| pass | plait | floor | plait / floor |");
            println!("|---|---:|---:|---:|");
        }
        for (k, pass) in e.prepared.schedule().passes.iter().enumerate() {
            let (p, f) = (median(&e.plait_passes[k]), median(&e.floor_passes[k]));
            let row = format!("| {} | {p:.1} | {f:.1} | {:.2}× |", pass.name, p / f);
            if hand {
                // The hand-written program times each draw; a pass is the sum of its draws.
                let hw: f64 = names
                    .iter()
                    .zip(&hw_draws)
                    .filter(|(n, _)| **n == pass.name)
                    .map(|(_, v)| median(v))
                    .sum();
                println!("{row} {hw:.1} |");
            } else {
                println!("{row}");
            }
        }
    }
}
