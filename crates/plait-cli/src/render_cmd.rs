//! `plait render`: one pipeline, one scene, one PNG, a per-pass table; with
//! `--frames`, a sequence ([`crate::sequence`]).

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use plait::session::{SceneData, prepare_compiled, resolve_pipeline};
use plait::source::PipelineSource;
use plait_gpu::{FrameReport, Gpu};
use plait_graph::Schedule;
use plait_hair::scene::Scene;

use crate::args::{SetArgs, parse_scene, parse_size};
use crate::output::PendingFile;
use crate::table::{Align, Table};

#[derive(Args)]
pub struct RenderArgs {
    /// Pipeline file (default: pipelines/occupancy.toml, the occupancy-map method).
    pipeline: Option<PathBuf>,
    /// Scene file (default: the built-in scene).
    #[arg(long, value_parser = parse_scene)]
    scene: Option<PathBuf>,
    /// Where to write the image: a .png, or a .jpg/.jpeg file (default
    /// plait.png): the displayed image, after exposure and tone mapping. An
    /// .exr file (OpenEXR, 32-bit float) holds the linear radiance before
    /// them (the pipeline's `radiance` texture; with --show, that texture's
    /// values). With --frames, a folder (default frames/).
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
    /// What the renderer adapted to the adapter (format downgrades…) and
    /// the frame's level-of-detail notes.
    pub notes: Vec<String>,
    /// Drops from a bounded buffer the user capped, one line each, as the
    /// session worded them ([`plait::frames::Frame::dropped`]).
    pub dropped: Vec<String>,
    /// The linear image as stored, when asked for (`--out x.exr`).
    pub linear: Option<image::Rgba32FImage>,
}

pub fn load_scene(path: Option<&Path>) -> Result<Scene> {
    match path {
        Some(p) => Ok(Scene::load(p)?),
        None => Ok(Scene::builtin_default()),
    }
}

/// Which float texture a render also reads back as 32-bit floats.
pub struct LinearOut<'a> {
    /// The flag that asked for it (`--out x.exr`), where an error points.
    pub flag: &'a str,
}

/// Render `source` on `scene` at `size`: load it (the texture `show`
/// names checked there), read the scene, open the device, compile once with
/// the adapter's capabilities and limits, build, render, read the first
/// output (or `show`'s texture); with `linear`, also the float values of
/// `show`'s texture or of the radiance (checked before the GPU opens).
pub fn render(
    mut source: PipelineSource,
    scene: &Scene,
    size: (u32, u32),
    show: Option<&str>,
    linear: Option<LinearOut>,
) -> Result<Rendered> {
    if let Some(name) = show {
        source = source.with_output(name, &format!("--show {name}"));
    }
    let linear_name = linear
        .as_ref()
        .map(|_| show.unwrap_or(plait::linear::RADIANCE));
    if let (Some(l), None) = (&linear, show) {
        source = source.with_output(plait::linear::RADIANCE, l.flag);
    }
    let loaded = source.load(&[])?;
    if let Some(name) = show {
        crate::show::check_name(&loaded, name)?;
    }
    if let (Some(l), None) = (&linear, show) {
        plait::linear::check_radiance(&loaded, l.flag)?;
    }
    let data = SceneData::new(scene.clone())?;
    let gpu = Gpu::new()?;
    let schedule = plait::adapter::compile_on(&gpu, &loaded, &source, size)?;
    if let Some(name) = show {
        crate::show::check_readable(&schedule, name)?;
    }
    let mut prepared = prepare_compiled(&gpu, schedule, &source, &data, size)?;
    if let Some(name) = show {
        prepared.output = name.to_owned();
    }
    // The first frame includes pipeline warm-up in the driver; time the second.
    prepared.render()?;
    let frame = prepared.render()?;
    let mut notes = prepared.notes().to_vec();
    notes.extend(frame.notes);
    let image = match show {
        Some(name) => {
            let texels = prepared.read_resource(name)?;
            let (image, note) = crate::show::picture(name, &texels);
            notes.extend(note);
            image
        }
        None => prepared.image()?,
    };
    let linear = match linear_name {
        Some(name) => Some(plait::linear::to_f32_image(&prepared.read_resource(name)?)),
        None => None,
    };
    Ok(Rendered {
        schedule: prepared.schedule().clone(),
        report: frame.report,
        dropped: frame.dropped,
        image,
        adapter: gpu.adapter_name().to_owned(),
        backend: gpu.backend_name(),
        notes,
        linear,
    })
}

/// What a render did, printed with `PLAIT_COUNT=1`: the test that holds a
/// render to one load, one compile and one read of the pass library.
struct Counts {
    loads: usize,
    compiles: usize,
    library_reads: usize,
}

impl Counts {
    fn now() -> Self {
        Counts {
            loads: plait_graph::counters::loads(),
            compiles: plait_graph::counters::compiles(),
            library_reads: plait_passes::library_reads(),
        }
    }

    fn report_since(&self) {
        if std::env::var_os("PLAIT_COUNT").is_none() {
            return;
        }
        let now = Counts::now();
        eprintln!(
            "counts: loads={} compiles={} pass_library_reads={}",
            now.loads - self.loads,
            now.compiles - self.compiles,
            now.library_reads - self.library_reads
        );
    }
}

pub fn run(args: RenderArgs) -> Result<()> {
    let counts = Counts::now();
    let result = run_counted(args);
    counts.report_since();
    result
}

fn run_counted(args: RenderArgs) -> Result<()> {
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
        let pipeline = resolve_pipeline(args.pipeline.as_deref());
        return render_once(&args, PipelineSource::new(&pipeline, &args.set.sets));
    }
    let pipeline = resolve_pipeline(args.pipeline.as_deref());
    plait_view::watch::run_on_changes(
        || {
            // A new library value per change, read once: the render and the
            // list of files to watch both come from it.
            let source = PipelineSource::new(&pipeline, &args.set.sets);
            // An error is reported and the watch goes on: fixing the file renders again.
            if let Err(e) = render_once(&args, source.clone()) {
                let text = crate::error_text(&e);
                let prefix = if text.starts_with("error:") {
                    ""
                } else {
                    "error: "
                };
                eprintln!("{prefix}{text}");
            }
            plait::session::watched_files(&source, args.scene.as_deref())
        },
        |n| eprintln!("watching {n} files; save one to render again (Ctrl-C stops)"),
    )?;
    Ok(())
}

/// One render of `source` (the resolved pipeline, its `--set` flags and the
/// library read for it) as `args` ask.
fn render_once(args: &RenderArgs, source: PipelineSource) -> Result<()> {
    let out_path = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("plait.png"));
    let format = crate::output::image_format(&out_path, "--out")?;
    let out = PendingFile::create(&out_path, "--out")?;
    let pipeline = source.path.clone();
    let scene = load_scene(args.scene.as_deref())?;
    let exr = format == image::ImageFormat::OpenExr;
    let flag = format!("--out {}", out_path.display());
    let r = render(
        source,
        &scene,
        args.size,
        args.show.as_deref(),
        exr.then_some(LinearOut { flag: &flag }),
    )?;
    let bytes = match &r.linear {
        Some(linear) => plait::linear::encode_exr(linear)?,
        None => crate::output::encode_image(&r.image, format)?,
    };
    out.commit(&bytes)?;
    for note in &r.notes {
        eprintln!("note: {note}");
    }
    if args.json {
        outln!(
            "{}",
            serde_json::to_string_pretty(&report_json(
                &pipeline,
                args.scene.as_deref(),
                &r,
                &out_path
            ))?
        )?;
    } else {
        print_table(&pipeline, args.scene.as_deref(), &r, &out_path, "frame")?;
    }
    Ok(())
}

fn names(schedule: &Schedule, bindings: &[plait_graph::Binding]) -> Vec<String> {
    bindings
        .iter()
        .map(|b| {
            b.resolved(&schedule.resources)
                .map(|r| r.name.clone())
                .unwrap_or_else(|| b.resource_name.clone())
        })
        .collect()
}

pub fn report_json(
    pipeline: &Path,
    scene: Option<&Path>,
    r: &Rendered,
    out: &Path,
) -> serde_json::Value {
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
                plait_graph::ResourceDesc::AccelerationStructure => {
                    ("acceleration_structure", None)
                }
            };
            serde_json::json!({
                "name": res.name, "kind": kind, "format": format, "desc": res.desc.label(),
                "bytes": res.desc.bytes(), "shares_memory_with": s.shares_memory_with(plait_graph::ResourceId::new(id)),
            })
        })
        .collect();
    serde_json::json!({
        "pipeline": pipeline.display().to_string(),
        // `null` for the built-in default scene.
        "scene": scene.map(|p| p.display().to_string()),
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

/// The scene file as found on the search path, or the built-in one.
pub fn scene_words(scene: Option<&Path>) -> String {
    scene.map_or_else(
        || "the built-in default (no --scene)".to_string(),
        |p| p.display().to_string(),
    )
}

fn ms(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.3}")).unwrap_or_else(|| "n/a".into())
}

/// The per-pass table; `total` names the last row (`frame`, `median frame`).
/// Its columns are as wide as their content ([`Table`]); a new section is a
/// line before or after it.
pub fn print_table(
    pipeline: &Path,
    scene: Option<&Path>,
    r: &Rendered,
    out: &Path,
    total: &str,
) -> std::io::Result<()> {
    let s = &r.schedule;
    outln!(
        "{} on {} ({}), {}x{}",
        pipeline.display(),
        r.adapter,
        r.backend,
        r.image.width(),
        r.image.height()
    )?;
    outln!("scene: {}", scene_words(scene))?;
    // The techniques in effect, `--set techniques.…` swaps included: the
    // file named above says only what it chooses itself.
    if !s.techniques.is_empty() {
        let chosen: Vec<String> = s.techniques.iter().map(|t| t.label()).collect();
        outln!("techniques: {}", chosen.join(", "))?;
    }
    let technique = |p: &plait_graph::ScheduledPass| p.technique.clone().unwrap_or_default();
    let mut table = Table::new(&[
        ("pass", Align::Left),
        ("type", Align::Left),
        ("technique", Align::Left),
        ("GPU ms", Align::Right),
    ]);
    for (p, t) in s.passes.iter().zip(&r.report.passes) {
        table.row(vec![
            p.name.clone(),
            p.type_name.clone(),
            technique(p),
            ms(t.gpu_ms),
        ]);
    }
    for c in &s.culled {
        table.row_with_note(
            vec![
                c.pass.name.clone(),
                c.pass.type_name.clone(),
                technique(&c.pass),
                "culled".into(),
            ],
            format!("({})", c.reason),
        );
    }
    table.row(vec![
        total.to_owned(),
        String::new(),
        String::new(),
        ms(r.report.total_gpu_ms),
    ]);
    for line in table.lines() {
        outln!("{line}")?;
    }
    if r.report.total_gpu_ms.is_none() {
        outln!("(this adapter has no timestamp queries: GPU times are not available)")?;
    }
    outln!("{}", memory_line(&s.memory, s.physical.len()))?;
    // One line per bounded buffer that dropped data (only a size the user
    // set can: the session grows the defaults until they hold everything).
    for line in &r.dropped {
        outln!("{line}")?;
    }
    outln!("wrote {}", out.display())
}

/// `memory: 20.00 MiB in 9 allocations (sharing saves 9.41 MiB of 29.41 MiB)`;
/// when no two resources share an allocation there is no saving to state.
fn memory_line(memory: &plait_graph::MemoryReport, allocations: usize) -> String {
    let mib = |b: u64| b as f64 / 1048576.0;
    let plural = if allocations == 1 { "" } else { "s" };
    let mut line = format!(
        "memory: {:.2} MiB in {allocations} allocation{plural}",
        mib(memory.peak_bytes)
    );
    if memory.unpooled_bytes > memory.peak_bytes {
        line.push_str(&format!(
            " (sharing saves {:.2} MiB of {:.2} MiB)",
            mib(memory.unpooled_bytes - memory.peak_bytes),
            mib(memory.unpooled_bytes)
        ));
    } else {
        line.push_str(" (no two resources share one)");
    }
    line
}
