//! The report as Markdown tables (`report.md`): one table per scene, one row
//! per variant — what the book's gallery tables are made from
//! (`scripts/gallery.sh`), so no figure there is typed by hand.

use std::fmt::Write as _;

use super::{Report, cost_ms};

/// `| variant | frame GPU ms | × reference | peak MiB | mean / max |ΔV| | RMSE | SSIM | FLIP |`
/// per scene; |ΔV| only where the variants were probed. With
/// `--camera-distance`, first a table per scene of error and frame time
/// against the distance ([`super::distance_markdown`]).
pub fn markdown(report: &Report) -> String {
    let mut out = String::new();
    let timing = if report.provenance.timestamps {
        "frame GPU ms"
    } else {
        "frame wall ms"
    };
    let _ = writeln!(
        out,
        "<!-- made by plait ab ({} repeat{}, {}×{}, {}) -->",
        report.provenance.repeats,
        if report.provenance.repeats == 1 {
            ""
        } else {
            "s"
        },
        report.provenance.size[0],
        report.provenance.size[1],
        report.provenance.adapter.name
    );
    out.push_str(&super::distance::distance_markdown(report));
    for scene in &report.scenes {
        // A provider probed against itself (every variant sharing the
        // reference's self-shadowing) says nothing: no |ΔV| column then.
        let probed = scene.runs.iter().any(|r| {
            r.visibility
                .as_ref()
                .is_some_and(|v| v.provider != v.reference_provider)
        });
        let reference_ms = scene
            .runs
            .iter()
            .find(|r| report.variant(&r.variant).is_some_and(|v| v.is_reference))
            .map(|r| cost_ms(&r.timing));
        // The scene's name alone on its line: the book reads tables by it.
        let color = scene
            .hair_color
            .map(|c| format!("Every strand's colour {c:?}. "))
            .unwrap_or_default();
        let _ = writeln!(
            out,
            "\n**{}**\n\n{color}{}\n",
            scene.name,
            scene.metrics_note()
        );
        let apart = report.timed_apart(scene);
        if let Some(note) = report.timed_apart_note(scene) {
            let _ = writeln!(out, "{note}\n");
        }
        let reference_shard = scene
            .runs
            .iter()
            .find(|r| report.variant(&r.variant).is_some_and(|v| v.is_reference))
            .and_then(|r| r.shard);
        let _ = write!(
            out,
            "| variant | {timing} | × faster than the reference | peak MiB |"
        );
        if probed {
            out.push_str(" mean / max \\|ΔV\\| |");
        }
        out.push_str(" RMSE | SSIM | FLIP |");
        let temporal = scene.runs.iter().any(|r| r.temporal.is_some());
        if temporal {
            out.push_str(" image flicker | visibility flicker |");
        }
        // Only a size the user capped drops: a column then, never silence.
        let dropping = scene
            .runs
            .iter()
            .any(|r| r.overflow.iter().any(|o| o.dropped > 0));
        if dropping {
            out.push_str(" dropped |");
        }
        out.push_str("\n|---|---:|---:|---:|");
        if probed {
            out.push_str("---:|");
        }
        out.push_str("---:|---:|---:|");
        if temporal {
            out.push_str("---:|---:|");
        }
        if dropping {
            out.push_str("---:|");
        }
        out.push('\n');
        for run in &scene.runs {
            let Some(variant) = report.variant(&run.variant) else {
                continue;
            };
            let ms = cost_ms(&run.timing);
            let mut speedup = reference_ms.map_or(String::new(), |r| format!("{:.1}", r / ms));
            let mut ms_cell = format!("{ms:.0}");
            if apart && let Some(on) = report.timed_on(run) {
                ms_cell = format!("{ms_cell} ({on})");
                if run.shard != reference_shard {
                    speedup = format!("{speedup} (across shards)");
                }
            }
            let _ = write!(
                out,
                "| {}{} | {} | {} | {:.1} |",
                variant.label,
                if variant.is_reference && !variant.label.contains("reference") {
                    " (reference)"
                } else {
                    ""
                },
                ms_cell,
                speedup,
                variant.memory.peak_bytes as f64 / (1u64 << 20) as f64
            );
            if probed {
                match &run.visibility {
                    Some(v) => {
                        let _ = write!(out, " {:.4} / {:.2} |", v.mean_abs_error, v.max_abs_error);
                    }
                    None => out.push_str(" |"),
                }
            }
            let m = &run.metrics;
            let _ = write!(out, " {:.4} | {:.3} | {:.3} |", m.rmse, m.ssim, m.flip_mean);
            if temporal {
                match &run.temporal {
                    Some(t) => {
                        let visibility = t
                            .visibility_flicker_mean
                            .map_or(String::new(), |v| format!("{v:.5}"));
                        let _ = write!(out, " {:.5} | {visibility} |", t.image_flicker_mean);
                    }
                    None => out.push_str(" | |"),
                }
            }
            if dropping {
                let dropped: u64 = run.overflow.iter().map(|o| o.dropped).sum();
                let _ = write!(out, " {dropped} |");
            }
            out.push('\n');
        }
    }
    out
}
