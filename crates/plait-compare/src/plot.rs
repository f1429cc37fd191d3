//! Small SVG charts drawn by hand: scatter and line plots with axes, ticks,
//! a legend and optional per-point marker sizes (no scripts, no fonts to load).

use std::fmt::Write as _;

/// One point; `size` is the marker radius in pixels (default 4).
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub x: f64,
    pub y: f64,
    pub size: Option<f64>,
    pub label: Option<String>,
}

/// A named set of points, joined by a line when `line` is set.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<Point>,
    pub line: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// A note under the title (e.g. "marker area ∝ peak memory").
    pub note: Option<String>,
}

/// Colors of the series, in order (Tableau 10).
pub const PALETTE: [&str; 10] = [
    "#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7",
    "#9c755f", "#bab0ac",
];

/// XML-escape text for SVG and HTML.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// About `n` round tick values covering `lo..=hi`.
pub fn ticks(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater)
        || !lo.is_finite()
        || !hi.is_finite()
    {
        return vec![lo];
    }
    let raw = (hi - lo) / n.max(1) as f64;
    let p = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * p);
    let mut t = (lo / step).ceil() * step;
    let mut out = Vec::new();
    while t <= hi + step * 1e-9 {
        out.push(if t.abs() < step * 1e-9 { 0.0 } else { t });
        t += step;
    }
    out
}

fn fmt_tick(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e4).contains(&a) {
        format!("{v:.1e}")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// The chart as a standalone `<svg>` element (640×400, wider when a
/// series' name needs more than the legend's 170 px).
pub fn svg(chart: &Chart) -> String {
    // The legend column fits the longest name (about 6.5 px a character at
    // 11 px sans-serif, after the marker): labels such as
    // `occupancy [techniques.transparency=compute_raster, …]` were cut off
    // at the image's edge.
    let longest = chart
        .series
        .iter()
        .map(|s| s.name.chars().count())
        .max()
        .unwrap_or(0);
    let right = f64::max(170.0, 30.0 + 6.5 * longest as f64);
    let (w, h) = (470.0 + right, 400.0);
    let (left, top, bottom) = (70.0, 44.0, 50.0);
    let pts: Vec<&Point> = chart
        .series
        .iter()
        .flat_map(|s| &s.points)
        .filter(|p| p.x.is_finite() && p.y.is_finite())
        .collect();
    let mut out = chart_header(w, h, &chart.title, chart.note.as_deref());
    if pts.is_empty() {
        let _ = write!(
            out,
            r##"<text x="{}" y="{}" text-anchor="middle" fill="#777">no data</text></svg>"##,
            w / 2.0,
            h / 2.0
        );
        return out;
    }
    let (mut x0, mut x1) = pts
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.x), b.max(p.x)));
    let (mut y0, mut y1) = pts
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.y), b.max(p.y)));
    let pw = w - left - right;
    let ph = h - top - bottom;
    // Markers are drawn whole inside the frame: the largest marker's radius
    // plus a gap is kept free on every side, so a point at the edge of the
    // data (an error of 0, the cheapest variant) never sits on the frame.
    let max_radius = pts
        .iter()
        .map(|p| p.size.unwrap_or(4.0))
        .fold(4.0, f64::max);
    let pad = |a: &mut f64, b: &mut f64, plot_px: f64| {
        if *b - *a < 1e-12 {
            let d = if a.abs() > 0.0 { a.abs() * 0.1 } else { 1.0 };
            *a -= d;
            *b += d;
        }
        let keep_px = (max_radius + 6.0).min(plot_px / 4.0);
        let d = (*b - *a) * keep_px / (plot_px - 2.0 * keep_px);
        *a -= d;
        *b += d;
    };
    pad(&mut x0, &mut x1, pw);
    pad(&mut y0, &mut y1, ph);
    let sx = |x: f64| left + (x - x0) / (x1 - x0) * pw;
    let sy = |y: f64| top + ph - (y - y0) / (y1 - y0) * ph;
    let _ = write!(
        out,
        r##"<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#333"/>"##
    );
    for t in ticks(x0, x1, 6) {
        let x = sx(t);
        let _ = write!(
            out,
            r##"<line x1="{x:.1}" y1="{top}" x2="{x:.1}" y2="{}" stroke="#eee"/><text x="{x:.1}" y="{}" text-anchor="middle">{}</text>"##,
            top + ph,
            top + ph + 14.0,
            fmt_tick(t)
        );
    }
    for t in ticks(y0, y1, 6) {
        let y = sy(t);
        let _ = write!(
            out,
            r##"<line x1="{left}" y1="{y:.1}" x2="{}" y2="{y:.1}" stroke="#eee"/><text x="{}" y="{:.1}" text-anchor="end">{}</text>"##,
            left + pw,
            left - 4.0,
            y + 4.0,
            fmt_tick(t)
        );
    }
    let _ = write!(
        out,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        left + pw / 2.0,
        h - 12.0,
        escape(&chart.x_label)
    );
    let _ = write!(
        out,
        r#"<text x="16" y="{}" text-anchor="middle" transform="rotate(-90 16 {})">{}</text>"#,
        top + ph / 2.0,
        top + ph / 2.0,
        escape(&chart.y_label)
    );
    for (i, s) in chart.series.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let ok: Vec<&Point> = s
            .points
            .iter()
            .filter(|p| p.x.is_finite() && p.y.is_finite())
            .collect();
        if s.line && ok.len() > 1 {
            let path: Vec<String> = ok
                .iter()
                .map(|p| format!("{:.1},{:.1}", sx(p.x), sy(p.y)))
                .collect();
            let _ = write!(
                out,
                r#"<polyline points="{}" fill="none" stroke="{color}" stroke-width="1.5"/>"#,
                path.join(" ")
            );
        }
        for p in &ok {
            let r = p.size.unwrap_or(4.0);
            let _ = write!(
                out,
                r#"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" fill="{color}" fill-opacity="0.55" stroke="{color}"><title>{}: ({}, {})</title></circle>"#,
                sx(p.x),
                sy(p.y),
                escape(&s.name),
                fmt_tick(p.x),
                fmt_tick(p.y)
            );
            if let Some(l) = &p.label {
                let _ = write!(
                    out,
                    r##"<text x="{:.1}" y="{:.1}" fill="#333" font-size="9">{}</text>"##,
                    sx(p.x) + r + 2.0,
                    sy(p.y) - 2.0,
                    escape(l)
                );
            }
        }
        let ly = top + 8.0 + i as f64 * 16.0;
        let lx = left + pw + 12.0;
        let _ = write!(
            out,
            r#"<circle cx="{lx}" cy="{ly}" r="5" fill="{color}" fill-opacity="0.55" stroke="{color}"/><text x="{}" y="{}">{}</text>"#,
            lx + 10.0,
            ly + 4.0,
            escape(&s.name)
        );
    }
    out.push_str("</svg>");
    out
}

/// A table of numbers drawn as coloured cells: one row per value of the
/// first sweep, one column per value of the second.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    pub title: String,
    /// What the rows are (the first sweep's key).
    pub row_label: String,
    /// What the columns are (the second sweep's key).
    pub column_label: String,
    pub rows: Vec<String>,
    pub columns: Vec<String>,
    /// `cells[row][column]`; `None` where nothing was measured.
    pub cells: Vec<Vec<Option<f64>>>,
    pub note: Option<String>,
}

/// Light to dark blue (ColorBrewer "Blues", its ends): a sequential scale
/// that reads as "more" without a legend of hues.
const LIGHT: [f64; 3] = [247.0, 251.0, 255.0];
const DARK: [f64; 3] = [8.0, 48.0, 107.0];

fn shade(t: f64) -> String {
    let c = |i: usize| (LIGHT[i] + (DARK[i] - LIGHT[i]) * t.clamp(0.0, 1.0)).round() as u8;
    format!("#{:02x}{:02x}{:02x}", c(0), c(1), c(2))
}

/// Four significant digits, as in the report's tables.
fn fmt_cell(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 6) as usize;
    format!("{v:.digits$}")
}

/// The grid as a standalone `<svg>`: each cell shaded from the smallest
/// value (lightest) to the largest (darkest), its number written in it.
pub fn grid_svg(grid: &Grid) -> String {
    let columns = grid.columns.len().max(1);
    let cell_w = (480.0 / columns as f64).clamp(56.0, 110.0);
    let cell_h = 28.0;
    let (left, top) = (130.0, 76.0);
    let w = (left + cell_w * columns as f64 + 20.0).max(420.0);
    let h = top + cell_h * grid.rows.len().max(1) as f64 + 44.0;
    let values: Vec<f64> = grid
        .cells
        .iter()
        .flatten()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .collect();
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let t_of = |v: f64| if hi > lo { (v - lo) / (hi - lo) } else { 0.5 };
    let mut out = chart_header(w, h, &grid.title, grid.note.as_deref());
    let _ = write!(
        out,
        r#"<text x="{}" y="52" text-anchor="middle">{} →</text>"#,
        left + cell_w * columns as f64 / 2.0,
        escape(&grid.column_label)
    );
    let _ = write!(
        out,
        r#"<text x="{}" y="68" text-anchor="end">{} ↓</text>"#,
        left - 6.0,
        escape(&grid.row_label)
    );
    for (c, name) in grid.columns.iter().enumerate() {
        let _ = write!(
            out,
            r#"<text x="{:.1}" y="68" text-anchor="middle">{}</text>"#,
            left + cell_w * (c as f64 + 0.5),
            escape(name)
        );
    }
    for (r, name) in grid.rows.iter().enumerate() {
        let y = top + cell_h * r as f64;
        let _ = write!(
            out,
            r#"<text x="{}" y="{:.1}" text-anchor="end">{}</text>"#,
            left - 6.0,
            y + cell_h / 2.0 + 4.0,
            escape(name)
        );
        for c in 0..grid.columns.len() {
            let x = left + cell_w * c as f64;
            let cell = grid
                .cells
                .get(r)
                .and_then(|row| row.get(c))
                .copied()
                .flatten();
            let (fill, text, ink) = match cell {
                Some(v) if v.is_finite() => {
                    let t = t_of(v);
                    (
                        shade(t),
                        fmt_cell(v),
                        if t > 0.55 { "white" } else { "#222" },
                    )
                }
                _ => ("#f0f0f0".to_string(), "–".to_string(), "#777"),
            };
            let _ = write!(
                out,
                r##"<rect x="{x:.1}" y="{y:.1}" width="{cell_w:.1}" height="{cell_h}" fill="{fill}" stroke="#fff"><title>{} = {}, {} = {}: {}</title></rect><text x="{:.1}" y="{:.1}" text-anchor="middle" fill="{ink}">{}</text>"##,
                escape(&grid.row_label),
                escape(name),
                escape(&grid.column_label),
                escape(&grid.columns[c]),
                escape(&text),
                x + cell_w / 2.0,
                y + cell_h / 2.0 + 4.0,
                escape(&text)
            );
        }
    }
    if !values.is_empty() {
        // The scale: lightest = smallest value, darkest = largest.
        let y = top + cell_h * grid.rows.len() as f64 + 14.0;
        let steps = 24;
        let bar_w = 160.0;
        for i in 0..steps {
            let _ = write!(
                out,
                r#"<rect x="{:.1}" y="{y:.1}" width="{:.1}" height="10" fill="{}"/>"#,
                left + bar_w * i as f64 / steps as f64,
                bar_w / steps as f64 + 0.5,
                shade(i as f64 / (steps - 1) as f64)
            );
        }
        let _ = write!(
            out,
            r#"<text x="{}" y="{:.1}" text-anchor="end">{}</text><text x="{}" y="{:.1}">{}</text>"#,
            left - 4.0,
            y + 9.0,
            fmt_cell(lo),
            left + bar_w + 4.0,
            y + 9.0,
            fmt_cell(hi)
        );
    }
    out.push_str("</svg>");
    out
}

/// An SVG chart's opening: the canvas, a white background, the title and an
/// optional note under it.
fn chart_header(w: f64, h: f64, title: &str, note: Option<&str>) -> String {
    let mut out = String::new();
    let _ = write!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w} {h}" width="{w}" height="{h}" font-family="sans-serif" font-size="11">"#
    );
    let _ = write!(out, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = write!(
        out,
        r#"<text x="{}" y="18" font-size="14" text-anchor="middle">{}</text>"#,
        w / 2.0,
        escape(title)
    );
    if let Some(note) = note {
        let _ = write!(
            out,
            r##"<text x="{}" y="33" fill="#555" text-anchor="middle">{}</text>"##,
            w / 2.0,
            escape(note)
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round() {
        assert_eq!(
            ticks(0.0, 1.0, 5),
            vec![0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
        );
        assert_eq!(ticks(3.0, 3.0, 5), vec![3.0]);
    }

    /// `(cx, cy, r)` of every data marker (legend markers have no `<title>`).
    fn markers(svg: &str) -> Vec<(f64, f64, f64)> {
        svg.split("<circle ")
            .skip(1)
            .filter(|c| c.contains("<title>"))
            .map(|c| {
                let attr = |k: &str| -> f64 {
                    let start = c.find(&format!("{k}=\"")).unwrap() + k.len() + 2;
                    let end = c[start..].find('"').unwrap() + start;
                    c[start..end].parse().unwrap()
                };
                (attr("cx"), attr("cy"), attr("r"))
            })
            .collect()
    }

    #[test]
    fn markers_stay_inside_the_frame() {
        // The reference at error 0 and the costliest variant with the
        // largest marker: both at the edges of the data.
        let point = |x: f64, y: f64, size: f64| Point {
            x,
            y,
            size: Some(size),
            label: None,
        };
        let c = Chart {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            note: None,
            series: vec![Series {
                name: "s".into(),
                line: false,
                points: vec![
                    point(1.0, 0.0, 16.0),
                    point(9.0, 0.3, 16.0),
                    point(4.0, 0.1, 3.0),
                ],
            }],
        };
        let s = svg(&c);
        let (left, top, right, bottom) = (70.0, 44.0, 640.0 - 170.0, 400.0 - 50.0);
        let marks = markers(&s);
        assert_eq!(marks.len(), 3);
        for (cx, cy, r) in marks {
            assert!(
                cx - r > left && cx + r < right && cy - r > top && cy + r < bottom,
                "marker at ({cx}, {cy}) r {r} touches the frame"
            );
        }
    }

    #[test]
    fn a_long_series_name_widens_the_chart_to_hold_its_legend() {
        let chart = |name: &str| Chart {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            note: None,
            series: vec![Series {
                name: name.into(),
                line: false,
                points: vec![Point {
                    x: 1.0,
                    y: 1.0,
                    size: None,
                    label: None,
                }],
            }],
        };
        let width = |s: &str| -> f64 {
            let at = s.find("width=\"").expect("width") + 7;
            s[at..]
                .split('"')
                .next()
                .expect("value")
                .parse()
                .expect("number")
        };
        assert_eq!(width(&svg(&chart("short"))), 640.0);
        let long =
            "occupancy [techniques.transparency=compute_raster, techniques.shading_space=strand]";
        let wide = svg(&chart(long));
        // The legend text starts 22 px into the column; at ~6.5 px a
        // character it must end inside the image.
        assert!(
            width(&wide) >= 470.0 + 22.0 + 6.5 * long.len() as f64,
            "{}",
            width(&wide)
        );
    }

    #[test]
    fn chart_has_points_legend_and_escaped_text() {
        let c = Chart {
            title: "error <vs> cost".into(),
            x_label: "ms".into(),
            y_label: "FLIP".into(),
            note: None,
            series: vec![Series {
                name: "a&b".into(),
                line: true,
                points: vec![
                    Point {
                        x: 1.0,
                        y: 0.1,
                        size: Some(8.0),
                        label: Some("64".into()),
                    },
                    Point {
                        x: 2.0,
                        y: 0.05,
                        size: None,
                        label: None,
                    },
                ],
            }],
        };
        let s = svg(&c);
        assert!(s.starts_with("<svg") && s.ends_with("</svg>"));
        assert_eq!(s.matches("<circle").count(), 3); // two points + legend
        assert!(
            s.contains("error &lt;vs&gt; cost") && s.contains("a&amp;b") && s.contains("<polyline")
        );
        assert!(
            svg(&Chart {
                series: vec![],
                ..c
            })
            .contains("no data")
        );
    }

    #[test]
    fn grid_has_a_cell_per_combination_shaded_by_value() {
        let g = Grid {
            title: "small: occupancy — ꟻLIP".into(),
            row_label: "params.light_size".into(),
            column_label: "techniques.self_shadow".into(),
            rows: vec!["128".into(), "256".into()],
            columns: vec!["occupancy".into(), "deep_opacity".into(), "<x>".into()],
            cells: vec![
                vec![Some(0.1), Some(0.3), None],
                vec![Some(0.2), Some(0.123456), Some(0.0)],
            ],
            note: None,
        };
        let s = grid_svg(&g);
        assert!(s.starts_with("<svg") && s.ends_with("</svg>"));
        // One titled cell per combination, the missing one marked.
        assert_eq!(s.matches("<title>").count(), 6);
        assert!(
            s.contains("params.light_size = 256, techniques.self_shadow = deep_opacity: 0.1235")
        );
        assert!(s.contains(">–</text>"), "the cell without a value");
        assert!(s.contains("&lt;x&gt;") && !s.contains("<x>"));
        // The smallest value is the lightest shade, the largest the darkest.
        let fill = |value: &str| {
            let at = s.find(&format!(": {value}</title>")).unwrap();
            let start = s[..at].rfind("fill=\"").unwrap() + 6;
            s[start..start + 7].to_string()
        };
        assert_eq!(fill("0"), shade(0.0));
        assert_eq!(fill("0.3000"), shade(1.0));
    }
}
