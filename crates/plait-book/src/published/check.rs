//! A published figure against today's measurement of it: every frame-time
//! ratio and every error metric, with today's spread, and whether it moved.
//!
//! Speed is compared as ratios within one run — each row's frame time over
//! the first row's of its scene, the two measured side by side — never as
//! milliseconds, which depend on the machine and its load. A ratio moved
//! when the published value lies outside today's spread (each side's
//! fastest and slowest repeat) widened by the figure's `speed_tolerance`.
//! Error metrics are deterministic on one driver, so they moved when they
//! differ by more than 2 % (or a small absolute floor for values near 0).

use std::fmt::Write as _;

use super::{Figure, Record, Row};

/// One compared value.
#[derive(Clone, Debug)]
pub struct Comparison {
    pub scene: String,
    pub variant: String,
    pub quantity: String,
    pub published: Option<f64>,
    pub today: Option<f64>,
    /// Today's range (equal to `today` for deterministic quantities).
    pub lo: f64,
    pub hi: f64,
    pub moved: bool,
}

/// Relative tolerance and absolute floor per error metric.
const METRICS: [(&str, f64, f64); 4] = [
    ("RMSE", 0.02, 0.0005),
    ("SSIM", 0.02, 0.002),
    ("FLIP", 0.02, 0.001),
    ("mean |ΔV|", 0.02, 0.0002),
];

fn metric(row: &Row, name: &str) -> Option<f64> {
    match name {
        "RMSE" => Some(row.rmse),
        "SSIM" => Some(row.ssim),
        "FLIP" => Some(row.flip),
        _ => row.mean_dv,
    }
}

/// Every value of `published` against `today`'s.
pub fn compare(figure: &Figure, published: &Record, today: &Record) -> Vec<Comparison> {
    if let (Some(p), Some(t)) = (&published.table, &today.table) {
        return super::table::compare(figure, p, t);
    }
    let mut out = Vec::new();
    let mut scenes = published.scenes();
    for s in today.scenes() {
        if !scenes.contains(&s) {
            scenes.push(s);
        }
    }
    for scene in scenes {
        let was: Vec<&Row> = published.scene_rows(scene).collect();
        let now: Vec<&Row> = today.scene_rows(scene).collect();
        // Speed is a ratio of two GPU frames of one run; a row timed otherwise
        // (a path-traced reference's CPU wall time) has no speed figure.
        let base = |rows: &[&Row]| rows.first().filter(|r| r.gpu_timed).map(|r| r.ms);
        let (was_base, now_base) = (base(&was), base(&now));
        // A scene's reference is one row on each side, whatever its label
        // says: a path-traced reference's label carries its own noise
        // ("… noise RMSE 0.0108 on small"), a measurement, not a name.
        let same = |a: &Row, b: &Row| a.variant == b.variant || (a.reference && b.reference);
        let mut variants: Vec<&Row> = was.clone();
        for r in &now {
            if !variants.iter().any(|v| same(v, r)) {
                variants.push(r);
            }
        }
        for (i, key) in variants.into_iter().enumerate() {
            let variant = key.variant.as_str();
            let p = was.iter().find(|r| same(r, key));
            let t = now.iter().find(|r| same(r, key));
            let row =
                |quantity: &str, published: Option<f64>, today: Option<f64>, lo, hi, moved| {
                    Comparison {
                        scene: scene.to_string(),
                        variant: variant.to_string(),
                        quantity: quantity.to_string(),
                        published,
                        today,
                        lo,
                        hi,
                        moved,
                    }
                };
            let (Some(p), Some(t)) = (p, t) else {
                // A row only one side has: the table changed shape.
                let (pv, tv) = (p.map(|r| r.rmse), t.map(|r| r.rmse));
                out.push(row("row present", pv, tv, f64::NAN, f64::NAN, true));
                continue;
            };
            if i > 0
                && p.gpu_timed
                && t.gpu_timed
                && let (Some(wb), Some(nb)) = (was_base, now_base)
            {
                let published = p.ms.median / wb.median;
                let today = t.ms.median / nb.median;
                let lo = t.ms.min / nb.max * (1.0 - figure.speed_tolerance);
                let hi = t.ms.max / nb.min * (1.0 + figure.speed_tolerance);
                let moved = !(lo..=hi).contains(&published);
                out.push(row(
                    "× first row's frame",
                    Some(published),
                    Some(today),
                    lo,
                    hi,
                    moved,
                ));
            }
            for (name, rel, abs) in METRICS {
                let (pv, tv) = (metric(p, name), metric(t, name));
                if pv.is_none() && tv.is_none() {
                    continue;
                }
                let moved = match (pv, tv) {
                    (Some(a), Some(b)) => (a - b).abs() > (rel * a.abs()).max(abs),
                    _ => true,
                };
                let today = tv.unwrap_or(f64::NAN);
                out.push(row(name, pv, tv, today, today, moved));
            }
        }
    }
    out
}

fn num(v: Option<f64>) -> String {
    match v {
        Some(v) if v.abs() >= 100.0 => format!("{v:.0}"),
        Some(v) if v.abs() >= 1.0 => format!("{v:.3}"),
        Some(v) => format!("{v:.4}"),
        None => "—".to_string(),
    }
}

/// The comparison as a plain-text table, every value on its line.
pub fn table(figure: &Figure, published: &Record, rows: &[Comparison]) -> String {
    let mut out = String::new();
    let moved = rows.iter().filter(|r| r.moved).count();
    let _ = writeln!(
        out,
        "figure {} ({}): published at {} on {}; {} values, {} moved",
        figure.id,
        figure.page,
        &published.commit[..published.commit.len().min(10)],
        published.date,
        rows.len(),
        moved
    );
    let _ = writeln!(
        out,
        "  {:<12} {:<34} {:<20} {:>10} {:>10} {:>21}  status",
        "scene", "variant", "quantity", "published", "today", "today's spread"
    );
    for r in rows {
        let spread = if r.lo.is_nan() {
            String::new()
        } else if r.lo == r.hi {
            "(deterministic)".to_string()
        } else {
            format!("{}–{}", num(Some(r.lo)), num(Some(r.hi)))
        };
        let _ = writeln!(
            out,
            "  {:<12} {:<34} {:<20} {:>10} {:>10} {:>21}  {}",
            r.scene,
            r.variant,
            r.quantity,
            num(r.published),
            num(r.today),
            spread,
            if r.moved { "MOVED" } else { "ok" }
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::record::Spread;
    use super::*;

    fn figure() -> Figure {
        Figure {
            id: "f".into(),
            page: "README.md".into(),
            command: vec!["ab".into()],
            kind: super::super::Kind::Ab,
            key: vec![],
            columns: Default::default(),
            measures: vec![],
            except: vec![],
            speed_tolerance: 0.10,
        }
    }

    fn row(variant: &str, ms: (f64, f64, f64), rmse: f64) -> Row {
        Row {
            scene: "small".into(),
            variant: variant.into(),
            reference: false,
            ms: Spread {
                median: ms.0,
                min: ms.1,
                max: ms.2,
            },
            gpu_timed: true,
            rmse,
            ssim: 0.99,
            flip: 0.01,
            mean_dv: None,
        }
    }

    fn record(rows: Vec<Row>) -> Record {
        Record {
            id: "f".into(),
            commit: "0123456789abcdef".into(),
            dirty: false,
            date: "2026-12-06".into(),
            adapter: "llvmpipe".into(),
            repeats: 3,
            command_line: "plait ab".into(),
            rows,
            table: None,
            markdown: String::new(),
        }
    }

    #[test]
    fn a_ratio_within_the_spread_holds_and_one_outside_moves() {
        let published = record(vec![
            row("fragment", (100.0, 100.0, 100.0), 0.02),
            row("strand", (74.0, 74.0, 74.0), 0.02),
        ]);
        // Today strand space is slower than per fragment: 0.74 published,
        // 1.02 today with a spread of 0.95–1.10 → moved.
        let slower = record(vec![
            row("fragment", (100.0, 98.0, 102.0), 0.02),
            row("strand", (102.0, 97.0, 105.0), 0.02),
        ]);
        let rows = compare(&figure(), &published, &slower);
        let speed = rows.iter().find(|r| r.quantity.starts_with('×')).unwrap();
        assert!(speed.moved, "{speed:?}");
        // Today 0.76 with the same noise: within spread and tolerance.
        let same = record(vec![
            row("fragment", (100.0, 98.0, 102.0), 0.02),
            row("strand", (76.0, 73.0, 79.0), 0.02),
        ]);
        let rows = compare(&figure(), &published, &same);
        assert!(rows.iter().all(|r| !r.moved), "{rows:?}");
    }

    #[test]
    fn a_row_timed_on_the_cpu_has_no_speed_figure_but_keeps_its_metrics() {
        // A path-traced reference: Mitsuba's wall time, 60 s published and
        // 6 s today (a cache hit, another load), beside GPU frames.
        let cpu = |ms: f64, rmse: f64| Row {
            gpu_timed: false,
            ..row("path_traced", (ms, ms, ms), rmse)
        };
        let published = record(vec![row("a", (50.0, 50.0, 50.0), 0.05), cpu(60_000.0, 0.0)]);
        let today = record(vec![row("a", (50.0, 49.0, 51.0), 0.05), cpu(6_000.0, 0.0)]);
        let rows = compare(&figure(), &published, &today);
        assert!(
            rows.iter().all(|r| !r.quantity.starts_with('×')),
            "{rows:?}"
        );
        assert!(rows.iter().all(|r| !r.moved), "{rows:?}");
        // First in its scene, it is no base for the GPU rows either.
        let published = record(vec![cpu(60_000.0, 0.0), row("a", (50.0, 50.0, 50.0), 0.05)]);
        let today = record(vec![cpu(6_000.0, 0.0), row("a", (50.0, 49.0, 51.0), 0.05)]);
        let rows = compare(&figure(), &published, &today);
        assert!(
            rows.iter().all(|r| !r.quantity.starts_with('×')),
            "{rows:?}"
        );
        // Its error metrics still count.
        let today = record(vec![cpu(6_000.0, 0.0), row("a", (50.0, 49.0, 51.0), 0.07)]);
        let rows = compare(&figure(), &published, &today);
        assert!(
            rows.iter().any(|r| r.moved && r.quantity == "RMSE"),
            "{rows:?}"
        );
    }

    #[test]
    fn a_reference_whose_label_carries_its_noise_is_the_same_row() {
        let reference = |label: &str| Row {
            reference: true,
            ..row(label, (60.0, 60.0, 60.0), 0.0)
        };
        let published = record(vec![
            row("a", (10.0, 10.0, 10.0), 0.02),
            reference("path_traced (noise RMSE 0.0108 on small)"),
        ]);
        let today = record(vec![
            row("a", (10.0, 10.0, 10.0), 0.02),
            reference("path_traced (noise RMSE 0.0105 on small)"),
        ]);
        let rows = compare(&figure(), &published, &today);
        assert!(rows.iter().all(|r| !r.moved), "{rows:?}");
        assert!(rows.iter().all(|r| r.quantity != "row present"), "{rows:?}");
        // A non-reference row renamed is still another row.
        let today = record(vec![
            row("b", (10.0, 10.0, 10.0), 0.02),
            reference("path_traced (noise RMSE 0.0105 on small)"),
        ]);
        let rows = compare(&figure(), &published, &today);
        assert_eq!(
            rows.iter().filter(|r| r.quantity == "row present").count(),
            2
        );
    }

    #[test]
    fn an_error_metric_that_changed_moves_and_a_missing_row_moves() {
        let published = record(vec![
            row("a", (10.0, 10.0, 10.0), 0.0200),
            row("b", (10.0, 10.0, 10.0), 0.0100),
        ]);
        let today = record(vec![
            row("a", (10.0, 10.0, 10.0), 0.0201),
            row("b", (10.0, 10.0, 10.0), 0.0130),
            row("c", (10.0, 10.0, 10.0), 0.0100),
        ]);
        let rows = compare(&figure(), &published, &today);
        let moved: Vec<(&str, &str)> = rows
            .iter()
            .filter(|r| r.moved)
            .map(|r| (r.variant.as_str(), r.quantity.as_str()))
            .collect();
        assert_eq!(moved, [("b", "RMSE"), ("c", "row present")]);
    }
}
