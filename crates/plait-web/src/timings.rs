//! The page's GPU-time table: the rows `plait render` prints (pass, type,
//! technique, GPU ms to three decimals; culled passes with their reason; a
//! last `frame` row), built here so the page and the CLI cannot drift.

use plait_gpu::FrameReport;
use plait_graph::Schedule;

/// One row of the table.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Row {
    pub pass: String,
    pub type_name: String,
    pub technique: String,
    /// `12.345`, `n/a` without a time, `culled`.
    pub gpu_ms: String,
    /// `(why it was culled)`, `(first frame's: runs once)`.
    pub note: Option<String>,
}

/// The table and what stands below it.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Timings {
    pub rows: Vec<Row>,
    /// Why there are no times ([`plait_gpu::timing::NO_TIMESTAMPS`]): the
    /// missing feature named; `None` when the adapter has timestamps.
    pub missing: Option<String>,
}

/// As `plait render` writes a time (`render_cmd.rs`'s `ms`).
fn ms(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.3}")).unwrap_or_else(|| "n/a".into())
}

impl Timings {
    /// The table of `report`, rendered from `schedule`, on a device that
    /// `timed` (has timestamp queries).
    pub fn of(schedule: &Schedule, report: &FrameReport, timed: bool) -> Timings {
        let technique = |p: &plait_graph::ScheduledPass| p.technique.clone().unwrap_or_default();
        let mut rows: Vec<Row> = schedule
            .passes
            .iter()
            .zip(&report.passes)
            .map(|(p, t)| Row {
                pass: p.name.clone(),
                type_name: p.type_name.clone(),
                technique: technique(p),
                gpu_ms: ms(t.gpu_ms),
                note: t
                    .cached
                    .then(|| "(the first frame's: runs once)".to_owned()),
            })
            .collect();
        rows.extend(schedule.culled.iter().map(|c| Row {
            pass: c.pass.name.clone(),
            type_name: c.pass.type_name.clone(),
            technique: technique(&c.pass),
            gpu_ms: "culled".into(),
            note: Some(format!("({})", c.reason)),
        }));
        rows.push(Row {
            pass: "frame".into(),
            type_name: String::new(),
            technique: String::new(),
            gpu_ms: ms(report.total_gpu_ms),
            note: None,
        });
        Timings {
            rows,
            missing: (!timed).then(|| plait_gpu::timing::NO_TIMESTAMPS.to_owned()),
        }
    }
}
