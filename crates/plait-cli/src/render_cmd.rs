//! `plait render`: one pipeline, one scene, one PNG, a per-pass table; with
//! `--frames`, a sequence ([`crate::sequence`]).

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use plait::session::{SceneData, compile_checked, prepare, resolve_pipeline};
use plait_gpu::{FrameReport, Gpu};
use plait_graph::{CompileOptions, Schedule};
use plait_hair::scene::Scene;

use crate::args::{SetArgs, parse_scene, parse_size};
use crate::output::PendingFile;

#[derive(Args)]
pub struct RenderArgs {
    /// Pipeline file (default: pipelines/occupancy.toml, the occupancy-map method).
    pipeline: Option<PathBuf>,
    /// Scene file (default: the built-in scene).
    #[arg(long, value_parser = parse_scene)]
    scene: Option<PathBuf>,
    /// Where to write the image: a .png, or a .jpg/.jpeg file (default
    /// plait.png). With --frames, a folder (default frames/).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Render size, `WIDTHxHEIGHT` (a lowercase or capital x).
    #[arg(long, value_parser = parse_size, default_value = "960x720")]
    size: (u32, u32),
    /// Write this texture resource instead of the pipeline's output (look at
    /// any intermediate: a light map, the hair image, …). Colour in 0…1 is
    /// encoded to sRGB; other values (depths, ranges, counts) are mapped from
    /// their smallest to their largest value, which a note reports.
    #[arg(long, value_name = "RESOURCE")]
    show: Option<String>,
    /// Print one JSON object on standard output instead of the table.
    #[arg(long)]
    json: bool,
    /// Render again on every save of the pipeline, a file it extends, a
    /// shader it uses or the scene, until interrupted (Ctrl-C).
    #[arg(long)]
    watch: bool,
    /// Render an animated sequence of this many frames into the folder
    /// --out: 0000.png …, animation.png (an animated PNG preview) and
    /// frames.json; the table shows per-pass medians over the frames.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100000), conflicts_with_all = ["show", "watch"])]
    frames: Option<u32>,
    /// Frames per second of the sequence: frame i is at time i / fps (the
    /// scene's [animation]).
    #[arg(long, value_parser = crate::sequence::parse_fps, default_value = "30", requires = "frames")]
    fps: f32,
    #[command(flatten)]
    set: SetArgs,
}

/// A rendered frame with everything the report needs.
pub struct Rendered {
    pub schedule: Schedule,
    pub report: FrameReport,
    pub image: image::RgbaImage,
    pub adapter: String,
    pub backend: String,
    /// What the renderer adapted to the adapter (format downgrades…).
    pub notes: Vec<String>,
}

pub fn load_scene(path: Option<&Path>) -> Result<Scene> {
    match path {
        Some(p) => Ok(Scene::load(p)?),
        None => Ok(Scene::builtin_default()),
    }
}

/// Render `pipeline` on `scene` at `size`: compile and check without the GPU
/// first, then open the device, build, render, read the first output (or the
/// texture `show` names, checked before any GPU work).
pub fn render(
    pipeline: &Path,
    sets: &[String],
    scene: &Scene,
    size: (u32, u32),
    show: Option<&str>,
) -> Result<Rendered> {
    let mut sets = sets.to_vec();
    if let Some(name) = show {
        let loaded = plait_graph::load(pipeline, &sets)?;
        crate::show::check_name(&loaded, name)?;
        sets.push(crate::show::extra_output_set(&loaded, name));
    }
    // Everything that can fail without a GPU fails before one is opened.
    // The adapter's texture limit is checked once the device is open.
    let checked = compile_checked(
        pipeline,
        &sets,
        &CompileOptions {
            screen: size,
            max_texture_dimension: u32::MAX,
            max_buffer_binding_size: u64::MAX,
        },
    )?;
    if let Some(name) = show {
        crate::show::check_readable(&checked, name)?;
    }
    let data = SceneData::new(scene.clone())?;
    let gpu = Gpu::new()?;
    let mut prepared = prepare(&gpu, pipeline, &sets, &data, size)?;
    if let Some(name) = show {
        prepared.output = name.to_owned();
    }
    // The first frame includes pipeline warm-up in the driver; time the second.
    prepared.renderer.render()?;
    let report = prepared.renderer.render()?;
    plait::overflow::check_frame(&report)?;
    let mut notes = prepared.renderer.notes().to_vec();
    let image = match show {
        Some(name) => {
            let texels = prepared.renderer.read_resource(name)?;
            let (image, note) = crate::show::picture(name, &texels);
            notes.extend(note);
            image
        }
        None => prepared.image()?,
    };
    Ok(Rendered {
        schedule: prepared.schedule().clone(),
        report,
        image,
        adapter: gpu.adapter_name().to_owned(),
        backend: gpu.backend_name(),
        notes,
    })
}

pub fn run(args: RenderArgs) -> Result<()> {
    if let Some(frames) = args.frames {
        let pipeline = resolve_pipeline(args.pipeline.as_deref());
        let scene = load_scene(args.scene.as_deref())?;
        let out = args
            .out
            .clone()
            .unwrap_or_else(crate::sequence::default_out);
        return crate::sequence::run(&crate::sequence::SequenceArgs {
            pipeline: &pipeline,
            sets: &args.set.sets,
            scene: &scene,
            scene_path: args.scene.as_deref(),
            size: args.size,
            frames,
            fps: args.fps,
            out: &out,
            json: args.json,
        });
    }
    if !args.watch {
        return render_once(&args);
    }
    let pipeline = resolve_pipeline(args.pipeline.as_deref());
    plait_view::watch::run_on_changes(
        || plait::session::watched_files(&pipeline, &args.set.sets, args.scene.as_deref()),
        || {
            // An error is reported and the watch goes on: fixing the file renders again.
            if let Err(e) = render_once(&args) {
                let text = crate::error_text(&e);
                let prefix = if text.starts_with("error:") {
                    ""
                } else {
                    "error: "
                };
                eprintln!("{prefix}{text}");
            }
        },
        |n| eprintln!("watching {n} files; save one to render again (Ctrl-C stops)"),
    )?;
    Ok(())
}

fn render_once(args: &RenderArgs) -> Result<()> {
    let out_path = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("plait.png"));
    let format = crate::output::image_format(&out_path, "--out")?;
    let out = PendingFile::create(&out_path, "--out")?;
    let pipeline = resolve_pipeline(args.pipeline.as_deref());
    let scene = load_scene(args.scene.as_deref())?;
    let r = render(
        &pipeline,
        &args.set.sets,
        &scene,
        args.size,
        args.show.as_deref(),
    )?;
    out.commit(&crate::output::encode_image(&r.image, format)?)?;
    for note in &r.notes {
        eprintln!("note: {note}");
    }
    if args.json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&report_json(&pipeline, &r, &out_path))?
        )?;
    } else {
        print_table(&pipeline, &r, &out_path, "frame")?;
    }
    Ok(())
}

fn names(schedule: &Schedule, bindings: &[plait_graph::Binding]) -> Vec<String> {
    bindings
        .iter()
        .map(|b| {
            schedule
                .resources
                .get(b.resource)
                .map(|r| r.name.clone())
                .unwrap_or_else(|| b.resource_name.clone())
        })
        .collect()
}

pub fn report_json(pipeline: &Path, r: &Rendered, out: &Path) -> serde_json::Value {
    let s = &r.schedule;
    let mut passes: Vec<serde_json::Value> = s
        .passes
        .iter()
        .zip(&r.report.passes)
        .map(|(p, t)| {
            serde_json::json!({
                "name": p.name, "type": p.type_name,
                "reads": names(s, &p.reads), "writes": names(s, &p.writes),
                "gpu_ms": t.gpu_ms, "culled": false, "stats": t.stats,
            })
        })
        .collect();
    passes.extend(s.culled.iter().map(|c| {
        serde_json::json!({
            "name": c.pass.name, "type": c.pass.type_name,
            "reads": names(s, &c.pass.reads), "writes": names(s, &c.pass.writes),
            "gpu_ms": null, "culled": true, "culled_reason": c.reason,
        })
    }));
    let resources: Vec<_> = s
        .resources
        .iter()
        .enumerate()
        .map(|(id, res)| {
            let (kind, format) = match &res.desc {
                plait_graph::ResourceDesc::Texture { format, .. } => {
                    ("texture", Some(format.name()))
                }
                plait_graph::ResourceDesc::Buffer { .. } => ("buffer", None),
            };
            serde_json::json!({
                "name": res.name, "kind": kind, "format": format, "desc": res.desc.label(),
                "bytes": res.desc.bytes(), "shares_memory_with": s.shares_memory_with(id),
            })
        })
        .collect();
    serde_json::json!({
        "pipeline": pipeline.display().to_string(),
        "adapter": { "name": r.adapter, "backend": r.backend },
        "size": [r.image.width(), r.image.height()],
        "passes": passes,
        "total_gpu_ms": r.report.total_gpu_ms,
        "resources": resources,
        "memory": { "peak_bytes": s.memory.peak_bytes, "unpooled_bytes": s.memory.unpooled_bytes },
        "output": out.display().to_string(),
        "notes": r.notes,
        // Every declared overflow counter, `dropped` 0 when its buffer held everything.
        "overflow": r.report.overflow,
    })
}

fn ms(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.3}")).unwrap_or_else(|| "n/a".into())
}

/// The per-pass table; `total` names the last row (`frame`, `median frame`).
pub fn print_table(pipeline: &Path, r: &Rendered, out: &Path, total: &str) -> std::io::Result<()> {
    let s = &r.schedule;
    outln!(
        "{} on {} ({}), {}x{}",
        pipeline.display(),
        r.adapter,
        r.backend,
        r.image.width(),
        r.image.height()
    )?;
    outln!("{:<20} {:<16} {:>10}", "pass", "type", "GPU ms")?;
    for (p, t) in s.passes.iter().zip(&r.report.passes) {
        outln!("{:<20} {:<16} {:>10}", p.name, p.type_name, ms(t.gpu_ms))?;
    }
    for c in &s.culled {
        outln!(
            "{:<20} {:<16} {:>10}  ({})",
            c.pass.name,
            c.pass.type_name,
            "culled",
            c.reason
        )?;
    }
    outln!("{:<20} {:<16} {:>10}", total, "", ms(r.report.total_gpu_ms))?;
    if r.report.total_gpu_ms.is_none() {
        outln!("(this adapter has no timestamp queries: GPU times are not available)")?;
    }
    outln!(
        "memory: {:.2} MiB in {} allocations ({:.2} MiB without sharing)",
        s.memory.peak_bytes as f64 / 1048576.0,
        s.physical.len(),
        s.memory.unpooled_bytes as f64 / 1048576.0
    )?;
    print_dropped(&r.report)?;
    outln!("wrote {}", out.display())
}

/// One line per bounded buffer that dropped data (only a size the user set
/// can: the session grows the defaults until they hold everything).
fn print_dropped(report: &FrameReport) -> std::io::Result<()> {
    for o in report.dropped() {
        outln!(
            "dropped: {o} (a size set by --set or the pipeline file is a cap; left unset, it grows to hold everything)"
        )?;
    }
    Ok(())
}
