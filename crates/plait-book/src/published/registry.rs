//! `docs/figures.toml`: which figures are published, where, measured by
//! which command, and which files they measure.

use std::path::Path;

use serde::Deserialize;

use super::REGISTRY;
use crate::error::BookError;

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Registry {
    #[serde(rename = "figure")]
    pub figures: Vec<Figure>,
}

/// One published table.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Figure {
    /// Its name in the markers `<!-- figure:ID -->` and in `docs/figures/ID.json`.
    pub id: String,
    /// The Markdown file that shows it, relative to the repository root.
    pub page: String,
    /// `kind = "ab"` (the default): `plait`'s arguments, an `ab` command;
    /// the tool adds `--out DIR`. `kind = "table"`: a program and its
    /// arguments, run from the repository root (a benchmark, a script), whose
    /// standard output's last Markdown table is the figure.
    pub command: Vec<String>,
    #[serde(default)]
    pub kind: Kind,
    /// A table figure's columns naming a row (default: the first column).
    #[serde(default)]
    pub key: Vec<String>,
    /// A table figure's compared columns and how (the rest are shown, not
    /// compared: a paper's numbers, a description).
    #[serde(default)]
    pub columns: indexmap::IndexMap<String, Column>,
    /// Files and folders whose change can move the figure: a commit touching
    /// one after the figure's own commit makes it stale.
    pub measures: Vec<String>,
    /// Files inside `measures` that the figure's command never runs (the
    /// path tracer's shaders under `shaders`, for a rasterized figure): a
    /// commit touching only these leaves the figure fresh.
    #[serde(default)]
    pub except: Vec<String>,
    /// Relative change of a frame-time ratio still within the machine's noise
    /// beyond the run's own spread (default 0.10: lavapipe on a 2-core
    /// machine repeats to about ±10 %, book → Performance).
    #[serde(default = "default_speed_tolerance")]
    pub speed_tolerance: f64,
}

impl Figure {
    /// What it measures as git pathspecs: `measures`, less `except`.
    pub fn pathspecs(&self) -> Vec<String> {
        let excluded = self.except.iter().map(|e| format!(":(exclude){e}"));
        self.measures.iter().cloned().chain(excluded).collect()
    }
}

/// How a figure is measured.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// One `plait ab` run (its `report.json`).
    #[default]
    Ab,
    /// The last Markdown table a program prints.
    Table,
}

/// How a table figure's column is compared with today's.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Column {
    /// Times of one run: compared as each row's ratio to the first row's
    /// (side by side, never as milliseconds), within `speed_tolerance`.
    Time,
    /// A ratio measured within the run (its cell may give the rounds'
    /// range as `[lo–hi]`), within that range widened by `speed_tolerance`.
    Ratio,
    /// A deterministic metric: within 2 % (or 0.001 near 0).
    Metric,
    /// Text or a count that must not change.
    Exact,
}

fn default_speed_tolerance() -> f64 {
    0.10
}

impl Registry {
    pub fn load(repo: &Path) -> Result<Registry, BookError> {
        let path = repo.join(REGISTRY);
        let text = std::fs::read_to_string(&path).map_err(BookError::io(&path))?;
        let registry: Registry = toml::from_str(&text)
            .map_err(|e| BookError::content(&path, format!("{}", e).trim_end().to_string()))?;
        let mut seen = std::collections::HashSet::new();
        for f in &registry.figures {
            if !seen.insert(f.id.as_str()) {
                return Err(BookError::content(
                    &path,
                    format!("figure `{}` is registered twice", f.id),
                ));
            }
            match f.kind {
                Kind::Ab if f.command.first().map(String::as_str) != Some("ab") => {
                    return Err(BookError::content(
                        &path,
                        format!(
                            "figure `{}`: command must be a `plait ab` command (starts with \"ab\"), or give kind = \"table\"",
                            f.id
                        ),
                    ));
                }
                Kind::Table if f.command.is_empty() || f.columns.is_empty() => {
                    return Err(BookError::content(
                        &path,
                        format!(
                            "figure `{}`: a table figure needs a command and the columns it compares",
                            f.id
                        ),
                    ));
                }
                _ => {}
            }
            if f.command.iter().any(|a| a == "--out") {
                return Err(BookError::content(
                    &path,
                    format!(
                        "figure `{}`: command must not name --out (the tool picks it)",
                        f.id
                    ),
                ));
            }
            for m in f.measures.iter().chain(&f.except) {
                if !repo.join(m).exists() {
                    return Err(BookError::content(
                        &path,
                        format!("figure `{}`: measures `{m}`, which does not exist", f.id),
                    ));
                }
            }
            // An exception outside every measured path would hide nothing and
            // say something false about the figure.
            if let Some(e) = f.except.iter().find(|e| {
                !f.measures
                    .iter()
                    .any(|m| Path::new(e.as_str()).starts_with(m.as_str()))
            }) {
                return Err(BookError::content(
                    &path,
                    format!(
                        "figure `{}`: except `{e}` lies outside everything it measures",
                        f.id
                    ),
                ));
            }
        }
        Ok(registry)
    }

    pub fn figure(&self, id: &str) -> Option<&Figure> {
        self.figures.iter().find(|f| f.id == id)
    }

    /// Every page that publishes a figure, once.
    pub fn pages(&self) -> Vec<String> {
        let mut pages: Vec<String> = self.figures.iter().map(|f| f.page.clone()).collect();
        pages.sort();
        pages.dedup();
        pages
    }

    /// `; did you mean `X`?` for the registered id nearest `id`, or nothing.
    pub fn suggest(&self, id: &str) -> String {
        plait_graph::suggest::did_you_mean(id, self.figures.iter().map(|f| f.id.as_str()))
    }

    /// The figures named by `ids` (all without), or the unknown name.
    pub fn select(&self, ids: &[String]) -> Result<Vec<&Figure>, String> {
        if ids.is_empty() {
            return Ok(self.figures.iter().collect());
        }
        ids.iter()
            .map(|id| {
                self.figure(id)
                    .ok_or_else(|| format!("no figure `{id}` in {REGISTRY}{}", self.suggest(id)))
            })
            .collect()
    }
}

impl Figure {
    /// The command line as a reader types it.
    pub fn command_line(&self) -> String {
        let program = match self.kind {
            Kind::Ab => Some("plait"),
            Kind::Table => None,
        };
        program
            .into_iter()
            .chain(self.command.iter().map(String::as_str))
            .map(|a| {
                if a.chars().any(char::is_whitespace) {
                    format!("'{a}'")
                } else {
                    a.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join(" ")
    }
}
