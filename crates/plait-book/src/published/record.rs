//! `docs/figures/ID.json`: what a figure published, at full precision, and
//! where it came from. Made from a `plait ab` run's `report.json` and
//! `report.md` (schema `plait-ab/2`, `plait_compare::report`).

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::Figure;
use crate::error::BookError;

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Record {
    pub id: String,
    /// `git rev-parse HEAD` when it was measured.
    pub commit: String,
    /// Whether a file it measures had uncommitted changes then (the figure
    /// then measures more than its commit).
    pub dirty: bool,
    /// UTC, `YYYY-MM-DD`.
    pub date: String,
    pub adapter: String,
    pub repeats: u32,
    pub command_line: String,
    pub rows: Vec<Row>,
    /// A table figure's cells (`kind = "table"`; `rows` is then empty).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<super::table::Table>,
    /// The report's Markdown tables, as the page shows them.
    pub markdown: String,
}

/// One variant on one scene.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Row {
    pub scene: String,
    pub variant: String,
    pub reference: bool,
    /// Frame GPU ms (wall ms without timestamp queries) over the repeats.
    pub ms: Spread,
    /// Whether `ms` is GPU time. A path-traced reference's row is Mitsuba's
    /// wall time on the CPU: no ratio to a GPU frame is a speed figure.
    /// Records written before this field had only GPU-timed rows.
    #[serde(default = "gpu_timed_default")]
    pub gpu_timed: bool,
    pub rmse: f64,
    pub ssim: f64,
    pub flip: f64,
    /// Self-shadowing error, where the run probed it.
    pub mean_dv: Option<f64>,
}

fn gpu_timed_default() -> bool {
    true
}

/// Median and range over the repeats (read from the report's `Stats`,
/// whose quartiles and samples it leaves out).
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
pub struct Spread {
    pub median: f64,
    pub min: f64,
    pub max: f64,
}

/// The part of `report.json` a record takes.
#[derive(Deserialize)]
struct Report {
    schema: String,
    provenance: Provenance,
    variants: Vec<Variant>,
    scenes: Vec<Scene>,
}

#[derive(Deserialize)]
struct Provenance {
    adapter: Adapter,
    repeats: u32,
}

#[derive(Deserialize)]
struct Adapter {
    name: String,
}

#[derive(Deserialize)]
struct Variant {
    id: String,
    label: String,
    is_reference: bool,
}

#[derive(Deserialize)]
struct Scene {
    name: String,
    runs: Vec<Run>,
}

#[derive(Deserialize)]
struct Run {
    variant: String,
    timing: Timing,
    metrics: Metrics,
    visibility: Option<Visibility>,
}

#[derive(Deserialize)]
struct Timing {
    total_gpu_ms: Option<Spread>,
    wall_ms: Spread,
}

#[derive(Deserialize)]
struct Metrics {
    rmse: f64,
    ssim: f64,
    flip_mean: f64,
}

#[derive(Deserialize)]
struct Visibility {
    provider: String,
    reference_provider: String,
    mean_abs_error: f64,
}

/// Where and when a measurement was made.
pub struct Made {
    pub commit: String,
    pub dirty: bool,
    pub date: String,
}

impl Record {
    pub fn load(path: &Path) -> Result<Record, BookError> {
        let text = std::fs::read_to_string(path).map_err(BookError::io(path))?;
        serde_json::from_str(&text).map_err(|e| BookError::content(path, e.to_string()))
    }

    pub fn save(&self, path: &Path) -> Result<(), BookError> {
        let text = serde_json::to_string_pretty(self).expect("a record serializes") + "\n";
        let tmp = path.with_extension("json.tmp");
        std::fs::write(&tmp, text).map_err(BookError::io(&tmp))?;
        std::fs::rename(&tmp, path).map_err(BookError::io(path))
    }

    /// Reads a finished `plait ab` run's folder (`report.json`, `report.md`).
    pub fn from_run(figure: &Figure, dir: &Path, made: Made) -> Result<Record, BookError> {
        let json = dir.join("report.json");
        let text = std::fs::read_to_string(&json).map_err(BookError::io(&json))?;
        let report: Report =
            serde_json::from_str(&text).map_err(|e| BookError::content(&json, e.to_string()))?;
        if report.schema != "plait-ab/2" {
            return Err(BookError::content(
                &json,
                format!("schema `{}`, this tool reads `plait-ab/2`", report.schema),
            ));
        }
        let md = dir.join("report.md");
        let markdown = std::fs::read_to_string(&md).map_err(BookError::io(&md))?;
        let mut rows = Vec::new();
        for scene in &report.scenes {
            for run in &scene.runs {
                let variant = report
                    .variants
                    .iter()
                    .find(|v| v.id == run.variant)
                    .ok_or_else(|| {
                        BookError::content(
                            &json,
                            format!("run of unknown variant `{}`", run.variant),
                        )
                    })?;
                rows.push(Row {
                    scene: scene.name.clone(),
                    variant: variant.label.clone(),
                    reference: variant.is_reference,
                    ms: run.timing.total_gpu_ms.unwrap_or(run.timing.wall_ms),
                    gpu_timed: run.timing.total_gpu_ms.is_some(),
                    rmse: run.metrics.rmse,
                    ssim: run.metrics.ssim,
                    flip: run.metrics.flip_mean,
                    // A provider probed against itself measures nothing.
                    mean_dv: run
                        .visibility
                        .as_ref()
                        .filter(|v| v.provider != v.reference_provider)
                        .map(|v| v.mean_abs_error),
                });
            }
        }
        Ok(Record {
            id: figure.id.clone(),
            commit: made.commit,
            dirty: made.dirty,
            date: made.date,
            adapter: report.provenance.adapter.name,
            repeats: report.provenance.repeats,
            command_line: figure.command_line(),
            rows,
            table: None,
            markdown: markdown.trim_end().to_string(),
        })
    }

    /// What the page shows between the figure's markers: the tables, then
    /// where they came from and how to check them again.
    pub fn block(&self, figure: &Figure) -> String {
        let short = &self.commit[..self.commit.len().min(10)];
        let dirty = if self.dirty {
            " with uncommitted changes"
        } else {
            ""
        };
        // A table figure's program prints its own adapter and repeats.
        let (verb, run) = if self.table.is_some() {
            ("Printed", String::new())
        } else {
            let plural = if self.repeats == 1 { "" } else { "s" };
            (
                "Measured",
                format!(" ({}, {} repeat{plural})", self.adapter, self.repeats),
            )
        };
        format!(
            "{}\n\n*{verb} by `{}` at commit `{short}`{dirty} on {}{run}; \
             re-measured by `bash scripts/bench.sh --check {}`.*",
            self.markdown,
            figure.command_line(),
            self.date,
            figure.id
        )
    }

    /// The rows of one scene, in the run's order.
    pub fn scene_rows<'a>(&'a self, scene: &'a str) -> impl Iterator<Item = &'a Row> + 'a {
        self.rows.iter().filter(move |r| r.scene == scene)
    }

    /// Scene names in order, once each.
    pub fn scenes(&self) -> Vec<&str> {
        let mut out: Vec<&str> = Vec::new();
        for r in &self.rows {
            if !out.contains(&r.scene.as_str()) {
                out.push(&r.scene);
            }
        }
        out
    }
}
