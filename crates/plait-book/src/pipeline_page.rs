//! One page per gallery pipeline, generated from its file: its description
//! and leading comment, the techniques it resolves to, its picture on the
//! reference scenes, its schedule, its rows of the last measurement run and
//! the file itself with its comments.

use crate::context::{Context, GalleryPipeline};
use crate::error::BookError;
use crate::figures::renders_markdown;
use crate::plait_cmd::Figure;
use crate::technique_page;

pub fn write(p: &GalleryPipeline, ctx: &mut Context) -> Result<String, BookError> {
    let text = std::fs::read_to_string(&p.path).map_err(BookError::io(&p.path))?;
    let figure = Figure {
        pipeline: p.file_name.clone(),
        sets: Vec::new(),
    };
    let renders = ctx.figures.renders(&figure)?;
    let graph = ctx.figures.graph(&figure)?;
    let stem = p.file_name.trim_end_matches(".toml");

    let mut md = format!(
        "# `{}`\n\n{}.\n\n",
        p.file_name,
        p.description.trim_end_matches('.')
    );
    let lead = leading_comment(&text);
    if !lead.is_empty() {
        md.push_str("From the file's own comment:\n\n");
        for line in lead.lines() {
            md.push_str(&format!("> {line}\n"));
        }
        md.push('\n');
    }
    md.push_str(&format!(
        "```sh\nplait render {} --out hair.png     # also: plait view {}, plait check {}\n```\n\n",
        p.file_name, p.file_name, p.file_name
    ));
    md.push_str(
        "## Techniques\n\n| choice point | technique | set by this file |\n|---|---|---|\n",
    );
    for (point, name) in &p.chosen {
        let own = p
            .own_choices
            .iter()
            .any(|(op, on)| op == point && on == name);
        md.push_str(&format!(
            "| `{point}` | [{name}](../{}) | {} |\n",
            technique_page::page_path(point, name),
            if own { "yes" } else { "inherited" }
        ));
    }
    if p.chosen.is_empty() {
        md.push_str("| — | none: every pass is written out in the file | |\n");
    }
    md.push_str("\n## Picture\n\n");
    md.push_str(&renders_markdown(&renders, 1));
    let thumbnail = ctx.repo.join("docs/variants").join(format!("{stem}.png"));
    if thumbnail.exists() {
        md.push_str(&format!(
            "\nAt the gallery's measurement size (`bash scripts/gallery.sh`):\n\n\
             ![{stem}, measured](../docs/variants/{stem}.png)\n"
        ));
    }
    if ctx.live {
        md.push_str(&crate::live::section(&p.page, &figure));
    }
    md.push_str(&format!(
        "\n## Schedule\n\nPasses as rows, resource lifetimes as columns; a technique's passes are tinted.\n\n\
         ![schedule](../{})\n\n```sh\n{}\n```\n",
        graph.file, graph.command
    ));
    md.push_str("\n## Measured\n\n");
    let measured = crate::measured::rows_markdown(&ctx.runs, stem);
    if measured.is_empty() {
        md.push_str(
            "Not in the gallery's measurement runs; `plait ab` measures it against any reference \
             ([`plait ab` and its report](../guide/ab.md)).\n",
        );
    } else {
        md.push_str(&measured);
    }
    md.push_str(&format!(
        "\n## The pipeline file\n\n`pipelines/{}`, with its comments:\n\n```toml\n{}\n```\n",
        p.file_name,
        text.trim_end()
    ));
    Ok(md)
}

/// The comment block a pipeline file opens with, without the `#`s.
fn leading_comment(text: &str) -> String {
    text.lines()
        .take_while(|l| l.starts_with('#'))
        .map(|l| {
            l.trim_start_matches('#')
                .strip_prefix(' ')
                .unwrap_or(l.trim_start_matches('#'))
        })
        .collect::<Vec<_>>()
        .join("\n")
}
