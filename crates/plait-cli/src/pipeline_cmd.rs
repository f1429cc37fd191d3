//! `plait check`, `plait graph`, `plait passes`: everything that needs no GPU.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::{Args, ValueEnum};
use plait::session::compile_checked;
use plait_graph::{CompileOptions, PassTypeSpec};

use crate::output::PendingFile;

/// `--set key=value` in one place for every command.
#[derive(Args, Clone, Debug, Default)]
pub struct SetArgs {
    /// Override a key of the pipeline file, e.g. `--set params.slices=64`
    /// or `--set passes.self_shadow.type=deep_opacity` (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

#[derive(Args)]
pub struct CheckArgs {
    /// Pipeline files to validate.
    #[arg(required = true)]
    pipelines: Vec<PathBuf>,
    #[command(flatten)]
    set: SetArgs,
}

pub fn check(args: CheckArgs) -> Result<()> {
    let mut failures = Vec::new();
    for path in &args.pipelines {
        match compile_checked(path, &args.set.sets, &CompileOptions::default()) {
            Ok(s) => {
                let culled = if s.culled.is_empty() {
                    String::new()
                } else {
                    format!(", {} culled", s.culled.len())
                };
                outln!(
                    "ok  {}: {} passes{culled}, {} resources",
                    path.display(),
                    s.passes.len(),
                    s.resources.len()
                )?;
            }
            Err(e) => failures.push(format!("{e:#}")),
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        anyhow::bail!("{}", failures.join("\n"))
    }
}

#[derive(Clone, Copy, ValueEnum)]
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
    #[arg(long, value_enum, default_value = "dot")]
    format: GraphFormat,
    /// Write to this file instead of standard output.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Render size the schedule is compiled for, `WIDTHxHEIGHT`.
    #[arg(long, value_parser = crate::render_cmd::parse_size, default_value = "960x720")]
    size: (u32, u32),
    #[command(flatten)]
    set: SetArgs,
}

pub fn graph(args: GraphArgs) -> Result<()> {
    let out = args
        .out
        .as_deref()
        .map(|p| PendingFile::create(p, "--out"))
        .transpose()?;
    let opts = CompileOptions {
        screen: args.size,
        ..CompileOptions::default()
    };
    let schedule = compile_checked(&args.pipeline, &args.set.sets, &opts)?;
    let text = match args.format {
        GraphFormat::Dot => plait_graph::to_dot(&schedule),
        GraphFormat::Svg => plait_graph::to_svg(&schedule)
            .map_err(|e| anyhow::anyhow!("drawing the graph: {}", e.0))?,
        GraphFormat::Text => plait_graph::schedule_text(&schedule),
    };
    match out {
        Some(file) => file.commit(text.as_bytes()),
        None => {
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

fn spec_json(spec: &PassTypeSpec) -> serde_json::Value {
    let slot = |s: &plait_graph::SlotSpec| {
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
            "name": p.name, "type": format!("{:?}", p.ty), "default": p.default, "doc": p.doc,
        })).collect::<Vec<_>>(),
        "dynamic_slots": spec.dynamic_slots,
        "required_features": spec.required_features,
    })
}

pub fn passes(args: PassesArgs) -> Result<()> {
    let library = plait_passes::library();
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
        outln!("{} ({:?}) — {}", spec.name, spec.shape, spec.description)?;
        if spec.source != "plait" {
            outln!("  source: {}", spec.source)?;
        }
        if spec.dynamic_slots {
            outln!(
                "  slots: the shader's group-1 bindings, matched by name; params fill its `params` uniform"
            )?;
        }
        for (title, slots) in [("inputs", &spec.inputs), ("outputs", &spec.outputs)] {
            if !slots.is_empty() {
                outln!("  {title}:")?;
            }
            for s in slots {
                let mut flags = Vec::new();
                if s.optional {
                    flags.push("optional");
                }
                if s.loads {
                    flags.push("loads");
                }
                let flags = if flags.is_empty() {
                    String::new()
                } else {
                    format!(" [{}]", flags.join(", "))
                };
                let formats = match s.kind {
                    plait_graph::ResourceKind::Texture => format!(" ({})", s.formats),
                    plait_graph::ResourceKind::Buffer => String::new(),
                };
                outln!(
                    "    {:<12} {} {:?}{formats}{flags} — {}",
                    s.name,
                    s.kind,
                    s.access,
                    s.doc
                )?;
            }
        }
        if !spec.params.is_empty() {
            outln!("  params:")?;
        }
        for p in &spec.params {
            let default = p
                .default
                .as_ref()
                .map(|d| format!(" = {d}"))
                .unwrap_or_else(|| " (required)".into());
            outln!("    {:<12} {:?}{default} — {}", p.name, p.ty, p.doc)?;
        }
        if !spec.required_features.is_empty() {
            outln!("  needs: {}", spec.required_features.join(", "))?;
        }
        outln!()?;
    }
    Ok(())
}
