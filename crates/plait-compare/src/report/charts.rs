//! The charts of a scene: error against cost; with sweeps, error and cost
//! against the first sweep's values; with two sweeps, the grid of every
//! combination as coloured cells.

use crate::plot::{Chart, Grid, Point, Series, grid_svg, svg};

use super::{Report, Run, SceneResult, Variant, cost_ms};
use crate::temporal::Temporal;

pub(super) fn cost_label(report: &Report) -> &'static str {
    if report.provenance.timestamps {
        "GPU ms per frame (median)"
    } else {
        "wall ms per frame (median, no GPU timestamps)"
    }
}

/// Sweep values as numbers when they all parse, else their positions.
fn sweep_x(values: &[String]) -> (Vec<f64>, bool) {
    let nums: Option<Vec<f64>> = values
        .iter()
        .map(|v| v.trim().parse::<f64>().ok())
        .collect();
    match nums {
        Some(n) => (n, true),
        None => ((0..values.len()).map(|i| i as f64).collect(), false),
    }
}

/// Runs drawn as one series: their name and the runs.
struct Group<'r> {
    name: String,
    runs: Vec<(&'r Run, &'r Variant)>,
}

/// A scene's runs grouped into series: by pipeline, and by the values of
/// the sweeps from `split_from` on (so the points of a series differ only
/// in the sweeps before it). The reference is a group of its own.
fn groups<'r>(report: &'r Report, scene: &'r SceneResult, split_from: usize) -> Vec<Group<'r>> {
    let mut keyed: Vec<((String, Vec<&str>), Group<'r>)> = Vec::new();
    for run in &scene.runs {
        let Some(v) = report.variant(&run.variant) else {
            continue;
        };
        let rest: Vec<&str> = v
            .sweep_values
            .values()
            .skip(split_from)
            .map(String::as_str)
            .collect();
        let key = (v.pipeline.clone(), rest);
        let key = if v.is_reference {
            (format!("{} (reference)", v.pipeline), Vec::new())
        } else {
            key
        };
        match keyed.iter_mut().find(|(k, _)| *k == key) {
            Some((_, group)) => group.runs.push((run, v)),
            None => {
                let name = if v.is_reference {
                    format!("{} (reference)", v.pipeline_stem())
                } else {
                    // The keys are in the chart's note: the legend
                    // keeps to the pipeline and the values.
                    let shared: Vec<&str> = v
                        .sweep_values
                        .values()
                        .skip(split_from)
                        .map(String::as_str)
                        .collect();
                    if shared.is_empty() {
                        v.pipeline_stem()
                    } else {
                        format!("{}, {}", v.pipeline_stem(), shared.join(", "))
                    }
                };
                keyed.push((
                    key,
                    Group {
                        name,
                        runs: vec![(run, v)],
                    },
                ));
            }
        }
    }
    keyed.into_iter().map(|(_, group)| group).collect()
}

/// Every chart of a scene: error vs cost (marker area ∝ peak memory); with
/// sweeps, error and cost against the first sweep's values (one line per
/// pipeline and value of the second sweep); with two sweeps, each
/// pipeline's grid of error and of cost.
pub fn scene_charts(report: &Report, scene: &SceneResult) -> Vec<String> {
    let max_mem = report
        .variants
        .iter()
        .map(|v| v.memory.peak_bytes)
        .max()
        .unwrap_or(1)
        .max(1) as f64;
    let radius = |bytes: u64| 3.0 + 13.0 * (bytes as f64 / max_mem).sqrt();
    let series = |groups: &[Group<'_>],
                  joined: bool,
                  y: &dyn Fn(&Run) -> f64,
                  x: &dyn Fn(&Run, &Variant) -> Option<f64>,
                  sized: bool,
                  labelled: bool|
     -> Vec<Series> {
        groups
            .iter()
            .map(|group| Series {
                name: group.name.clone(),
                line: joined && group.runs.len() > 1,
                points: group
                    .runs
                    .iter()
                    .filter_map(|(r, v)| {
                        Some(Point {
                            x: x(r, v)?,
                            y: y(r),
                            size: sized.then(|| radius(v.memory.peak_bytes)),
                            label: if labelled { v.sweep_label() } else { None },
                        })
                    })
                    .collect(),
            })
            .collect()
    };
    let mut charts = Vec::new();
    // A line through a pipeline's points follows one sweep; across a grid
    // it would zig-zag, so grid points stand alone here.
    let by_pipeline = groups(report, scene, report.sweeps.len());
    charts.push(svg(&Chart {
        title: format!("{}: error vs cost", scene.name),
        x_label: cost_label(report).into(),
        y_label: "ꟻLIP mean vs reference".into(),
        note: Some(match report.sweeps.as_slice() {
            [a, b] => format!("marker area ∝ peak memory; labels: {}, {}", a.key, b.key),
            _ => "marker area ∝ peak memory; labels: sweep value".into(),
        }),
        series: series(
            &by_pipeline,
            report.sweeps.len() < 2,
            &|r| r.metrics.flip_mean,
            &|r, _| Some(cost_ms(&r.timing)),
            true,
            true,
        ),
    }));
    if let Some(sw) = report.sweeps.first() {
        let (xs, numeric) = sweep_x(&sw.values);
        let x_of = |_: &Run, v: &Variant| -> Option<f64> {
            let val = v.sweep_values.get(&sw.key)?;
            sw.values.iter().position(|s| s == val).map(|i| xs[i])
        };
        let x_label = if numeric {
            sw.key.clone()
        } else {
            format!("{} (index: {})", sw.key, sw.values.join(", "))
        };
        let lines = groups(report, scene, 1);
        let rmse_label = format!("RMSE ({})", scene.error_space().words());
        for (title, y_label, y) in [
            (
                "ꟻLIP mean",
                "ꟻLIP mean vs reference",
                &(|r: &Run| r.metrics.flip_mean) as &dyn Fn(&Run) -> f64,
            ),
            ("RMSE", rmse_label.as_str(), &|r: &Run| r.metrics.rmse),
            ("cost", cost_label(report), &|r: &Run| cost_ms(&r.timing)),
        ] {
            charts.push(svg(&Chart {
                title: format!("{}: {title} vs {}", scene.name, sw.key),
                x_label: x_label.clone(),
                y_label: y_label.into(),
                // One sweep: points labelled with their value, as they
                // always were; a grid: one line per value of the second
                // sweep, named in the legend.
                note: report
                    .sweeps
                    .get(1)
                    .map(|second| format!("one line per pipeline and {}", second.key)),
                series: series(&lines, true, y, &x_of, false, report.sweeps.len() < 2)
                    .into_iter()
                    .filter(|s| !s.points.is_empty())
                    .collect(),
            }));
        }
    }
    charts.extend(temporal_charts(report, scene));
    if let [rows, columns] = report.sweeps.as_slice() {
        for pipeline in grid_pipelines(report) {
            for (what, value) in [
                (
                    "ꟻLIP mean",
                    &(|r: &Run| Some(r.metrics.flip_mean)) as &dyn Fn(&Run) -> Option<f64>,
                ),
                (cost_label(report), &|r: &Run| Some(cost_ms(&r.timing))),
            ] {
                charts.push(grid_svg(&Grid {
                    title: format!("{}: {} — {what}", scene.name, stem(pipeline)),
                    row_label: rows.key.clone(),
                    column_label: columns.key.clone(),
                    rows: rows.values.clone(),
                    columns: columns.values.clone(),
                    cells: grid_cells(report, scene, pipeline, value),
                    note: Some("darker = larger".into()),
                }));
            }
        }
    }
    charts
}

/// With `--frames`: image and visibility flicker against time, one line per
/// variant (the reference's is zero by construction and left out).
fn temporal_charts(report: &Report, scene: &SceneResult) -> Vec<String> {
    type Values = fn(&Temporal) -> Option<&Vec<f64>>;
    fn image(t: &Temporal) -> Option<&Vec<f64>> {
        Some(&t.image_flicker)
    }
    fn visibility(t: &Temporal) -> Option<&Vec<f64>> {
        t.visibility_flicker.as_ref()
    }
    let over_time = |values: Values| {
        scene
            .runs
            .iter()
            .filter_map(|run| {
                let v = report.variant(&run.variant)?;
                let t = run.temporal.as_ref()?;
                let values = values(t)?;
                (!v.is_reference).then(|| Series {
                    name: v.label.clone(),
                    line: true,
                    points: values
                        .iter()
                        .enumerate()
                        .map(|(k, &y)| Point {
                            // Transition k → k + 1 ends at frame k + 1.
                            x: (k + 1) as f64 / t.fps,
                            y,
                            size: Some(2.5),
                            label: None,
                        })
                        .collect(),
                })
            })
            .collect::<Vec<_>>()
    };
    let mut charts = Vec::new();
    for (what, y_label, values) in [
        (
            "image flicker",
            "mean |ΔI − ΔR| (sRGB 0..1)",
            image as Values,
        ),
        (
            "visibility flicker",
            "mean |ΔV − ΔV_exact| on the probe rays",
            visibility as Values,
        ),
    ] {
        let series = over_time(values);
        if series.iter().any(|s| !s.points.is_empty()) {
            charts.push(svg(&Chart {
                title: format!("{}: {what} over time", scene.name),
                x_label: "time (s)".into(),
                y_label: y_label.into(),
                note: Some(
                    "frame-to-frame change beyond the reference's own change (0 = as stable as the reference)"
                        .into(),
                ),
                series,
            }));
        }
    }
    charts
}

fn stem(pipeline: &str) -> String {
    std::path::Path::new(pipeline)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| pipeline.to_string())
}

/// The pipelines swept over the grid, in the order of the variants.
pub(super) fn grid_pipelines(report: &Report) -> Vec<&str> {
    let mut out: Vec<&str> = Vec::new();
    for v in report.variants.iter().filter(|v| !v.is_reference) {
        if !out.contains(&v.pipeline.as_str()) {
            out.push(&v.pipeline);
        }
    }
    out
}

/// `cells[row][column]` of one pipeline on one scene: `value` of the run at
/// the first sweep's row-th value and the second sweep's column-th value
/// (`None` when there is no such run, or no such value).
pub(super) fn grid_cells(
    report: &Report,
    scene: &SceneResult,
    pipeline: &str,
    value: &dyn Fn(&Run) -> Option<f64>,
) -> Vec<Vec<Option<f64>>> {
    let [rows, columns] = report.sweeps.as_slice() else {
        return Vec::new();
    };
    let at = |row: &str, column: &str| {
        scene.runs.iter().find(|run| {
            report.variant(&run.variant).is_some_and(|v| {
                !v.is_reference
                    && v.pipeline == pipeline
                    && v.sweep_values.get(&rows.key).map(String::as_str) == Some(row)
                    && v.sweep_values.get(&columns.key).map(String::as_str) == Some(column)
            })
        })
    };
    rows.values
        .iter()
        .map(|row| {
            columns
                .values
                .iter()
                .map(|column| at(row, column).and_then(value))
                .collect()
        })
        .collect()
}
