//! The schedule as an SVG picture that reads at a glance: passes are rows in
//! execution order, resources are columns in order of first use, and each
//! column's line is the resource's lifetime, from the pass that writes it to
//! the last pass that reads it (to the bottom for an output). A square marks
//! a write, a hollow circle a read, a filled circle a write that adds to what
//! is there (blending, atomics). Culled passes are dashed rows at the end.
//!
//! A grid needs no layout algorithm, so the picture is deterministic and as
//! compact as the schedule (24 px per resource, 30 px per pass), and every
//! mark sits on the row and column it belongs to: no label floats away from
//! its edge. Column headers are stacked like stairs, each with a leader down
//! to its column, so they need no rotated text. The SVG uses plain shapes
//! and one style per `<text>` (no CSS, markers, rotation or `<tspan>`), which
//! browsers, librsvg and ImageMagick's own renderer all draw alike.

use std::fmt::Write as _;

use crate::schedule::{Binding, DROPPED_RESOURCE, ResourceDesc, Schedule, ScheduledPass};
use crate::spec::ResourceKind;

const FONT: &str = "DejaVu Sans, Verdana, Arial, sans-serif";
const FONT_SIZE: f64 = 12.0;
/// Average advance of a character at `FONT_SIZE`, regular and bold (no font
/// metrics here; generous, so text never runs into its neighbour).
const CHAR_W: f64 = 7.0;
const BOLD_CHAR_W: f64 = 8.0;
/// Vertical step between the stacked column headers.
const HEADER_STEP: f64 = 16.0;
const ROW_H: f64 = 30.0;
const COL_W: f64 = 24.0;
const MARGIN: f64 = 12.0;
const TITLE_H: f64 = 28.0;
/// Width of the legend's first line (writes, reads, adds, culled).
const LEGEND_W: f64 = 560.0;
/// Where the notes beside the legend's second line start.
const NOTES_X: f64 = MARGIN + 220.0;
/// Space between two technique entries on a legend line.
const ENTRY_GAP: f64 = 18.0;

const TEXTURE_COLOUR: &str = "#2f6db5";
const BUFFER_COLOUR: &str = "#c0661a";
const GREY: &str = "#888888";
const GUIDE: &str = "#e4e4e4";

/// Fills of the pass labels of each chosen technique, in `[techniques]` order.
const TECHNIQUE_TINTS: &[&str] = &["#e3edfb", "#fcebd9", "#e2f2e5", "#efe3fa", "#fbf3d5"];

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn text_width(s: &str) -> f64 {
    s.chars().count() as f64 * CHAR_W
}

fn bold_width(s: &str) -> f64 {
    s.chars().count() as f64 * BOLD_CHAR_W
}

/// `rg32float 512×512`, `buffer 4 MiB`: short enough for a column header.
fn short_desc(desc: &ResourceDesc) -> String {
    match *desc {
        ResourceDesc::Texture {
            format,
            width,
            height,
            layers,
            samples,
        } => {
            let mut s = format!("{format} {width}×{height}");
            if layers > 1 {
                let _ = write!(s, "×{layers}");
            }
            if samples > 1 {
                let _ = write!(s, " {samples}×MSAA");
            }
            s
        }
        ResourceDesc::Buffer { size } => format!("buffer {}", bytes(size)),
    }
}

fn bytes(n: u64) -> String {
    const KIB: f64 = 1024.0;
    let x = n as f64;
    if x < KIB {
        format!("{n} B")
    } else if x < KIB * KIB {
        format!("{:.1} KiB", x / KIB)
    } else {
        format!("{:.1} MiB", x / (KIB * KIB))
    }
}

/// Entries `(text, width)` laid out in lines no wider than `max_w`: per
/// line, each entry's index and x offset. An entry wider than a line gets a
/// line of its own.
fn wrap_entries(entries: &[(String, f64)], max_w: f64) -> Vec<Vec<(usize, f64)>> {
    let mut lines: Vec<Vec<(usize, f64)>> = Vec::new();
    let mut x = 0.0;
    for (k, (_, w)) in entries.iter().enumerate() {
        match lines.last_mut() {
            Some(line) if x + w <= max_w => line.push((k, x)),
            _ => {
                lines.push(vec![(k, 0.0)]);
                x = 0.0;
            }
        }
        x += w + ENTRY_GAP;
    }
    lines
}

/// How a pass touches a resource, for its mark.
#[derive(Clone, Copy, PartialEq)]
enum Mark {
    Read,
    Write,
    /// Written on top of what is there (`loads`).
    Adds,
}

fn mark_of(pass: &ScheduledPass, resource: usize) -> Option<Mark> {
    let touches = |b: &&Binding| b.resource == resource && b.resource != DROPPED_RESOURCE;
    let writes: Vec<&Binding> = pass.writes.iter().filter(touches).collect();
    if writes.iter().any(|b| b.loads) {
        Some(Mark::Adds)
    } else if !writes.is_empty() {
        Some(Mark::Write)
    } else if pass.reads.iter().any(|b| touches(&b)) {
        Some(Mark::Read)
    } else {
        None
    }
}

/// The SVG picture of `schedule` (see the module docs).
pub fn schedule_svg(schedule: &Schedule) -> String {
    let rows: Vec<(&ScheduledPass, bool)> = schedule
        .passes
        .iter()
        .map(|p| (p, false))
        .chain(schedule.culled.iter().map(|c| (&c.pass, true)))
        .collect();
    // Columns in order of first use; ties (written by the same pass) by name
    // order in the file.
    let mut columns: Vec<usize> = (0..schedule.resources.len()).collect();
    columns.sort_by_key(|&r| (schedule.resources[r].first_use, r));

    let row_labels: Vec<(String, String)> = rows
        .iter()
        .map(|(p, culled)| {
            let kind = if *culled {
                format!("{} (culled)", p.type_name)
            } else {
                p.type_name.clone()
            };
            (p.name.clone(), kind)
        })
        .collect();
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
    let headers: Vec<(String, String)> = columns
        .iter()
        .map(|&r| {
            let res = &schedule.resources[r];
            (res.name.clone(), short_desc(&res.desc))
        })
        .collect();
    let header_len = |(n, d): &(String, String)| bold_width(n) + 8.0 + text_width(d);
    let header_h = HEADER_STEP * headers.len() as f64 + 8.0;

    let grid_x = MARGIN + label_w + 10.0;
    let col_x = |c: usize| grid_x + COL_W * (c as f64 + 0.5);
    let top = MARGIN + TITLE_H + header_h;
    // Live passes, then the output line, then culled passes.
    let live = schedule.passes.len();
    let slot_y = |slot: usize| top + ROW_H * (slot as f64 + 0.5);
    let row_y = |i: usize| slot_y(if i < live { i } else { i + 1 });
    let output_y = slot_y(live);
    let grid_bottom = top + ROW_H * (rows.len() as f64 + 1.0);
    let legend_y = grid_bottom + 22.0;
    let header_right = headers
        .iter()
        .enumerate()
        .map(|(c, h)| col_x(c) - 4.0 + header_len(h))
        .fold(grid_x + COL_W * columns.len() as f64, f64::max);
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
    // Each technique's passes share a tint, named in the legend: what a
    // `--set techniques.…` swap changes. A technique that adds no pass (it
    // only sets params, or culled nothing into the rows) has no tint to name.
    let technique_labels: Vec<String> = schedule
        .techniques
        .iter()
        .map(|t| t.label())
        .filter(|l| rows.iter().any(|(p, _)| p.technique.as_ref() == Some(l)))
        .collect();
    let tint = |pass: &ScheduledPass| {
        pass.technique
            .as_ref()
            .and_then(|t| technique_labels.iter().position(|l| l == t))
            .map_or("white", |i| TECHNIQUE_TINTS[i % TECHNIQUE_TINTS.len()])
    };
    // Everything the legend writes fits the picture: its first line, the
    // notes beside the second, and at least the widest technique entry.
    let technique_entries: Vec<(String, f64)> = technique_labels
        .iter()
        .map(|l| {
            let text = format!("technique {l}");
            let w = 16.0 + text_width(&text);
            (text, w)
        })
        .collect();
    let width = [
        header_right + MARGIN,
        MARGIN * 2.0 + LEGEND_W,
        notes
            .iter()
            .map(|n| NOTES_X + text_width(n) + MARGIN)
            .fold(0.0, f64::max),
        technique_entries
            .iter()
            .map(|(_, w)| MARGIN * 2.0 + w)
            .fold(0.0, f64::max),
    ]
    .into_iter()
    .fold(0.0, f64::max)
    .ceil();
    let technique_lines = wrap_entries(&technique_entries, width - MARGIN * 2.0);
    // The legend's second line (texture / buffer) holds the first note.
    let technique_y = legend_y + 18.0 * (1 + notes.len().max(1)) as f64;
    let height =
        (legend_y + 18.0 * (notes.len().max(1) + technique_lines.len()) as f64 + 18.0 + MARGIN)
            .ceil();

    let mut out = String::new();
    let _ = write!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="{FONT}" font-size="{FONT_SIZE}">"#
    );
    let _ = write!(
        out,
        r#"<rect x="0" y="0" width="{width}" height="{height}" fill="white"/>"#
    );
    let culled = if schedule.culled.is_empty() {
        String::new()
    } else {
        format!(", {} culled", schedule.culled.len())
    };
    let _ = write!(
        out,
        r#"<text x="{MARGIN}" y="{}" font-size="15" font-weight="bold">{}</text><text x="{}" y="{}" fill="{GREY}">{} passes{culled}, {} resources, {} peak</text>"#,
        MARGIN + 16.0,
        escape(&schedule.name),
        MARGIN + bold_width(&schedule.name) * 15.0 / FONT_SIZE + 12.0,
        MARGIN + 16.0,
        schedule.passes.len(),
        schedule.resources.len(),
        bytes(schedule.memory.peak_bytes)
    );

    // Column headers as stairs: header c on its own line, a leader from it
    // down to its column. Later headers start lower and further right, so no
    // text crosses a leader.
    for (c, (name, desc)) in headers.iter().enumerate() {
        let x = col_x(c);
        let y = MARGIN + TITLE_H + HEADER_STEP * (c as f64 + 1.0);
        let _ = write!(
            out,
            r#"<line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="{GUIDE}" stroke-width="1.5"/>"#,
            y + 3.0,
            top
        );
        let _ = write!(
            out,
            r#"<text x="{}" y="{y}" font-weight="bold">{}</text><text x="{}" y="{y}" fill="{GREY}">{}</text>"#,
            x - 4.0,
            escape(name),
            x - 4.0 + bold_width(name) + 8.0,
            escape(desc)
        );
    }

    // Row guides and pass labels.
    for (i, ((name, kind), (_, culled))) in row_labels.iter().zip(&rows).enumerate() {
        let y = row_y(i);
        let dash = if *culled {
            r#" stroke-dasharray="4 3""#
        } else {
            ""
        };
        let colour = if *culled { GREY } else { "#222222" };
        let _ = write!(
            out,
            r#"<line x1="{MARGIN}" y1="{y}" x2="{}" y2="{y}" stroke="{GUIDE}"/>"#,
            grid_x + COL_W * columns.len() as f64
        );
        let _ = write!(
            out,
            r#"<rect x="{MARGIN}" y="{}" width="{label_w}" height="{}" rx="3" fill="{}" stroke="{colour}"{dash}/>"#,
            y - ROW_H / 2.0 + 3.0,
            ROW_H - 6.0,
            tint(rows[i].0)
        );
        let _ = write!(
            out,
            r#"<text x="{}" y="{}" font-weight="bold" fill="{colour}">{}</text><text x="{}" y="{}" fill="{GREY}">{}</text>"#,
            MARGIN + 8.0,
            y + 4.0,
            escape(name),
            kind_x,
            y + 4.0,
            escape(kind)
        );
    }
    let _ = write!(
        out,
        r#"<text x="{}" y="{}" font-style="italic" fill="{GREY}">output</text>"#,
        MARGIN + 8.0,
        output_y + 4.0
    );

    // Lifetimes and marks.
    for (c, &r) in columns.iter().enumerate() {
        let res = &schedule.resources[r];
        let colour = match res.desc.kind() {
            ResourceKind::Texture => TEXTURE_COLOUR,
            ResourceKind::Buffer => BUFFER_COLOUR,
        };
        let x = col_x(c);
        let is_output = schedule.outputs.contains(&r);
        let end = if is_output {
            output_y
        } else {
            row_y(res.last_use)
        };
        let _ = write!(
            out,
            r#"<line x1="{x}" y1="{}" x2="{x}" y2="{end}" stroke="{colour}" stroke-width="3"/>"#,
            row_y(res.first_use)
        );
        if is_output {
            let y = output_y;
            let _ = write!(
                out,
                r#"<polygon points="{},{} {},{} {x},{}" fill="{colour}"/>"#,
                x - 6.0,
                y - 6.0,
                x + 6.0,
                y - 6.0,
                y + 3.0
            );
        }
        for (i, (pass, culled)) in rows.iter().enumerate() {
            let Some(mark) = mark_of(pass, r) else {
                continue;
            };
            let y = row_y(i);
            let colour = if *culled { GREY } else { colour };
            if *culled {
                // A culled pass sits below the live schedule: a dashed lead
                // from the resource's lifetime to its mark.
                let _ = write!(
                    out,
                    r#"<line x1="{x}" y1="{end}" x2="{x}" y2="{y}" stroke="{GREY}" stroke-dasharray="3 3"/>"#
                );
            }
            let _ = match mark {
                Mark::Write => write!(
                    out,
                    r#"<rect x="{}" y="{}" width="11" height="11" fill="{colour}"/>"#,
                    x - 5.5,
                    y - 5.5
                ),
                Mark::Adds => write!(out, r#"<circle cx="{x}" cy="{y}" r="6" fill="{colour}"/>"#),
                Mark::Read => write!(
                    out,
                    r#"<circle cx="{x}" cy="{y}" r="5" fill="white" stroke="{colour}" stroke-width="2.5"/>"#
                ),
            };
        }
    }

    // The legend, drawn with the same shapes as the marks.
    let (ly, lx) = (legend_y, MARGIN);
    let _ = write!(
        out,
        r##"<rect x="{}" y="{}" width="11" height="11" fill="{TEXTURE_COLOUR}"/><text x="{}" y="{}" fill="{GREY}">writes</text><circle cx="{}" cy="{}" r="5" fill="white" stroke="{TEXTURE_COLOUR}" stroke-width="2.5"/><text x="{}" y="{}" fill="{GREY}">reads</text><circle cx="{}" cy="{}" r="6" fill="{TEXTURE_COLOUR}"/><text x="{}" y="{}" fill="{GREY}">adds to what is there (blending, atomics)</text><line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{GREY}" stroke-dasharray="4 3"/><text x="{}" y="{}" fill="{GREY}">culled</text>"##,
        lx,
        ly - 9.5,
        lx + 16.0,
        ly,
        lx + 80.0,
        ly - 4.0,
        lx + 91.0,
        ly,
        lx + 146.0,
        ly - 4.0,
        lx + 158.0,
        ly,
        lx + 450.0,
        ly - 4.0,
        lx + 480.0,
        ly - 4.0,
        lx + 486.0,
        ly
    );
    let _ = write!(
        out,
        r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{TEXTURE_COLOUR}" stroke-width="3"/><text x="{}" y="{}" fill="{GREY}">texture</text><line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{BUFFER_COLOUR}" stroke-width="3"/><text x="{}" y="{}" fill="{GREY}">buffer lifetime</text>"#,
        lx,
        ly + 14.0,
        lx + 12.0,
        ly + 14.0,
        lx + 16.0,
        ly + 18.0,
        lx + 80.0,
        ly + 14.0,
        lx + 92.0,
        ly + 14.0,
        lx + 96.0,
        ly + 18.0
    );
    for (k, note) in notes.iter().enumerate() {
        let _ = write!(
            out,
            r#"<text x="{}" y="{}" fill="{GREY}">{}</text>"#,
            NOTES_X,
            legend_y + 18.0 + 18.0 * k as f64,
            escape(note)
        );
    }
    for (line, entries) in technique_lines.iter().enumerate() {
        let y = technique_y + 18.0 * line as f64;
        for &(k, x) in entries {
            let _ = write!(
                out,
                r#"<rect x="{}" y="{}" width="11" height="11" fill="{}" stroke="{GREY}"/><text x="{}" y="{y}" fill="{GREY}">{}</text>"#,
                MARGIN + x,
                y - 9.0,
                TECHNIQUE_TINTS[k % TECHNIQUE_TINTS.len()],
                MARGIN + x + 16.0,
                escape(&technique_entries[k].0)
            );
        }
    }
    out.push_str("</svg>\n");
    out
}
