//! The A/B report: the data of `report.json` and its rendering as one
//! self-contained `report.html` (inline CSS, JS and SVG; images referenced
//! relatively from the report's directory, so it opens from disk offline).
//!
//! # `report.json` (schema `plait-ab/1`)
//! ```text
//! { schema, provenance {…}, sweep: {key, values} | null,
//!   variants: [ {id, label, pipeline, is_reference, sweep_value, sets, schedule_name,
//!                memory {peak_bytes, unpooled_bytes, allocations, resources: [{name, desc, bytes, shares_memory_with}]},
//!                graph_svg: file name | null} ],
//!   scenes: [ {name, path, reference_image,
//!              runs: [ {variant, image, diff_image, flip_image, diff_scale,
//!                       timing {total_gpu_ms: Stats|null, wall_ms: Stats, passes: [{name, type_name, gpu_ms: Stats|null}]},
//!                       metrics {rmse, psnr_db, ssim, flip_mean, max_abs_diff},
//!                       visibility: Visibility | null} ] } ] }
//! ```
//! `Stats` is `{median, min, max, q1, q3, samples}` in milliseconds.
//!
//! `visibility` is reserved for self-shadowing error (Figure 5 of the
//! occupancy-map paper): for variants whose pipeline produces a visibility
//! provider, curves of visibility against depth for sampled light texels
//! (exact and reconstructed) with the mean and max absolute error over the
//! hair fragments. `plait ab` does not compute it yet and writes `null`; the
//! HTML report draws the curves whenever it is filled.

use std::fmt::Write as _;

use serde::Serialize;

use crate::plot::{Chart, Point, Series, escape, svg};
use crate::{Metrics, Stats};

pub const SCHEMA: &str = "plait-ab/1";

#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub schema: String,
    pub provenance: Provenance,
    pub sweep: Option<Sweep>,
    pub variants: Vec<Variant>,
    pub scenes: Vec<SceneResult>,
}

/// Where the numbers came from.
#[derive(Clone, Debug, Serialize)]
pub struct Provenance {
    pub plait_version: String,
    pub adapter: Adapter,
    /// Whether per-pass GPU times come from timestamp queries.
    pub timestamps: bool,
    /// `argv`, exactly, and as one shell-quoted line.
    pub command: Vec<String>,
    pub command_line: String,
    pub working_directory: String,
    pub size: [u32; 2],
    pub repeats: u32,
    /// Frames rendered per variant before timing (excluded).
    pub warmup_frames: u32,
    /// `interleaved`: repeat r renders every variant once, in order, before repeat r+1.
    pub order: String,
    pub sets: Vec<String>,
    pub reference: String,
    pub metrics: String,
    pub pipelines: Vec<PipelineProvenance>,
    /// Shader modules compiled into the binary (the `plait::` import library and pass types' own WGSL).
    pub builtin_shaders: Vec<FileHash>,
    pub scenes: Vec<FileHash>,
    pub unix_time: u64,
}

#[derive(Clone, Debug, Serialize)]
pub struct Adapter {
    pub name: String,
    pub backend: String,
    pub driver: String,
    pub driver_info: String,
}

#[derive(Clone, Debug, Serialize)]
pub struct PipelineProvenance {
    pub path: String,
    /// The pipeline file and every file it extends.
    pub files: Vec<FileHash>,
    /// WGSL files named by its passes.
    pub shaders: Vec<FileHash>,
}

#[derive(Clone, Debug, Serialize, PartialEq, Eq)]
pub struct FileHash {
    pub path: String,
    pub sha256: String,
    pub bytes: u64,
}

#[derive(Clone, Debug, Serialize)]
pub struct Sweep {
    pub key: String,
    pub values: Vec<String>,
}

/// One pipeline (at one sweep value), or the reference.
#[derive(Clone, Debug, Serialize)]
pub struct Variant {
    pub id: String,
    pub label: String,
    pub pipeline: String,
    pub is_reference: bool,
    pub sweep_value: Option<String>,
    /// Every `--set` applied (the sweep's last).
    pub sets: Vec<String>,
    pub schedule_name: String,
    pub memory: Memory,
    /// File name of the schedule's picture (also inlined in the HTML).
    pub graph_svg: Option<String>,
}

#[derive(Clone, Debug, Serialize)]
pub struct Memory {
    /// Bytes of all allocations, with sharing.
    pub peak_bytes: u64,
    /// Bytes if no resource shared an allocation.
    pub unpooled_bytes: u64,
    pub allocations: usize,
    pub resources: Vec<ResourceMemory>,
}

#[derive(Clone, Debug, Serialize)]
pub struct ResourceMemory {
    pub name: String,
    pub desc: String,
    pub bytes: u64,
    pub shares_memory_with: Vec<String>,
}

#[derive(Clone, Debug, Serialize)]
pub struct SceneResult {
    pub name: String,
    /// `null` for the built-in default scene.
    pub path: Option<String>,
    pub reference_image: String,
    pub runs: Vec<Run>,
}

/// One variant on one scene.
#[derive(Clone, Debug, Serialize)]
pub struct Run {
    pub variant: String,
    pub image: String,
    /// |RGB difference| heat map, 0 → `diff_scale`.
    pub diff_image: String,
    pub diff_scale: f64,
    /// ꟻLIP error map, 0 → 1.
    pub flip_image: String,
    pub timing: Timing,
    pub metrics: Metrics,
    pub visibility: Option<Visibility>,
}

#[derive(Clone, Debug, Serialize)]
pub struct Timing {
    /// First timestamp to last, over the repeats; `null` without timestamp queries.
    pub total_gpu_ms: Option<Stats>,
    /// `Renderer::render` on the CPU clock (submit + wait), over the repeats.
    pub wall_ms: Stats,
    pub passes: Vec<PassStats>,
}

#[derive(Clone, Debug, Serialize)]
pub struct PassStats {
    pub name: String,
    pub type_name: String,
    pub gpu_ms: Option<Stats>,
}

/// Self-shadowing error of one variant: its visibility provider probed along
/// rays from the light through the hair, against the reference's.
#[derive(Clone, Debug, Serialize)]
pub struct Visibility {
    /// The variant's provider (`occupancy`, `deep_opacity`, …).
    pub provider: String,
    /// The reference's provider (`exact` for `reference.toml`).
    pub reference_provider: String,
    /// Probe rays along which the reference sees hair; the errors are over their samples.
    pub rays_through_hair: usize,
    /// The rays through the most hair.
    pub curves: Vec<VisibilityCurve>,
    pub mean_abs_error: f64,
    pub max_abs_error: f64,
}

/// Visibility against light depth along one ray from the light.
#[derive(Clone, Debug, Serialize)]
pub struct VisibilityCurve {
    /// Where the ray crosses the light map (0..1, y down).
    pub light_uv: [f32; 2],
    /// Light NDC depth of each sample, spanning the hair.
    pub depth: Vec<f64>,
    /// The reference's visibility.
    pub exact: Vec<f64>,
    /// The variant's visibility.
    pub approx: Vec<f64>,
}

impl Report {
    pub fn variant(&self, id: &str) -> Option<&Variant> {
        self.variants.iter().find(|v| v.id == id)
    }
}

/// The cost used on plots: median total GPU ms, else median wall ms.
pub fn cost_ms(t: &Timing) -> f64 {
    t.total_gpu_ms
        .as_ref()
        .map(|s| s.median)
        .unwrap_or(t.wall_ms.median)
}

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

impl Variant {
    /// The pipeline's file stem (`forward` for `pipelines/forward.toml`).
    pub fn pipeline_stem(&self) -> String {
        std::path::Path::new(&self.pipeline)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| self.pipeline.clone())
    }
}

fn ms(s: &Option<Stats>) -> String {
    match s {
        Some(s) => format!("{:.3}", s.median),
        None => "n/a".into(),
    }
}

fn spread(s: &Option<Stats>) -> String {
    match s {
        Some(s) => format!("{:.3}–{:.3} (IQR {:.3}–{:.3})", s.min, s.max, s.q1, s.q3),
        None => String::new(),
    }
}

fn mib(b: u64) -> String {
    format!("{:.2}", b as f64 / 1048576.0)
}

fn num(v: f64, digits: usize) -> String {
    format!("{v:.digits$}")
}

const CSS: &str = r#"
body{font-family:system-ui,sans-serif;margin:1.5em;color:#222;max-width:1400px}
h1{font-size:1.5em}h2{margin-top:2em;border-bottom:1px solid #ccc}h3{margin-top:1.5em}
table{border-collapse:collapse;margin:.5em 0;font-size:13px}
td,th{border:1px solid #ccc;padding:3px 7px;text-align:right}th{background:#f3f3f3}
td.l,th.l{text-align:left}
tr.ref td{background:#f8f8e8}
.grid{display:flex;flex-wrap:wrap;gap:14px}
figure{margin:0;display:inline-block;vertical-align:top}
figcaption{font-size:12px;max-width:420px}
.img{image-rendering:pixelated;border:1px solid #999;display:block}
.flip{cursor:pointer;position:relative}
.flip .ref{display:none}.flip.showref .ref{display:block}.flip.showref .var{display:none}
.flip .tag{position:absolute;left:4px;top:4px;background:rgba(0,0,0,.6);color:#fff;font-size:11px;padding:1px 4px}
.flip .tag.r{display:none}.flip.showref .tag.r{display:block}.flip.showref .tag.v{display:none}
.legend{display:flex;justify-content:space-between;font-size:11px}
.graph svg{max-width:100%;height:auto;border:1px solid #ddd}
code{background:#f4f4f4;padding:0 3px}
.note{color:#555;font-size:13px}
"#;

const JS: &str = r#"
function flipOne(e){e.currentTarget.classList.toggle('showref')}
document.querySelectorAll('.flip').forEach(function(f){f.addEventListener('click',flipOne)});
document.addEventListener('keydown',function(e){if(e.key==='f'){document.querySelectorAll('.flip').forEach(function(f){f.classList.toggle('showref')})}});
function zoom(z){document.querySelectorAll('.img').forEach(function(i){i.style.width=(i.naturalWidth*z)+'px'})}
"#;

/// The whole report as one HTML page. `graphs` maps a variant id to the
/// inline SVG picture of its schedule.
pub fn html(report: &Report, graphs: &[(String, String)]) -> String {
    let p = &report.provenance;
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>plait ab report</title><style>{CSS}</style></head><body>"
    );
    let _ = write!(
        h,
        "<h1>plait ab: {} variant(s) vs <code>{}</code></h1>",
        report.variants.iter().filter(|v| !v.is_reference).count(),
        escape(&p.reference)
    );
    let _ = write!(
        h,
        "<p class=\"note\">{}×{} px, {} timed repeat(s) per variant after {} warm-up frame(s), {} order, on {} ({}). Metrics: {}</p>",
        p.size[0],
        p.size[1],
        p.repeats,
        p.warmup_frames,
        escape(&p.order),
        escape(&p.adapter.name),
        escape(&p.adapter.backend),
        escape(&p.metrics)
    );
    h.push_str("<p class=\"note\">Click an image (or press <b>f</b> for all) to flip between the variant and the reference. Zoom: <a href=\"#\" onclick=\"zoom(1);return false\">1×</a> <a href=\"#\" onclick=\"zoom(2);return false\">2×</a> <a href=\"#\" onclick=\"zoom(3);return false\">3×</a></p>");

    for scene in &report.scenes {
        let _ = write!(h, "<h2>Scene {}</h2>", escape(&scene.name));
        // Summary table.
        h.push_str("<table><tr><th class=l>variant</th><th class=l>sweep</th><th>frame ms (median)</th><th class=l>spread min–max (IQR)</th><th>wall ms</th><th>peak MiB</th><th>unpooled MiB</th><th>RMSE</th><th>PSNR dB</th><th>SSIM</th><th>ꟻLIP</th></tr>");
        for run in &scene.runs {
            let Some(v) = report.variant(&run.variant) else {
                continue;
            };
            let m = &run.metrics;
            let _ = write!(
                h,
                "<tr{}><td class=l>{}</td><td class=l>{}</td><td>{}</td><td class=l>{}</td><td>{:.3}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                if v.is_reference { " class=ref" } else { "" },
                escape(&v.label),
                escape(v.sweep_value.as_deref().unwrap_or("")),
                ms(&run.timing.total_gpu_ms),
                spread(&run.timing.total_gpu_ms),
                run.timing.wall_ms.median,
                mib(v.memory.peak_bytes),
                mib(v.memory.unpooled_bytes),
                num(m.rmse, 5),
                m.psnr_db.map(|x| num(x, 2)).unwrap_or_else(|| "∞".into()),
                num(m.ssim, 5),
                num(m.flip_mean, 5)
            );
        }
        h.push_str("</table>");

        // Images.
        let _ = write!(
            h,
            "<h3>Images</h3><div class=grid><figure><img class=img src=\"{}\" alt=\"reference\"><figcaption><b>reference</b>: {}</figcaption></figure></div>",
            escape(&scene.reference_image),
            escape(&p.reference)
        );
        for run in &scene.runs {
            let Some(v) = report.variant(&run.variant) else {
                continue;
            };
            if v.is_reference {
                continue;
            }
            let _ = write!(
                h,
                "<h4>{}</h4><div class=grid><figure class=flip><span class='tag v'>variant</span><span class='tag r'>reference</span><img class='img var' src=\"{}\" alt=\"{}\"><img class='img ref' src=\"{}\" alt=\"reference\"><figcaption>{} — click to flip with the reference</figcaption></figure>",
                escape(&v.label),
                escape(&run.image),
                escape(&v.label),
                escape(&scene.reference_image),
                escape(&v.label)
            );
            let _ = write!(
                h,
                "<figure><img class=img src=\"{}\" alt=\"difference\"><div class=legend><span>0</span><span>|Δ| mean RGB</span><span>{}</span></div><figcaption>absolute difference (max {:.4})</figcaption></figure>",
                escape(&run.diff_image),
                run.diff_scale,
                run.metrics.max_abs_diff
            );
            let _ = write!(
                h,
                "<figure><img class=img src=\"{}\" alt=\"FLIP\"><div class=legend><span>0</span><span>ꟻLIP</span><span>1</span></div><figcaption>ꟻLIP error map (mean {:.4})</figcaption></figure></div>",
                escape(&run.flip_image),
                run.metrics.flip_mean
            );
        }

        // Plots.
        h.push_str("<h3>Error vs cost</h3><div class=grid>");
        for c in scene_charts(report, scene) {
            h.push_str(&c);
        }
        h.push_str("</div>");

        // Per-pass times.
        h.push_str("<h3>Per-pass GPU time (ms)</h3><table><tr><th class=l>variant</th><th class=l>pass</th><th class=l>type</th><th>median</th><th>min</th><th>max</th><th>q1</th><th>q3</th></tr>");
        for run in &scene.runs {
            let Some(v) = report.variant(&run.variant) else {
                continue;
            };
            let rows = run
                .timing
                .passes
                .iter()
                .map(|ps| (ps.name.as_str(), ps.type_name.as_str(), &ps.gpu_ms))
                .chain(std::iter::once(("frame", "", &run.timing.total_gpu_ms)));
            for (name, ty, s) in rows {
                let cells = match s {
                    Some(s) => format!(
                        "<td>{:.3}</td><td>{:.3}</td><td>{:.3}</td><td>{:.3}</td><td>{:.3}</td>",
                        s.median, s.min, s.max, s.q1, s.q3
                    ),
                    None => "<td colspan=5>n/a (no timestamp queries)</td>".into(),
                };
                let bold = if name == "frame" {
                    " style=\"font-weight:bold\""
                } else {
                    ""
                };
                let _ = write!(
                    h,
                    "<tr{bold}><td class=l>{}</td><td class=l>{}</td><td class=l>{}</td>{cells}</tr>",
                    escape(&v.label),
                    escape(name),
                    escape(ty)
                );
            }
        }
        h.push_str("</table>");

        // Visibility (reserved).
        h.push_str("<h3>Self-shadowing visibility</h3>");
        let mut any = false;
        for run in &scene.runs {
            let (Some(vis), Some(v)) = (&run.visibility, report.variant(&run.variant)) else {
                continue;
            };
            any = true;
            if renders_like_the_reference(report, v) {
                // The reference's provider against itself: curves on top of
                // each other, differing only by noise. Say so instead.
                let _ = write!(
                    h,
                    "<p>{} ({}): the reference itself — no curves to compare</p>",
                    escape(&v.label),
                    escape(&vis.provider)
                );
                continue;
            }
            let _ = write!(
                h,
                "<p>{} ({}): mean |ΔV| {:.4}, max |ΔV| {:.4} over {} rays through the hair</p><div class=grid>",
                escape(&v.label),
                escape(&vis.provider),
                vis.mean_abs_error,
                vis.max_abs_error,
                vis.rays_through_hair
            );
            for c in &vis.curves {
                let line = |name: &str, ys: &[f64]| Series {
                    name: name.into(),
                    line: true,
                    points: c
                        .depth
                        .iter()
                        .zip(ys)
                        .map(|(&x, &y)| Point {
                            x,
                            y,
                            size: Some(2.0),
                            label: None,
                        })
                        .collect(),
                };
                h.push_str(&svg(&Chart {
                    title: format!(
                        "{}: light uv ({:.2}, {:.2})",
                        v.label, c.light_uv[0], c.light_uv[1]
                    ),
                    x_label: "light depth (NDC)".into(),
                    y_label: "visibility".into(),
                    note: None,
                    series: vec![
                        line(&format!("reference ({})", vis.reference_provider), &c.exact),
                        line(&v.label, &c.approx),
                    ],
                }));
            }
            h.push_str("</div>");
        }
        if !any {
            h.push_str("<p class=note>Not computed: the reference pipeline has no visibility provider (use one with self-shadowing, e.g. <code>reference.toml</code>).</p>");
        }
    }

    // Memory.
    h.push_str("<h2>Memory</h2>");
    for v in &report.variants {
        let _ = write!(
            h,
            "<h4>{}</h4><p class=note>peak {} MiB in {} allocation(s) ({} MiB without sharing)</p><table><tr><th class=l>resource</th><th class=l>descriptor</th><th>bytes</th><th>MiB</th><th class=l>shares memory with</th></tr>",
            escape(&v.label),
            mib(v.memory.peak_bytes),
            v.memory.allocations,
            mib(v.memory.unpooled_bytes)
        );
        for r in &v.memory.resources {
            let _ = write!(
                h,
                "<tr><td class=l>{}</td><td class=l>{}</td><td>{}</td><td>{}</td><td class=l>{}</td></tr>",
                escape(&r.name),
                escape(&r.desc),
                r.bytes,
                mib(r.bytes),
                escape(&r.shares_memory_with.join(", "))
            );
        }
        h.push_str("</table>");
    }

    // Graphs, at their own size (a few hundred pixels: readable as they are).
    h.push_str("<h2>Pipelines</h2><div class=grid>");
    for (id, graph) in graphs {
        let label = report
            .variant(id)
            .map(|v| v.label.clone())
            .unwrap_or_else(|| id.clone());
        let _ = write!(
            h,
            "<div><h4>{}</h4><div class=graph>{}</div></div>",
            escape(&label),
            strip_xml_prolog(graph)
        );
    }
    h.push_str("</div>");

    // Provenance.
    h.push_str("<h2>Provenance</h2><table>");
    let row = |h: &mut String, k: &str, v: &str| {
        let _ = write!(
            h,
            "<tr><th class=l>{}</th><td class=l><code>{}</code></td></tr>",
            escape(k),
            escape(v)
        );
    };
    row(&mut h, "plait version", &p.plait_version);
    row(
        &mut h,
        "adapter",
        &format!(
            "{} ({}; {} {})",
            p.adapter.name, p.adapter.backend, p.adapter.driver, p.adapter.driver_info
        ),
    );
    row(
        &mut h,
        "GPU timestamps",
        if p.timestamps { "yes" } else { "no" },
    );
    row(&mut h, "command", &p.command_line);
    row(&mut h, "working directory", &p.working_directory);
    row(&mut h, "--set", &p.sets.join(" "));
    if let Some(sw) = &report.sweep {
        row(
            &mut h,
            "--sweep",
            &format!("{}={}", sw.key, sw.values.join(",")),
        );
    }
    for s in &p.scenes {
        row(&mut h, "scene", &format!("{}  sha256 {}", s.path, s.sha256));
    }
    for (f, users) in provenance_files(p) {
        row(
            &mut h,
            &format!("file of {}", users.join(", ")),
            &format!("{}  sha256 {}", f.path, f.sha256),
        );
    }
    for f in &p.builtin_shaders {
        row(
            &mut h,
            "built-in shader",
            &format!("{}  sha256 {}", f.path, f.sha256),
        );
    }
    h.push_str("</table><p class=note>Every number above is in report.json.</p>");
    let _ = write!(h, "<script>{JS}</script></body></html>");
    h
}

/// Whether `v` renders exactly what the reference renders: the reference
/// itself, or the same pipeline file with the same `--set`s.
fn renders_like_the_reference(report: &Report, v: &Variant) -> bool {
    v.is_reference
        || report
            .variants
            .iter()
            .find(|r| r.is_reference)
            .is_some_and(|r| r.pipeline == v.pipeline && r.sets == v.sets)
}

/// Every pipeline file and shader once (pipelines that extend one base, or
/// share shaders, name the same file), with the pipelines that use it.
fn provenance_files(p: &Provenance) -> Vec<(&FileHash, Vec<&str>)> {
    let mut out: Vec<(&FileHash, Vec<&str>)> = Vec::new();
    for pp in &p.pipelines {
        for f in pp.files.iter().chain(&pp.shaders) {
            match out.iter_mut().find(|(seen, _)| *seen == f) {
                Some((_, users)) => {
                    if !users.contains(&pp.path.as_str()) {
                        users.push(&pp.path);
                    }
                }
                None => out.push((f, vec![&pp.path])),
            }
        }
    }
    out
}

fn strip_xml_prolog(svg: &str) -> &str {
    match svg.find("<svg") {
        Some(i) => &svg[i..],
        None => svg,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stats(v: f64) -> Stats {
        Stats::of(&[v, v + 1.0]).unwrap()
    }

    fn sample() -> Report {
        let variant = |id: &str, reference: bool, sweep: Option<&str>| Variant {
            id: id.into(),
            label: id.into(),
            pipeline: "pipelines/forward.toml".into(),
            is_reference: reference,
            sweep_value: sweep.map(str::to_string),
            sets: vec![],
            schedule_name: "forward".into(),
            memory: Memory {
                peak_bytes: 1 << 20,
                unpooled_bytes: 2 << 20,
                allocations: 2,
                resources: vec![],
            },
            graph_svg: None,
        };
        let run = |id: &str, flip: f64| Run {
            variant: id.into(),
            image: format!("{id}.png"),
            diff_image: "d.png".into(),
            diff_scale: 1.0,
            flip_image: "f.png".into(),
            timing: Timing {
                total_gpu_ms: Some(stats(2.0)),
                wall_ms: stats(3.0),
                passes: vec![PassStats {
                    name: "p".into(),
                    type_name: "t".into(),
                    gpu_ms: None,
                }],
            },
            metrics: Metrics {
                flip_mean: flip,
                ..Metrics::default()
            },
            visibility: None,
        };
        Report {
            schema: SCHEMA.into(),
            provenance: Provenance {
                plait_version: "0.1.0".into(),
                adapter: Adapter {
                    name: "lavapipe".into(),
                    backend: "vulkan".into(),
                    driver: String::new(),
                    driver_info: String::new(),
                },
                timestamps: true,
                command: vec!["plait".into()],
                command_line: "plait ab <x>".into(),
                working_directory: ".".into(),
                size: [4, 4],
                repeats: 2,
                warmup_frames: 1,
                order: "interleaved".into(),
                sets: vec![],
                reference: "pipelines/forward.toml".into(),
                metrics: String::new(),
                pipelines: vec![],
                builtin_shaders: vec![],
                scenes: vec![],
                unix_time: 0,
            },
            sweep: Some(Sweep {
                key: "params.x".into(),
                values: vec!["1".into(), "2".into()],
            }),
            variants: vec![
                variant("reference", true, None),
                variant("a@1", false, Some("1")),
                variant("a@2", false, Some("2")),
            ],
            scenes: vec![SceneResult {
                name: "s".into(),
                path: None,
                reference_image: "r.png".into(),
                runs: vec![run("reference", 0.0), run("a@1", 0.2), run("a@2", 0.1)],
            }],
        }
    }

    #[test]
    fn html_is_self_contained_and_escaped() {
        let r = sample();
        let page = html(
            &r,
            &[("a@1".into(), "<?xml version=\"1.0\"?><svg></svg>".into())],
        );
        assert!(page.contains("plait ab &lt;x&gt;"));
        assert!(!page.contains("<?xml"));
        assert!(!page.contains("<script src") && !page.contains("<link"));
        assert!(page.contains("a@1.png") && page.contains("r.png"));
        assert!(page.contains("Not computed"));
    }

    fn visibility(provider: &str) -> Visibility {
        Visibility {
            provider: provider.into(),
            reference_provider: "exact".into(),
            rays_through_hair: 3,
            curves: vec![VisibilityCurve {
                light_uv: [0.5, 0.5],
                depth: vec![0.1, 0.2],
                exact: vec![1.0, 0.5],
                approx: vec![1.0, 0.6],
            }],
            mean_abs_error: 0.05,
            max_abs_error: 0.1,
        }
    }

    /// The reference's provider plotted against itself is noise: the report
    /// says "the reference itself" instead; a real variant gets its curves.
    #[test]
    fn the_reference_gets_no_visibility_curves() {
        let mut r = sample();
        r.variants[1].pipeline = "pipelines/occupancy.toml".into();
        r.scenes[0].runs[0].visibility = Some(visibility("exact"));
        r.scenes[0].runs[1].visibility = Some(visibility("occupancy"));
        let page = html(&r, &[]);
        assert!(
            page.contains("reference (exact): the reference itself — no curves to compare"),
            "{page}"
        );
        assert!(page.contains("a@1: light uv"), "the variant's curve");
        assert!(
            !page.contains("reference: light uv"),
            "the reference's curve"
        );
        // The same pipeline as the reference (a@2 renders forward.toml too).
        r.scenes[0].runs[2].visibility = Some(visibility("exact"));
        r.variants[2].sets = r.variants[0].sets.clone();
        let page = html(&r, &[]);
        assert!(page.contains("a@2 (exact): the reference itself"), "{page}");
    }

    #[test]
    fn provenance_lists_each_file_once() {
        let mut r = sample();
        let file = |path: &str| FileHash {
            path: path.into(),
            sha256: format!("sha-of-{path}"),
            bytes: 1,
        };
        let pipeline = |path: &str, extra: &str| PipelineProvenance {
            path: path.into(),
            files: vec![file(path), file("pipelines/occupancy.toml")],
            shaders: vec![file(extra)],
        };
        r.provenance.pipelines = vec![
            pipeline("pipelines/deep_opacity.toml", "shaders/compose_over.wgsl"),
            pipeline("pipelines/exact_shadow.toml", "shaders/compose_over.wgsl"),
        ];
        let page = html(&r, &[]);
        assert_eq!(
            page.matches("<code>pipelines/occupancy.toml ").count(),
            1,
            "{page}"
        );
        assert_eq!(page.matches("<code>shaders/compose_over.wgsl ").count(), 1);
        assert!(page.contains("file of pipelines/deep_opacity.toml, pipelines/exact_shadow.toml"));
    }

    #[test]
    fn sweep_gives_extra_charts_and_json_has_nulls() {
        let r = sample();
        let charts = scene_charts(&r, &r.scenes[0]);
        assert_eq!(charts.len(), 4);
        let json = serde_json::to_value(&r).unwrap();
        assert!(json["scenes"][0]["runs"][0]["visibility"].is_null());
        assert_eq!(json["variants"].as_array().unwrap().len(), 3);
    }
}
