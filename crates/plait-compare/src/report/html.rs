//! `report.html`: one self-contained page.

use std::fmt::Write as _;

use crate::Stats;
use crate::plot::{Chart, Point, Series, escape, svg};

use super::charts::{cost_label, grid_cells, grid_pipelines};
use super::{FileHash, Provenance, Report, Run, SceneResult, Variant, cost_ms, scene_charts};

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
        "<p class=\"note\">{}×{} px, {} timed repeat(s) per variant{} after {} warm-up frame(s), {} order, on {} ({}). Metrics: {}</p>",
        p.size[0],
        p.size[1],
        p.repeats,
        p.reference_repeats
            .map(|n| format!(" ({n} for the reference)"))
            .unwrap_or_default(),
        p.warmup_frames,
        escape(&p.order),
        escape(&p.adapter.name),
        escape(&p.adapter.backend),
        escape(&p.metrics)
    );
    if !report.shards.is_empty() {
        let list: Vec<String> = report
            .shards
            .iter()
            .map(|s| format!("shard {} on {} ({})", s.index, s.machine, s.adapter.name))
            .collect();
        let _ = write!(
            h,
            "<p class=note>Merged from {} shards (<code>plait ab --shard</code>): {}. Each row was rendered and timed by its shard.</p>",
            report.shards.len(),
            escape(&list.join("; "))
        );
    }
    h.push_str("<p class=\"note\">Click an image (or press <b>f</b> for all) to flip between the variant and the reference. Zoom: <a href=\"#\" onclick=\"zoom(1);return false\">1×</a> <a href=\"#\" onclick=\"zoom(2);return false\">2×</a> <a href=\"#\" onclick=\"zoom(3);return false\">3×</a></p>");

    h.push_str(&super::distance::distance_html(report));

    for scene in &report.scenes {
        let _ = write!(
            h,
            "<h2>Scene {}</h2><p class=note>{}{}</p>",
            escape(&scene.name),
            scene
                .hair_color
                .map(|c| format!("Every strand's colour {c:?}. "))
                .unwrap_or_default(),
            escape(&scene.metrics_note())
        );
        if let Some(note) = report.timed_apart_note(scene) {
            let _ = write!(h, "<p class=note><b>{}</b></p>", escape(&note));
        }
        let apart = report.timed_apart(scene);
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
                escape(&v.sweep_label().unwrap_or_default()),
                match report.timed_on(run).filter(|_| apart) {
                    Some(on) => format!(
                        "{} <small>({})</small>",
                        ms(&run.timing.total_gpu_ms),
                        escape(&on)
                    ),
                    None => ms(&run.timing.total_gpu_ms),
                },
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
        h.push_str(&grid_tables(report, scene));

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
                "<figure><img class=img src=\"{}\" alt=\"difference\"><div class=legend><span>0</span><span>|Δ| mean RGB</span><span>{}</span></div><figcaption>absolute difference, {} (max {:.4})</figcaption></figure>",
                escape(&run.diff_image),
                run.diff_scale,
                run.metrics.error_space.words(),
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
        overflow_table(&mut h, report, scene);

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
        temporal_table(&mut h, report, scene);
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
    for sw in &report.sweeps {
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

/// A number of a run as a grid table shows it: title, digits, value.
type Measure<'a> = (&'a str, usize, &'a dyn Fn(&Run) -> Option<f64>);

/// With two sweeps, each pipeline's numbers as tables: a row per value of
/// the first sweep, a column per value of the second (empty without).
fn grid_tables(report: &Report, scene: &SceneResult) -> String {
    let [rows, columns] = report.sweeps.as_slice() else {
        return String::new();
    };
    let with_visibility = scene.runs.iter().any(|r| r.visibility.is_some());
    let mut measures: Vec<Measure<'_>> = vec![
        ("ꟻLIP mean", 5, &|r| Some(r.metrics.flip_mean)),
        ("RMSE", 5, &|r| Some(r.metrics.rmse)),
        (cost_label(report), 3, &|r| Some(cost_ms(&r.timing))),
    ];
    if with_visibility {
        measures.push(("mean |ΔV| (self-shadowing)", 4, &|r| {
            r.visibility.as_ref().map(|v| v.mean_abs_error)
        }));
    }
    let mut h = String::new();
    for pipeline in grid_pipelines(report) {
        let _ = write!(
            h,
            "<h4>{}: {} (rows) × {} (columns)</h4><div class=grid>",
            escape(pipeline),
            escape(&rows.key),
            escape(&columns.key)
        );
        for (what, digits, value) in &measures {
            let cells = grid_cells(report, scene, pipeline, *value);
            let _ = write!(
                h,
                "<table><caption style=\"text-align:left;font-weight:bold\">{}</caption><tr><th class=l>{} \\ {}</th>",
                escape(what),
                escape(&rows.key),
                escape(&columns.key)
            );
            for c in &columns.values {
                let _ = write!(h, "<th>{}</th>", escape(c));
            }
            h.push_str("</tr>");
            for (name, row) in rows.values.iter().zip(&cells) {
                let _ = write!(h, "<tr><th class=l>{}</th>", escape(name));
                for cell in row {
                    match cell {
                        Some(v) => {
                            let _ = write!(h, "<td>{}</td>", num(*v, *digits));
                        }
                        None => h.push_str("<td>–</td>"),
                    }
                }
                h.push_str("</tr>");
            }
            h.push_str("</table>");
        }
        h.push_str("</div>");
    }
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

/// `--frames`: each variant's flicker against the reference's own change
/// (the plots over time are among the scene's charts).
/// Bounded buffers that declare an overflow counter: what each variant's
/// dropped at its worst frame (only a size the user capped drops).
fn overflow_table(h: &mut String, report: &Report, scene: &super::SceneResult) {
    if scene.runs.iter().all(|r| r.overflow.is_empty()) {
        return;
    }
    h.push_str("<h3>Bounded buffers</h3><p class=note>items each buffer could not hold, at the worst frame; 0 = it held everything</p>");
    h.push_str("<table><tr><th class=l>variant</th><th class=l>buffer</th><th class=l>pass</th><th>dropped</th><th>holds</th><th>needed</th><th class=l>size</th></tr>");
    for run in &scene.runs {
        let Some(v) = report.variant(&run.variant) else {
            continue;
        };
        for o in &run.overflow {
            let (style, needed, size) = if o.dropped > 0 {
                (
                    " style=\"color:#b00;font-weight:bold\"",
                    o.needed.to_string(),
                    format!("{}={} (needs {})", o.param, o.value, o.value_needed),
                )
            } else {
                ("", "–".into(), format!("{}={}", o.param, o.value))
            };
            let _ = write!(
                h,
                "<tr{style}><td class=l>{}</td><td class=l>{}</td><td class=l>{}</td><td>{}</td><td>{}</td><td>{needed}</td><td class=l>{}</td></tr>",
                escape(&v.label),
                escape(&o.of),
                escape(&o.pass),
                o.dropped,
                o.capacity,
                escape(&size)
            );
        }
    }
    h.push_str("</table>");
}

fn temporal_table(h: &mut String, report: &Report, scene: &super::SceneResult) {
    if !scene.runs.iter().any(|r| r.temporal.is_some()) {
        return;
    }
    h.push_str("<h3>Temporal stability</h3><p class=note>per frame transition, the change beyond the reference's own change: mean |(I<sub>t</sub> − I<sub>t−1</sub>) − (R<sub>t</sub> − R<sub>t−1</sub>)| over pixels and RGB (sRGB 0..1), and the same over the visibility probe samples; 0 = as stable as the reference</p>");
    h.push_str("<table><tr><th class=l>variant</th><th>frames</th><th>image flicker mean</th><th>max</th><th>own change mean</th><th>visibility flicker mean</th><th>max</th></tr>");
    for run in &scene.runs {
        let (Some(t), Some(v)) = (&run.temporal, report.variant(&run.variant)) else {
            continue;
        };
        let opt = |x: Option<f64>| x.map_or("–".to_string(), |x| format!("{x:.5}"));
        let _ = write!(
            h,
            "<tr><td class=l>{}</td><td>{}</td><td>{:.5}</td><td>{:.5}</td><td>{:.5}</td><td>{}</td><td>{}</td></tr>",
            escape(&v.label),
            t.frames,
            t.image_flicker_mean,
            t.image_flicker_max,
            t.image_change_mean,
            opt(t.visibility_flicker_mean),
            opt(t.visibility_flicker_max),
        );
    }
    h.push_str("</table>");
}
