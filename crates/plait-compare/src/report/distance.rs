//! The camera-distance sweep of a report (`plait ab --camera-distance`):
//! each scene was run once per distance factor, so per scene the error of
//! every variant against the reference seen from the same place (ꟻLIP
//! mean, the report's main error metric) and every variant's frame time,
//! against the distance — where a level of detail wins, and where it stops
//! being good enough — as charts (`plot.rs`) and as a table.

use std::fmt::Write as _;

use crate::plot::{Chart, Point, Series, escape, svg};

use super::charts::cost_label;
use super::{Report, SceneResult, Variant, cost_ms};

/// One scene across the distances: its name and its results by factor, in
/// the order of `--camera-distance`.
pub(super) struct Swept<'r> {
    pub scene: &'r str,
    pub at: Vec<(f64, &'r SceneResult)>,
}

/// The report's scenes grouped by the scene they were moved in (none
/// without `--camera-distance`).
pub(super) fn swept_scenes(report: &Report) -> Vec<Swept<'_>> {
    let mut out: Vec<Swept<'_>> = Vec::new();
    for scene in &report.scenes {
        let Some(d) = &scene.distance else {
            continue;
        };
        match out.iter_mut().find(|s| s.scene == d.scene) {
            Some(s) => s.at.push((d.factor, scene)),
            None => out.push(Swept {
                scene: &d.scene,
                at: vec![(d.factor, scene)],
            }),
        }
    }
    out
}

/// `value` of `variant`'s run on `scene`, if it ran there.
fn value_of(scene: &SceneResult, variant: &Variant, value: fn(&super::Run) -> f64) -> Option<f64> {
    scene
        .runs
        .iter()
        .find(|r| r.variant == variant.id)
        .map(value)
}

fn flip(r: &super::Run) -> f64 {
    r.metrics.flip_mean
}

fn cost(r: &super::Run) -> f64 {
    cost_ms(&r.timing)
}

/// Per swept scene: ꟻLIP mean against the distance (one line per variant;
/// the reference's is zero by construction and left out) and frame time
/// against the distance (the reference's too: what the variants save).
pub fn distance_charts(report: &Report) -> Vec<String> {
    let series = |swept: &Swept<'_>, value: fn(&super::Run) -> f64, reference: bool| {
        report
            .variants
            .iter()
            .filter(|v| reference || !v.is_reference)
            .map(|v| Series {
                // Ids (`forward@lod`): labels with every --set are too long for a legend.
                name: v.id.clone(),
                line: true,
                points: swept
                    .at
                    .iter()
                    .filter_map(|(factor, scene)| {
                        Some(Point {
                            x: *factor,
                            y: value_of(scene, v, value)?,
                            size: Some(3.0),
                            label: None,
                        })
                    })
                    .collect(),
            })
            .filter(|s| !s.points.is_empty())
            .collect::<Vec<_>>()
    };
    let mut charts = Vec::new();
    for swept in swept_scenes(report) {
        charts.push(svg(&Chart {
            title: format!("{}: error vs camera distance", swept.scene),
            x_label: "camera distance (× the scene's)".into(),
            y_label: "ꟻLIP mean vs reference".into(),
            note: Some(
                "the reference is rendered from the same distance; mean over the whole image, so it falls as the hair covers fewer pixels"
                    .into(),
            ),
            series: series(&swept, flip, false),
        }));
        charts.push(svg(&Chart {
            title: format!("{}: frame time vs camera distance", swept.scene),
            x_label: "camera distance (× the scene's)".into(),
            y_label: cost_label(report).into(),
            note: None,
            series: series(&swept, cost, true),
        }));
    }
    charts
}

/// What the error column is, and how it is not to be read.
const MEAN_NOTE: &str = "ꟻLIP mean over the whole image: as the camera backs off the hair covers fewer pixels, so every variant's mean falls with the distance; compare variants at one distance (a row), not a variant across rows.";

/// The variants in the table's column order: the others, then the reference.
fn columns(report: &Report) -> impl Iterator<Item = &Variant> {
    let others = report.variants.iter().filter(|v| !v.is_reference);
    others.chain(report.variants.iter().filter(|v| v.is_reference))
}

/// Per swept scene, `| distance | <variant> ꟻLIP | <variant> ms | … |`, a
/// row per distance (the reference: ms only). Empty without
/// `--camera-distance`.
pub fn distance_markdown(report: &Report) -> String {
    let mut out = String::new();
    let unit = if report.provenance.timestamps {
        "GPU ms"
    } else {
        "wall ms"
    };
    for swept in swept_scenes(report) {
        let _ = writeln!(
            out,
            "\n**{}: error and frame time vs camera distance**\n",
            swept.scene
        );
        out.push_str(MEAN_NOTE);
        out.push_str("\n\n");
        out.push_str("| distance |");
        let mut rule = String::from("|---:|");
        for v in columns(report) {
            if !v.is_reference {
                let _ = write!(out, " {} ꟻLIP |", v.id);
                rule.push_str("---:|");
            }
            let _ = write!(out, " {} {unit} |", v.id);
            rule.push_str("---:|");
        }
        let _ = writeln!(out, "\n{rule}");
        for (factor, scene) in &swept.at {
            let _ = write!(out, "| {factor}× |");
            for v in columns(report) {
                let cell = |value, digits: usize| {
                    value_of(scene, v, value).map_or(String::new(), |x| format!("{x:.digits$}"))
                };
                if !v.is_reference {
                    let _ = write!(out, " {} |", cell(flip, 4));
                }
                let _ = write!(out, " {} |", cell(cost, 2));
            }
            out.push('\n');
        }
    }
    out
}

/// The same table as HTML, with the charts, under one heading; empty
/// without `--camera-distance`.
pub(super) fn distance_html(report: &Report) -> String {
    let swept = swept_scenes(report);
    if swept.is_empty() {
        return String::new();
    }
    let mut h = String::from(
        "<h2>Camera distance</h2><p class=note>every scene seen from its camera moved back along its view ray (× its distance to the target); every variant and the reference rendered from there; error = ꟻLIP mean against the reference</p>",
    );
    let _ = write!(h, "<p class=note>{}</p>", escape(MEAN_NOTE));
    h.push_str("<p class=note>columns: variant ids (hover for the full label)</p>");
    for s in &swept {
        let _ = write!(
            h,
            "<h3>{}</h3><table><tr><th>distance</th>",
            escape(s.scene)
        );
        for v in columns(report) {
            if !v.is_reference {
                let _ = write!(
                    h,
                    "<th title=\"{}\">{} ꟻLIP</th>",
                    escape(&v.label),
                    escape(&v.id)
                );
            }
            let _ = write!(
                h,
                "<th title=\"{}\">{} ms</th>",
                escape(&v.label),
                escape(&v.id)
            );
        }
        h.push_str("</tr>");
        for (factor, scene) in &s.at {
            let _ = write!(h, "<tr><td>{factor}×</td>");
            for v in columns(report) {
                let cell = |value, digits: usize| {
                    value_of(scene, v, value).map_or(String::new(), |x| format!("{x:.digits$}"))
                };
                if !v.is_reference {
                    let _ = write!(h, "<td>{}</td>", cell(flip, 5));
                }
                let _ = write!(h, "<td>{}</td>", cell(cost, 3));
            }
            h.push_str("</tr>");
        }
        h.push_str("</table>");
    }
    h.push_str("<div class=grid>");
    for c in distance_charts(report) {
        h.push_str(&c);
    }
    h.push_str("</div>");
    h
}
