//! One page per technique, generated from its folder: what it is, its paper,
//! its params (default, accepted range, the comment beside it), memory, the
//! files it consists of, its picture on the reference scenes, its schedule,
//! its rows of the last measurement run, and its `technique.toml` as written.

use std::path::Path;

use plait_graph::techniques::TechniqueInfo;

use crate::context::Context;
use crate::error::BookError;
use crate::figures::renders_markdown;
use crate::params::param_rows;
use crate::plait_cmd::Figure;

/// The page's path under `src/`.
pub fn page_path(point: &str, name: &str) -> String {
    format!("techniques/{point}/{name}.md")
}

/// The command that shows this technique: the gallery file that changes
/// just this key, else the default pipeline (if it is the default's choice),
/// else the default pipeline with `--set`.
fn figure_for(info: &TechniqueInfo, ctx: &Context) -> Figure {
    if let Some(p) = ctx
        .pipelines
        .iter()
        .find(|p| p.own_choices == [(info.point.clone(), info.name.clone())])
    {
        return Figure {
            pipeline: p.file_name.clone(),
            sets: Vec::new(),
        };
    }
    let default = ctx.default_pipeline();
    if default.selects(&info.point, &info.name) {
        return Figure {
            pipeline: default.file_name.clone(),
            sets: Vec::new(),
        };
    }
    let mut sets = vec![format!("techniques.{}={}", info.point, info.name)];
    sets.extend(required_choices(&info.path));
    Figure {
        pipeline: default.file_name.clone(),
        sets,
    }
}

/// The choices its `[technique.requires]` asks for, so its page renders a
/// combination plait accepts (an unreadable file adds none: the render
/// then says why).
fn required_choices(technique_file: &Path) -> Vec<String> {
    std::fs::read_to_string(technique_file)
        .map(|text| plait_graph::techniques::required_choices(&text))
        .unwrap_or_default()
}

pub fn write(info: &TechniqueInfo, ctx: &mut Context) -> Result<String, BookError> {
    let folder = info.path.parent().unwrap_or(Path::new(""));
    let rel_folder = folder
        .strip_prefix(&ctx.repo)
        .unwrap_or(folder)
        .display()
        .to_string();
    let figure = figure_for(info, ctx);
    let renders = ctx.figures.renders(&figure)?;
    let graph = ctx.figures.graph(&figure)?;
    let toml_text = std::fs::read_to_string(&info.path).map_err(BookError::io(&info.path))?;

    let mut md = format!("# {} — `{}`\n\n", info.name, info.point);
    md.push_str(&format!("{}.\n\n", info.description.trim_end_matches('.')));
    md.push_str(&format!(
        "- **Source:** {} (full references: [bibliography](../../reference/bibliography.md))\n",
        nonempty(&info.source)
    ));
    md.push_str(&format!(
        "- **Choose it:** `--set techniques.{}={}` on any pipeline, or `{} = \"{}\"` in its `[techniques]` table\n",
        info.point, info.name, info.point, info.name
    ));
    md.push_str(&format!("- **Memory:** {}\n", nonempty(&info.memory)));
    let users: Vec<String> = ctx
        .pipelines
        .iter()
        .filter(|p| p.selects(&info.point, &info.name))
        .map(|p| format!("[`{}`](../../{})", p.file_name, p.page))
        .collect();
    md.push_str(&format!(
        "- **Gallery pipelines that select it:** {}\n\n",
        if users.is_empty() {
            "none (use `--set`)".to_string()
        } else {
            users.join(", ")
        }
    ));

    md.push_str("## Params\n\n");
    let rows = param_rows(info, ctx)?;
    if rows.is_empty() {
        md.push_str("None: it has nothing to tune.\n\n");
    } else {
        md.push_str(
            "Set with `--set params.NAME=VALUE`. The range is what the pass that reads the param accepts \
             (`plait passes`); an out-of-range value is an error at load.\n\n",
        );
        // A list, not a table: the comments are sentences, and five columns
        // of them overflow the page.
        for r in rows {
            md.push_str(&format!(
                "- **`{}`** = `{}` — {}\\\n  *accepts* {}; *read by* {}\n",
                r.name,
                r.default,
                nonempty(&r.comment),
                r.accepts,
                nonempty(&r.read_by)
            ));
        }
        md.push('\n');
    }

    md.push_str(&format!("## Files\n\nIn `{rel_folder}/`:\n\n"));
    for f in &info.files {
        md.push_str(&format!("- `{f}`\n"));
    }
    md.push_str("\n## Picture\n\n");
    md.push_str(&renders_markdown(&renders, 2));
    if ctx.live {
        let page = page_path(&info.point, &info.name);
        md.push_str(&crate::live::section(&page, &figure));
    }
    md.push_str(&format!(
        "\n## Schedule\n\nThe passes of `{}` with this technique; its rows are tinted.\n\n\
         ![schedule](../../{})\n\n```sh\n{}\n```\n",
        figure.pipeline, graph.file, graph.command
    ));
    md.push_str("\n## Measured\n\n");
    let measured =
        crate::measured::rows_markdown(&ctx.runs, figure.pipeline.trim_end_matches(".toml"));
    if measured.is_empty() || !figure.sets.is_empty() {
        md.push_str(
            "Not in the gallery's measurement runs (`bash scripts/gallery.sh`): compare it yourself with \
             `plait ab` (see [`plait ab` and its report](../../guide/ab.md)).\n",
        );
    } else {
        md.push_str(&measured);
    }
    md.push_str(&format!(
        "\n## The technique file\n\n`{rel_folder}/technique.toml`, with its comments:\n\n```toml\n{}\n```\n",
        toml_text.trim_end()
    ));
    Ok(md)
}

fn nonempty(s: &str) -> &str {
    if s.is_empty() { "—" } else { s }
}
