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

use crate::schedule::{Binding, ResourceDesc, ResourceId, Schedule, ScheduledPass};
use crate::spec::ResourceKind;

mod measure;
use measure::{
    header_len, label_geometry, picture_width, row_labels, sharing_notes, technique_entries,
    technique_labels,
};

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
        ResourceDesc::AccelerationStructure => "strands (ray queries)".into(),
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

fn mark_of(pass: &ScheduledPass, resource: ResourceId) -> Option<Mark> {
    let touches = |b: &&Binding| b.resource == Some(resource);
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
    let layout = Layout::new(schedule);
    let mut out = String::new();
    layout.write_title(&mut out);
    layout.write_headers(&mut out);
    layout.write_rows(&mut out);
    for (c, &r) in layout.columns.iter().enumerate() {
        layout.write_column(&mut out, c, r);
    }
    layout.write_legend_key(&mut out);
    layout.write_legend_notes(&mut out);
    out.push_str("</svg>\n");
    out
}

/// Where everything goes in the picture, worked out before drawing.
struct Layout<'s> {
    schedule: &'s Schedule,
    /// Live passes in execution order, then culled ones (`true`).
    rows: Vec<(&'s ScheduledPass, bool)>,
    /// Resource ids, in column order.
    columns: Vec<usize>,
    /// Per row: the pass name and its type.
    row_labels: Vec<(String, String)>,
    /// Per column: the resource name and its short description.
    headers: Vec<(String, String)>,
    kind_x: f64,
    label_w: f64,
    grid_x: f64,
    top: f64,
    legend_y: f64,
    notes: Vec<String>,
    technique_labels: Vec<String>,
    technique_entries: Vec<(String, f64)>,
    technique_lines: Vec<Vec<(usize, f64)>>,
    technique_y: f64,
    width: f64,
    height: f64,
}

/// The x of column `c`'s line in a grid starting at `grid_x`.
fn column_x(grid_x: f64, c: usize) -> f64 {
    grid_x + COL_W * (c as f64 + 0.5)
}

impl<'s> Layout<'s> {
    /// Lays out the rows, columns, labels and legend of `schedule`.
    fn new(schedule: &'s Schedule) -> Self {
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

        let row_labels = row_labels(&rows);
        let (kind_x, label_w) = label_geometry(&row_labels);
        let headers: Vec<(String, String)> = columns
            .iter()
            .map(|&r| {
                let res = &schedule.resources[r];
                (res.name.clone(), short_desc(&res.desc))
            })
            .collect();
        let header_h = HEADER_STEP * headers.len() as f64 + 8.0;

        let grid_x = MARGIN + label_w + 10.0;
        let top = MARGIN + TITLE_H + header_h;
        let grid_bottom = top + ROW_H * (rows.len() as f64 + 1.0);
        let legend_y = grid_bottom + 22.0;
        let header_right = headers
            .iter()
            .enumerate()
            .map(|(c, h)| column_x(grid_x, c) - 4.0 + header_len(h))
            .fold(grid_x + COL_W * columns.len() as f64, f64::max);
        let notes = sharing_notes(schedule);
        let technique_labels = technique_labels(schedule, &rows);
        let technique_entries = technique_entries(&technique_labels);
        let width = picture_width(header_right, &notes, &technique_entries);
        let technique_lines = wrap_entries(&technique_entries, width - MARGIN * 2.0);
        // The legend's second line (texture / buffer) holds the first note.
        let technique_y = legend_y + 18.0 * (1 + notes.len().max(1)) as f64;
        let height =
            (legend_y + 18.0 * (notes.len().max(1) + technique_lines.len()) as f64 + 18.0 + MARGIN)
                .ceil();
        Layout {
            schedule,
            rows,
            columns,
            row_labels,
            headers,
            kind_x,
            label_w,
            grid_x,
            top,
            legend_y,
            notes,
            technique_labels,
            technique_entries,
            technique_lines,
            technique_y,
            width,
            height,
        }
    }

    /// The x of column `c`'s line.
    fn col_x(&self, c: usize) -> f64 {
        column_x(self.grid_x, c)
    }

    /// The y of row slot `slot`.
    fn slot_y(&self, slot: usize) -> f64 {
        self.top + ROW_H * (slot as f64 + 0.5)
    }

    /// The y of row `i`: live passes, then the output line, then culled passes.
    fn row_y(&self, i: usize) -> f64 {
        let live = self.schedule.passes.len();
        self.slot_y(if i < live { i } else { i + 1 })
    }

    /// The y of the output line, below the live passes.
    fn output_y(&self) -> f64 {
        self.slot_y(self.schedule.passes.len())
    }

    /// The fill of `pass`'s label: its technique's tint, or white.
    fn tint(&self, pass: &ScheduledPass) -> &'static str {
        pass.technique
            .as_ref()
            .and_then(|t| self.technique_labels.iter().position(|l| l == t))
            .map_or("white", |i| TECHNIQUE_TINTS[i % TECHNIQUE_TINTS.len()])
    }

    /// The `<svg>` element, the background and the title line.
    fn write_title(&self, out: &mut String) {
        let (width, height, schedule) = (self.width, self.height, self.schedule);
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
    }

    /// The column headers, stacked like stairs.
    fn write_headers(&self, out: &mut String) {
        // Column headers as stairs: header c on its own line, a leader from it
        // down to its column. Later headers start lower and further right, so no
        // text crosses a leader.
        for (c, (name, desc)) in self.headers.iter().enumerate() {
            let x = self.col_x(c);
            let y = MARGIN + TITLE_H + HEADER_STEP * (c as f64 + 1.0);
            let _ = write!(
                out,
                r#"<line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="{GUIDE}" stroke-width="1.5"/>"#,
                y + 3.0,
                self.top
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
    }

    /// Row guides and pass labels, and the output line's label.
    fn write_rows(&self, out: &mut String) {
        let label_w = self.label_w;
        for (i, ((name, kind), (_, culled))) in self.row_labels.iter().zip(&self.rows).enumerate() {
            let y = self.row_y(i);
            let dash = if *culled {
                r#" stroke-dasharray="4 3""#
            } else {
                ""
            };
            let colour = if *culled { GREY } else { "#222222" };
            let _ = write!(
                out,
                r#"<line x1="{MARGIN}" y1="{y}" x2="{}" y2="{y}" stroke="{GUIDE}"/>"#,
                self.grid_x + COL_W * self.columns.len() as f64
            );
            let _ = write!(
                out,
                r#"<rect x="{MARGIN}" y="{}" width="{label_w}" height="{}" rx="3" fill="{}" stroke="{colour}"{dash}/>"#,
                y - ROW_H / 2.0 + 3.0,
                ROW_H - 6.0,
                self.tint(self.rows[i].0)
            );
            let _ = write!(
                out,
                r#"<text x="{}" y="{}" font-weight="bold" fill="{colour}">{}</text><text x="{}" y="{}" fill="{GREY}">{}</text>"#,
                MARGIN + 8.0,
                y + 4.0,
                escape(name),
                self.kind_x,
                y + 4.0,
                escape(kind)
            );
        }
        let _ = write!(
            out,
            r#"<text x="{}" y="{}" font-style="italic" fill="{GREY}">output</text>"#,
            MARGIN + 8.0,
            self.output_y() + 4.0
        );
    }

    /// Column `c` (resource `r`): its lifetime line, an arrow if it is an
    /// output, and a mark on every row that touches it.
    fn write_column(&self, out: &mut String, c: usize, r: usize) {
        let res = &self.schedule.resources[r];
        let colour = match res.desc.kind() {
            ResourceKind::Texture => TEXTURE_COLOUR,
            ResourceKind::Buffer | ResourceKind::AccelerationStructure => BUFFER_COLOUR,
        };
        let x = self.col_x(c);
        let output_y = self.output_y();
        let is_output = self.schedule.outputs.contains(&ResourceId::new(r));
        let end = if is_output {
            output_y
        } else {
            self.row_y(res.last_use)
        };
        let _ = write!(
            out,
            r#"<line x1="{x}" y1="{}" x2="{x}" y2="{end}" stroke="{colour}" stroke-width="3"/>"#,
            self.row_y(res.first_use)
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
        for (i, (pass, culled)) in self.rows.iter().enumerate() {
            let Some(mark) = mark_of(pass, ResourceId::new(r)) else {
                continue;
            };
            let y = self.row_y(i);
            let colour = if *culled { GREY } else { colour };
            if *culled {
                // A culled pass sits below the live schedule: a dashed lead
                // from the resource's lifetime to its mark.
                let _ = write!(
                    out,
                    r#"<line x1="{x}" y1="{end}" x2="{x}" y2="{y}" stroke="{GREY}" stroke-dasharray="3 3"/>"#
                );
            }
            write_mark(out, mark, x, y, colour);
        }
    }

    /// The legend's first two lines, drawn with the same shapes as the marks.
    fn write_legend_key(&self, out: &mut String) {
        let (ly, lx) = (self.legend_y, MARGIN);
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
    }

    /// The notes beside the legend's second line, then the technique tints.
    fn write_legend_notes(&self, out: &mut String) {
        for (k, note) in self.notes.iter().enumerate() {
            let _ = write!(
                out,
                r#"<text x="{}" y="{}" fill="{GREY}">{}</text>"#,
                NOTES_X,
                self.legend_y + 18.0 + 18.0 * k as f64,
                escape(note)
            );
        }
        for (line, entries) in self.technique_lines.iter().enumerate() {
            let y = self.technique_y + 18.0 * line as f64;
            for &(k, x) in entries {
                let _ = write!(
                    out,
                    r#"<rect x="{}" y="{}" width="11" height="11" fill="{}" stroke="{GREY}"/><text x="{}" y="{y}" fill="{GREY}">{}</text>"#,
                    MARGIN + x,
                    y - 9.0,
                    TECHNIQUE_TINTS[k % TECHNIQUE_TINTS.len()],
                    MARGIN + x + 16.0,
                    escape(&self.technique_entries[k].0)
                );
            }
        }
    }
}

/// One mark at (`x`, `y`): a square for a write, a filled circle for an
/// add, a hollow one for a read.
fn write_mark(out: &mut String, mark: Mark, x: f64, y: f64, colour: &str) {
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
