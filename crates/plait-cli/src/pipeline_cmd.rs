//! `plait check`, `plait graph`, `plait passes`: everything that needs no GPU.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use plait::session::{compile_checked_in, resolve_pipeline};
use plait_graph::{
    CompileOptions, Formats, ParamType, PassShape, PassTypeSpec, ResourceKind, SlotSpec,
};

use crate::args::SetArgs;
use crate::output::PendingFile;

#[derive(Args)]
pub struct CheckArgs {
    /// Pipeline files to validate.
    #[arg(required = true)]
    pipelines: Vec<PathBuf>,
    #[command(flatten)]
    set: SetArgs,
    /// Also check them against the GPU adapter `plait render` opens (texture
    /// formats, downlevel flags, limits) at render's default size, 960x720.
    #[arg(long)]
    adapter: bool,
    /// With --adapter: the scene whose hair a ray-traced technique puts in an
    /// acceleration structure, checked against the adapter's BLAS primitive
    /// limit (default: the built-in scene, as `plait render`).
    #[arg(long, value_parser = crate::args::parse_scene, requires = "adapter")]
    scene: Option<PathBuf>,
}

pub fn check(args: CheckArgs) -> Result<()> {
    // Plain `check` needs no GPU; `--adapter` opens the one render would.
    let gpu = args.adapter.then(plait_gpu::Gpu::new).transpose()?;
    let mut failures = Vec::new();
    // A gallery name (`forward.toml`) is found on the library search path,
    // as `plait render` finds it.
    let paths: Vec<PathBuf> = args
        .pipelines
        .iter()
        .map(|given| resolve_pipeline(Some(given)))
        .collect();
    // One library for every pipeline checked together: two whose own
    // folders declare one module are an error naming both files.
    let library =
        plait_passes::library_for(&paths.iter().map(PathBuf::as_path).collect::<Vec<_>>());
    // The scene's hair size, read once and only if a pipeline needs it.
    let mut hair = None;
    for path in &paths {
        let checked = match &gpu {
            Some(gpu) => {
                plait::adapter::check_on_adapter(gpu, &library, path, &args.set.sets, (960, 720))
                    .map_err(anyhow::Error::from)
                    .and_then(|s| {
                        structure_fits(&s, gpu, &mut hair, args.scene.as_deref())?;
                        Ok(s)
                    })
            }
            None => compile_checked_in(&library, path, &args.set.sets, &CompileOptions::default())
                .map_err(anyhow::Error::from),
        };
        match checked {
            Ok(s) => {
                let culled = if s.culled.is_empty() {
                    String::new()
                } else {
                    format!(", {} culled", s.culled.len())
                };
                let on = gpu.as_ref().map_or(String::new(), |g| {
                    format!(", runs on adapter {}", g.support.describe())
                });
                outln!(
                    "ok  {}: {} passes{culled}, {} resources{on}",
                    path.display(),
                    s.passes.len(),
                    s.resources.len()
                )?;
                // Notes are not failures, but nothing is accepted silently
                // (a param of a technique the pipeline does not choose).
                for note in &s.notes {
                    outln!("    note: {note}")?;
                }
            }
            Err(e) => {
                let text = format!("{e:#}");
                // Pipeline errors start `error:` on every line; an adapter's
                // refusal starts with the adapter.
                failures.push(if text.starts_with("error:") {
                    text
                } else {
                    format!("error: {text}")
                });
            }
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        anyhow::bail!("{}", failures.join("\n"))
    }
}

/// The scene's hair and meshes as a strand structure holds them.
type StructureSize = (plait::structure_limit::HairSize, Vec<(String, u64)>);

/// `schedule`'s strand structure, if it has one, against `gpu`'s BLAS
/// primitive and TLAS instance limits for the hair and meshes of `scene`
/// (read into `hair` the first time).
fn structure_fits(
    schedule: &plait_graph::Schedule,
    gpu: &plait_gpu::Gpu,
    hair: &mut Option<StructureSize>,
    scene: Option<&Path>,
) -> Result<()> {
    if !schedule
        .passes
        .iter()
        .any(|p| p.type_name == plait::structure_limit::STRUCTURE_PASS)
    {
        return Ok(());
    }
    let (size, meshes) = match hair {
        Some(size) => size,
        None => {
            let mut scene = crate::render_cmd::load_scene(scene)?;
            let strands = scene.load_hair()?;
            let meshes = plait::structure_limit::mesh_sizes(&scene.opaque_meshes());
            hair.insert((plait::structure_limit::HairSize::of(&strands), meshes))
        }
    };
    let adapter = gpu.support.describe();
    plait::structure_limit::check(schedule, *size, meshes, &gpu.capabilities, &adapter)?;
    Ok(())
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum GraphFormat {
    Dot,
    Svg,
    Text,
}

#[derive(Args)]
pub struct GraphArgs {
    /// Pipeline file.
    pipeline: PathBuf,
    /// dot (Graphviz source), svg (a picture; no Graphviz needed), or text (the snapshot form).
    /// Default: from --out's extension (.dot/.gv, .svg, .txt), else dot.
    #[arg(long, value_enum)]
    format: Option<GraphFormat>,
    /// Write to this file instead of standard output.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Render size the schedule is compiled for, `WIDTHxHEIGHT`.
    #[arg(long, value_parser = crate::args::parse_size, default_value = "960x720")]
    size: (u32, u32),
    #[command(flatten)]
    set: SetArgs,
}

/// The format `--format` names, or the one `--out`'s extension names; the
/// two must agree, so `--out g.svg` never holds DOT.
fn graph_format(format: Option<GraphFormat>, out: Option<&Path>) -> Result<GraphFormat> {
    let ext = out
        .and_then(|p| p.extension())
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let by_ext = match ext.as_deref() {
        None => None,
        Some("dot" | "gv") => Some(GraphFormat::Dot),
        Some("svg") => Some(GraphFormat::Svg),
        Some("txt" | "text") => Some(GraphFormat::Text),
        Some(other) if format.is_none() => anyhow::bail!(
            "--out {}: `.{other}` names no graph format; use .dot, .svg or .txt, or give --format dot|svg|text",
            out.map_or(String::new(), |p| p.display().to_string())
        ),
        Some(_) => None,
    };
    match (format, by_ext) {
        (Some(f), Some(e)) if f != e => anyhow::bail!(
            "--format {} but --out {} names {} file; drop one or make them agree",
            f.name(),
            out.map_or(String::new(), |p| p.display().to_string()),
            e.file_kind()
        ),
        (Some(f), _) => Ok(f),
        (None, Some(e)) => Ok(e),
        (None, None) => Ok(GraphFormat::Dot),
    }
}

impl GraphFormat {
    fn name(self) -> &'static str {
        match self {
            GraphFormat::Dot => "dot",
            GraphFormat::Svg => "svg",
            GraphFormat::Text => "text",
        }
    }

    /// The kind of file, for a sentence.
    fn file_kind(self) -> &'static str {
        match self {
            GraphFormat::Dot => "a DOT",
            GraphFormat::Svg => "an SVG",
            GraphFormat::Text => "a text",
        }
    }
}

pub fn graph(args: GraphArgs) -> Result<()> {
    let format = graph_format(args.format, args.out.as_deref())?;
    let out = args
        .out
        .as_deref()
        .map(|p| PendingFile::create(p, "--out"))
        .transpose()?;
    let opts = CompileOptions {
        screen: args.size,
        ..CompileOptions::default()
    };
    let pipeline = resolve_pipeline(Some(&args.pipeline));
    let loaded = plait_graph::load(&pipeline, &args.set.sets)?;
    // A default capacity lowered to fit, as the render would (the graph
    // shows the schedule that runs).
    let source = plait::source::PipelineSource::new(&pipeline, &args.set.sets);
    let schedule = match compile_checked_in(&source.library, &pipeline, &args.set.sets, &opts) {
        Ok(schedule) => schedule,
        Err(errors) => {
            plait::size_limit::explain_default_limits(&loaded, &source, args.size)?;
            return Err(errors.into());
        }
    };
    let text = match format {
        GraphFormat::Dot => plait_graph::to_dot(&schedule),
        GraphFormat::Svg => plait_graph::to_svg(&schedule),
        GraphFormat::Text => plait_graph::schedule_text(&schedule),
    };
    match (out, &args.out) {
        (Some(file), Some(path)) => {
            file.commit(text.as_bytes())?;
            outln!("wrote {}", path.display())?;
            Ok(())
        }
        _ => {
            out!("{text}")?;
            Ok(())
        }
    }
}

#[derive(Args)]
pub struct PassesArgs {
    /// Print one JSON array instead of text.
    #[arg(long)]
    json: bool,
}

/// The param's accepted values as data: `{"kind": "number", "min": …, "max": …}`.
fn param_type_json(ty: &ParamType) -> serde_json::Value {
    match ty {
        ParamType::Int { min, max } => {
            serde_json::json!({ "kind": "integer", "min": min, "max": max })
        }
        ParamType::Float { min, max } => {
            serde_json::json!({ "kind": "number", "min": min, "max": max })
        }
        ParamType::Bool => serde_json::json!({ "kind": "bool" }),
        ParamType::Str => serde_json::json!({ "kind": "text" }),
        ParamType::Enum(choices) => serde_json::json!({ "kind": "one_of", "choices": choices }),
        ParamType::Vec3 => serde_json::json!({ "kind": "vec3" }),
    }
}

fn spec_json(spec: &PassTypeSpec) -> serde_json::Value {
    let slot = |s: &SlotSpec| {
        serde_json::json!({
            "name": s.name, "kind": s.kind, "access": s.access, "formats": s.formats.to_string(),
            "loads": s.loads, "optional": s.optional, "doc": s.doc,
        })
    };
    serde_json::json!({
        "name": spec.name,
        "description": spec.description,
        "source": spec.source,
        "shape": spec.shape,
        "inputs": spec.inputs.iter().map(slot).collect::<Vec<_>>(),
        "outputs": spec.outputs.iter().map(slot).collect::<Vec<_>>(),
        "params": spec.params.iter().map(|p| serde_json::json!({
            "name": p.name, "type": param_type_json(&p.ty), "accepts": p.ty.to_string(),
            "default": p.default, "doc": p.doc,
        })).collect::<Vec<_>>(),
        "dynamic_slots": spec.dynamic_slots,
        "required_features": spec.required_features,
    })
}

/// What a pass type is, in words, with what a raster pass needs set.
fn shape_words(shape: PassShape) -> &'static str {
    match shape {
        PassShape::Raster => {
            "raster pass: draws the scene from `view` (light | camera), `draw` (hair | opaque)"
        }
        PassShape::Fullscreen => "fullscreen pass",
        PassShape::Compute => "compute pass",
    }
}

/// `rg32float texture, sampled` / `buffer, storage, written`.
fn slot_words(slot: &SlotSpec) -> String {
    let mut words = match slot.kind {
        ResourceKind::Texture => match &slot.formats {
            Formats::Any => format!("texture (any format), {}", slot.access),
            formats => format!("{formats} texture, {}", slot.access),
        },
        ResourceKind::Buffer => format!("buffer, {}", slot.access),
        ResourceKind::AccelerationStructure => {
            format!("acceleration structure, {}", slot.access)
        }
    };
    if slot.loads {
        words.push_str(", adds to what is there");
    }
    if slot.optional {
        words.push_str(", optional");
    }
    words
}

/// Rows of `name  what — doc`, the names padded to one column.
fn print_rows(title: &str, rows: &[(String, String, String)]) -> std::io::Result<()> {
    if rows.is_empty() {
        return Ok(());
    }
    outln!("  {title}:")?;
    let width = rows
        .iter()
        .map(|(n, _, _)| n.chars().count())
        .max()
        .unwrap_or(0);
    for (name, what, doc) in rows {
        outln!("    {name:<width$}  {what} — {doc}")?;
    }
    Ok(())
}

pub fn passes(args: PassesArgs) -> Result<()> {
    let library = plait_passes::read_library(&[]);
    let specs: Vec<PassTypeSpec> = library.types.values().map(|t| t.spec()).collect();
    if args.json {
        let all: Vec<_> = specs.iter().map(spec_json).collect();
        outln!(
            "{}",
            serde_json::to_string_pretty(&all).context("serializing pass specs")?
        )?;
        return Ok(());
    }
    for spec in &specs {
        outln!("{} — {}", spec.name, spec.description)?;
        outln!("  {}", shape_words(spec.shape))?;
        if spec.source != "plait" {
            outln!("  paper: {}", spec.source)?;
        }
        if spec.dynamic_slots {
            outln!(
                "  slots: the shader's group-1 bindings, matched by name; params fill its `params` uniform"
            )?;
        }
        let slot_rows = |slots: &[SlotSpec]| -> Vec<(String, String, String)> {
            slots
                .iter()
                .map(|s| (s.name.clone(), slot_words(s), s.doc.clone()))
                .collect()
        };
        print_rows("inputs", &slot_rows(&spec.inputs))?;
        print_rows("outputs", &slot_rows(&spec.outputs))?;
        let params: Vec<_> = spec
            .params
            .iter()
            .map(|p| {
                let default = match &p.default {
                    Some(d) => format!(", default {}", value_words(d)),
                    None => ", required".into(),
                };
                (p.name.clone(), format!("{}{default}", p.ty), p.doc.clone())
            })
            .collect();
        print_rows("params", &params)?;
        if !spec.required_features.is_empty() {
            outln!(
                "  needs the GPU feature: {}",
                spec.required_features.join(", ")
            )?;
        }
        outln!()?;
    }
    outln!("Papers are cited by author and year; docs/bibliography.md gives each in full.")?;
    Ok(())
}

/// A default value as it would be written in a pipeline file, numbers short.
fn value_words(value: &plait_graph::Value) -> String {
    match value {
        plait_graph::Value::Float(x) => plait_graph::spec::short_number(*x),
        plait_graph::Value::Str(s) => s.clone(),
        other => other.to_string(),
    }
}
