//! `plait techniques`: every choice point, its techniques, their papers,
//! params and memory — read from the technique files, so a new file shows up
//! without a rebuild.

use std::path::PathBuf;

use anyhow::{Context, Result, anyhow};
use clap::Args;

#[derive(Args)]
pub struct TechniquesArgs {
    /// Print one JSON array instead of text.
    #[arg(long)]
    json: bool,
    /// The techniques folder (default: the one the default pipeline uses).
    #[arg(long, value_name = "DIR")]
    dir: Option<PathBuf>,
}

pub fn run(args: TechniquesArgs) -> Result<()> {
    let roots = match args.dir {
        Some(d) => plait_graph::techniques::TechniqueRoots::at(d),
        None => {
            let pipeline = plait::session::resolve_pipeline(None);
            let roots = plait_graph::techniques::TechniqueRoots::for_pipeline(&pipeline);
            if roots.is_empty() {
                return Err(anyhow!(
                    "no `techniques/` folder beside {} or above it",
                    pipeline.display()
                ));
            }
            roots
        }
    };
    let catalog = plait_graph::techniques::catalog(&roots)
        .map_err(|errors| anyhow!("{}", plait_graph::Errors(errors)))?;
    if args.json {
        let all: Vec<_> = catalog
            .iter()
            .map(|t| {
                serde_json::json!({
                    "point": t.point, "name": t.name, "file": t.path.display().to_string(), "files": t.files,
                    "description": t.description, "source": t.source, "memory": t.memory,
                    "params": t.params.iter().map(|(k, v)| serde_json::json!({"name": k, "default": v})).collect::<Vec<_>>(),
                })
            })
            .collect();
        outln!(
            "{}",
            serde_json::to_string_pretty(&all).context("serializing the techniques")?
        )?;
        return Ok(());
    }
    // One column for the names, as wide as the longest (a fixed width ran
    // `deep_opacity_directions` into its description).
    let w = catalog
        .iter()
        .map(|t| t.name.chars().count())
        .max()
        .unwrap_or(0);
    let mut point = None;
    for t in &catalog {
        if point != Some(&t.point) {
            point = Some(&t.point);
            outln!("\n{} — `--set techniques.{}=NAME`", t.point, t.point)?;
        }
        outln!("  {:<w$} {}", t.name, t.description)?;
        if !t.source.is_empty() && t.source != "—" {
            outln!("  {:<w$} paper: {}", "", t.source)?;
        }
        if !t.params.is_empty() {
            let params: Vec<String> = t.params.iter().map(|(k, v)| format!("{k} = {v}")).collect();
            outln!("  {:<w$} params: {}", "", params.join(", "))?;
        }
        if !t.memory.is_empty() {
            outln!("  {:<w$} memory: {}", "", t.memory)?;
        }
        let folder = t.path.parent().unwrap_or(&t.path);
        outln!(
            "  {:<w$} files: {}/ {}",
            "",
            folder.display(),
            t.files.join(", ")
        )?;
    }
    outln!("\nPapers: docs/bibliography.md")?;
    Ok(())
}
