//! The charts of a scene: error against cost, and error and cost against swept values.

use crate::plot::{Chart, Point, Series, svg};

use super::{Report, Run, SceneResult, Variant, cost_ms};

fn cost_label(report: &Report) -> &'static str {
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

/// Every chart of a scene: error vs cost (marker area ∝ peak memory), and
/// with a sweep, error and cost against the swept value.
pub fn scene_charts(report: &Report, scene: &SceneResult) -> Vec<String> {
    let max_mem = report
        .variants
        .iter()
        .map(|v| v.memory.peak_bytes)
        .max()
        .unwrap_or(1)
        .max(1) as f64;
    let radius = |bytes: u64| 3.0 + 13.0 * (bytes as f64 / max_mem).sqrt();
    // Group runs by pipeline (sweep points of one pipeline form one series).
    let mut groups: Vec<(String, Vec<(&Run, &Variant)>)> = Vec::new();
    for run in &scene.runs {
        let Some(v) = report.variant(&run.variant) else {
            continue;
        };
        let key = if v.is_reference {
            format!("{} (reference)", v.pipeline_stem())
        } else {
            v.pipeline.clone()
        };
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, list)) => list.push((run, v)),
            None => groups.push((key, vec![(run, v)])),
        }
    }
    let name_of = |key: &str, list: &[(&Run, &Variant)]| {
        list.first()
            .map(|(_, v)| {
                if v.is_reference {
                    key.to_string()
                } else {
                    v.pipeline_stem()
                }
            })
            .unwrap_or_default()
    };
    let mut charts = Vec::new();
    let series = |y: &dyn Fn(&Run) -> f64,
                  x: &dyn Fn(&Run, &Variant) -> Option<f64>,
                  sized: bool|
     -> Vec<Series> {
        groups
            .iter()
            .map(|(key, list)| Series {
                name: name_of(key, list),
                line: list.len() > 1,
                points: list
                    .iter()
                    .filter_map(|(r, v)| {
                        Some(Point {
                            x: x(r, v)?,
                            y: y(r),
                            size: if sized {
                                Some(radius(v.memory.peak_bytes))
                            } else {
                                None
                            },
                            label: v.sweep_value.clone(),
                        })
                    })
                    .collect(),
            })
            .collect()
    };
    charts.push(svg(&Chart {
        title: format!("{}: error vs cost", scene.name),
        x_label: cost_label(report).into(),
        y_label: "ꟻLIP mean vs reference".into(),
        note: Some("marker area ∝ peak memory; labels: sweep value".into()),
        series: series(
            &|r| r.metrics.flip_mean,
            &|r, _| Some(cost_ms(&r.timing)),
            true,
        ),
    }));
    if let Some(sw) = &report.sweep {
        let (xs, numeric) = sweep_x(&sw.values);
        let x_of = |_: &Run, v: &Variant| -> Option<f64> {
            let val = v.sweep_value.as_ref()?;
            sw.values.iter().position(|s| s == val).map(|i| xs[i])
        };
        let x_label = if numeric {
            sw.key.clone()
        } else {
            format!("{} (index: {})", sw.key, sw.values.join(", "))
        };
        for (title, y_label, y) in [
            (
                "ꟻLIP mean",
                "ꟻLIP mean vs reference",
                &(|r: &Run| r.metrics.flip_mean) as &dyn Fn(&Run) -> f64,
            ),
            ("RMSE", "RMSE (sRGB 0..1)", &|r: &Run| r.metrics.rmse),
            ("cost", cost_label(report), &|r: &Run| cost_ms(&r.timing)),
        ] {
            charts.push(svg(&Chart {
                title: format!("{}: {title} vs {}", scene.name, sw.key),
                x_label: x_label.clone(),
                y_label: y_label.into(),
                note: None,
                series: series(y, &x_of, false)
                    .into_iter()
                    .filter(|s| !s.points.is_empty())
                    .collect(),
            }));
        }
    }
    charts
}
