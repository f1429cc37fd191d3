//! Measuring the picture before drawing it: the labels, the legend's
//! entries and the width they need.

use crate::schedule::{Schedule, ScheduledPass};

use super::{LEGEND_W, MARGIN, NOTES_X, bold_width, text_width};

/// Each row's pass name and type (marked culled).
pub(super) fn row_labels(rows: &[(&ScheduledPass, bool)]) -> Vec<(String, String)> {
    rows.iter()
        .map(|(p, culled)| {
            let kind = if *culled {
                format!("{} (culled)", p.type_name)
            } else {
                p.type_name.clone()
            };
            (p.name.clone(), kind)
        })
        .collect()
}

/// Where the pass types start and how wide the pass labels are.
pub(super) fn label_geometry(row_labels: &[(String, String)]) -> (f64, f64) {
    // Pass names in bold, their types in a second aligned column.
    let name_w = row_labels
        .iter()
        .map(|(n, _)| bold_width(n))
        .fold(0.0, f64::max);
    let kind_x = MARGIN + 8.0 + name_w + 10.0;
    let label_w = row_labels
        .iter()
        .map(|(_, k)| kind_x - MARGIN + text_width(k))
        .fold(text_width("output"), f64::max)
        + 14.0;
    (kind_x, label_w)
}

/// How wide a column header is: its bold name, then its description.
pub(super) fn header_len((n, d): &(String, String)) -> f64 {
    bold_width(n) + 8.0 + text_width(d)
}

/// A note per allocation shared by several resources.
pub(super) fn sharing_notes(schedule: &Schedule) -> Vec<String> {
    let mut notes = Vec::new();
    for physical in &schedule.physical {
        if physical.users.len() > 1 {
            let names: Vec<&str> = physical
                .users
                .iter()
                .map(|&u| schedule.resources[u].name.as_str())
                .collect();
            notes.push(format!("one allocation for {}", names.join(", ")));
        }
    }
    notes
}

/// The chosen techniques that have a pass among the rows, in `[techniques]`
/// order.
pub(super) fn technique_labels(
    schedule: &Schedule,
    rows: &[(&ScheduledPass, bool)],
) -> Vec<String> {
    // Each technique's passes share a tint, named in the legend: what a
    // `--set techniques.…` swap changes. A technique that adds no pass (it
    // only sets params, or culled nothing into the rows) has no tint to name.
    schedule
        .techniques
        .iter()
        .map(|t| t.label())
        .filter(|l| rows.iter().any(|(p, _)| p.technique.as_ref() == Some(l)))
        .collect()
}

/// Each technique's legend entry and its width.
pub(super) fn technique_entries(labels: &[String]) -> Vec<(String, f64)> {
    labels
        .iter()
        .map(|l| {
            let text = format!("technique {l}");
            let w = 16.0 + text_width(&text);
            (text, w)
        })
        .collect()
}

/// The picture's width: the grid and its headers, and everything the legend
/// writes.
pub(super) fn picture_width(header_right: f64, notes: &[String], entries: &[(String, f64)]) -> f64 {
    // Everything the legend writes fits the picture: its first line, the
    // notes beside the second, and at least the widest technique entry.
    [
        header_right + MARGIN,
        MARGIN * 2.0 + LEGEND_W,
        notes
            .iter()
            .map(|n| NOTES_X + text_width(n) + MARGIN)
            .fold(0.0, f64::max),
        entries
            .iter()
            .map(|(_, w)| MARGIN * 2.0 + w)
            .fold(0.0, f64::max),
    ]
    .into_iter()
    .fold(0.0, f64::max)
    .ceil()
}
