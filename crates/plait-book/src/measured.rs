//! The last measurement run: the `plait ab` tables `scripts/gallery.sh`
//! writes (as the published figures `gallery-NAME`, `published`) between
//! `<!-- figure:gallery-NAME -->` markers of the gallery page. A
//! technique's or pipeline's page shows its rows from them, so no figure on a
//! generated page is typed by hand.

use std::path::Path;

use crate::error::BookError;

/// One `plait ab` run (`shadows`, `transparency`).
#[derive(Clone, Debug)]
pub struct Run {
    pub name: String,
    /// The report's own provenance line (`made by plait ab (…)`).
    pub provenance: String,
    pub scenes: Vec<SceneTable>,
}

/// One scene's table of a run.
#[derive(Clone, Debug)]
pub struct SceneTable {
    pub scene: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl SceneTable {
    /// The row of `variant` (the pipeline's file stem; the reference's row
    /// reads `stem (reference)`).
    pub fn row(&self, variant: &str) -> Option<&[String]> {
        self.rows
            .iter()
            .find(|r| {
                r.first().is_some_and(|c| {
                    c == variant || c.strip_suffix(" (reference)") == Some(variant)
                })
            })
            .map(Vec::as_slice)
    }
}

/// Reads every marked run of `page`; a marker without a table is an error
/// (an empty run would make every page silently lose its row).
pub fn read(page: &Path) -> Result<Vec<Run>, BookError> {
    let text = std::fs::read_to_string(page).map_err(BookError::io(page))?;
    let mut runs = Vec::new();
    let mut current: Option<Run> = None;
    let mut scene = String::new();
    for line in text.lines() {
        let line = line.trim();
        if let Some(name) = marker(line, "<!-- figure:gallery-") {
            current = Some(Run {
                name: name.to_string(),
                provenance: String::new(),
                scenes: Vec::new(),
            });
            continue;
        }
        let Some(run) = current.as_mut() else {
            continue;
        };
        if marker(line, "<!-- /figure:gallery-").is_some() {
            let run = current.take().expect("inside a run");
            if run.scenes.iter().all(|s| s.rows.is_empty()) {
                return Err(BookError::content(
                    page,
                    format!(
                        "the `{}` measurement run has no table; run `bash scripts/gallery.sh`",
                        run.name
                    ),
                ));
            }
            runs.push(run);
        } else if let Some(p) = line.strip_prefix("*Measured by ") {
            // The figure's own provenance line: command, commit, date, adapter.
            let p = p.trim_end_matches('*');
            run.provenance = format!(
                "measured by {}",
                p.split("; re-measured").next().unwrap_or(p)
            );
        } else if let Some(p) = line.strip_prefix("<!-- made by ") {
            if run.provenance.is_empty() {
                run.provenance = format!("made by {}", p.trim_end_matches("-->").trim());
            }
        } else if let Some(s) = line.strip_prefix("**").and_then(|l| l.strip_suffix("**")) {
            scene = s.to_string();
        } else if line.starts_with('|') {
            let cells = cells(line);
            if cells
                .iter()
                .all(|c| c.chars().all(|ch| matches!(ch, '-' | ':')))
            {
                continue; // the separator row
            }
            match run.scenes.last_mut() {
                Some(t) if t.scene == scene => t.rows.push(cells),
                _ => run.scenes.push(SceneTable {
                    scene: scene.clone(),
                    header: cells,
                    rows: Vec::new(),
                }),
            }
        }
    }
    if let Some(run) = current {
        return Err(BookError::content(
            page,
            format!("`<!-- figure:gallery-{} -->` is never closed", run.name),
        ));
    }
    Ok(runs)
}

fn marker<'a>(line: &'a str, open: &str) -> Option<&'a str> {
    line.strip_prefix(open)?.strip_suffix("-->").map(str::trim)
}

/// The cells of a Markdown table row; `\|` stays inside its cell.
fn cells(line: &str) -> Vec<String> {
    let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
    let mut out = Vec::new();
    let mut cell = String::new();
    let mut chars = inner.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'|') => {
                cell.push_str("\\|");
                chars.next();
            }
            '|' => out.push(std::mem::take(&mut cell).trim().to_string()),
            c => cell.push(c),
        }
    }
    out.push(cell.trim().to_string());
    out
}

/// The Markdown of `variant`'s rows in every run and scene, under the runs'
/// provenance; empty when the variant was not measured.
pub fn rows_markdown(runs: &[Run], variant: &str) -> String {
    let mut out = String::new();
    for run in runs {
        let tables: Vec<_> = run
            .scenes
            .iter()
            .filter_map(|t| t.row(variant).map(|r| (t, r)))
            .collect();
        let Some((first, _)) = tables.first() else {
            continue;
        };
        out.push_str(&format!(
            "The `{}` run of the gallery page ({}):\n\n| scene | {} |\n|---|{}\n",
            run.name,
            run.provenance,
            first.header[1..].join(" | "),
            "---:|".repeat(first.header.len() - 1),
        ));
        for (t, row) in tables {
            out.push_str(&format!("| {} | {} |\n", t.scene, row[1..].join(" | ")));
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_found_per_scene_and_an_empty_run_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let page = dir.path().join("gallery.md");
        std::fs::write(
            &page,
            "<!-- figure:gallery-t -->\n<!-- made by plait ab (1 repeat) -->\n\n**small**\n\n\
             | variant | ms | \\|ΔV\\| |\n|---|---:|---:|\n| a | 1 | 0.5 / 1 |\n| b (reference) | 2 | 0 |\n\n\
             **stray**\n\n| variant | ms | \\|ΔV\\| |\n|---|---:|---:|\n| a | 3 | 0.1 |\n<!-- /figure:gallery-t -->\n",
        )
        .unwrap();
        let runs = read(&page).unwrap();
        assert_eq!(runs[0].scenes.len(), 2);
        assert_eq!(runs[0].scenes[0].row("b").unwrap()[1], "2");
        let md = rows_markdown(&runs, "a");
        assert!(md.contains("| small | 1 | 0.5 / 1 |"), "{md}");
        assert!(md.contains("| stray | 3 | 0.1 |"), "{md}");
        assert!(md.contains("made by plait ab (1 repeat)"), "{md}");
        assert_eq!(rows_markdown(&runs, "c"), "");

        std::fs::write(
            &page,
            "<!-- figure:gallery-t -->\n<!-- /figure:gallery-t -->\n",
        )
        .unwrap();
        let err = read(&page).unwrap_err().to_string();
        assert!(err.contains("`t` measurement run has no table"), "{err}");
    }
}
