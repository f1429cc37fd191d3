//! Table figures (`kind = "table"` in `docs/figures.toml`): a benchmark or
//! script prints a Markdown table; its last table is the figure, recorded
//! cell by cell, and re-checked column by column as the registry says
//! (`Column`): times as ratios to the first row's within one run, ratios
//! against their rounds' range, metrics within 2 %, the rest exactly.

use serde::{Deserialize, Serialize};

use super::check::Comparison;
use super::registry::Column;
use super::{Figure, Made, Record};
use crate::error::BookError;

/// A table's header and its rows' cells, as printed.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

fn cells(line: &str) -> Vec<String> {
    let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
    inner.split('|').map(|c| c.trim().to_string()).collect()
}

/// The last Markdown table of `text`: its lines and the parsed table.
pub fn last_table(text: &str) -> Option<(String, Table)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = None;
    let mut i = 0;
    while i + 1 < lines.len() {
        let rule = lines[i + 1].trim();
        if lines[i].trim().starts_with('|') && (rule.starts_with("|--") || rule.starts_with("|:-"))
        {
            let end = (i + 2..lines.len())
                .find(|&j| !lines[j].trim().starts_with('|'))
                .unwrap_or(lines.len());
            found = Some((i, end));
            i = end;
        } else {
            i += 1;
        }
    }
    let (start, end) = found?;
    let table = Table {
        header: cells(lines[start]),
        rows: lines[start + 2..end].iter().map(|l| cells(l)).collect(),
    };
    Some((lines[start..end].join("\n"), table))
}

/// The record of a table figure from its command's standard output.
pub fn record(figure: &Figure, stdout: &str, made: Made) -> Result<Record, BookError> {
    let missing = |what: String| BookError::content(std::path::Path::new(&figure.id), what);
    let (markdown, table) = last_table(stdout).ok_or_else(|| {
        missing(format!(
            "`{}` printed no Markdown table",
            figure.command_line()
        ))
    })?;
    for name in figure.key.iter().chain(figure.columns.keys()) {
        if !table.header.contains(name) {
            return Err(missing(format!(
                "the table has no column `{name}` (its columns: {})",
                table.header.join(", ")
            )));
        }
    }
    Ok(Record {
        id: figure.id.clone(),
        commit: made.commit,
        dirty: made.dirty,
        date: made.date,
        adapter: String::new(),
        repeats: 0,
        command_line: figure.command_line(),
        rows: Vec::new(),
        table: Some(table),
        markdown,
    })
}

/// The first number of a cell (`1,523`, `0.58×`, `92 %`), and the range a
/// ratio cell gives in brackets (`1.24× [1.18–1.45]`).
fn number(cell: &str) -> Option<f64> {
    let s: String = cell.chars().filter(|c| *c != ',').collect();
    let start = s.find(|c: char| c.is_ascii_digit() || c == '-')?;
    let digits: String = s[start..]
        .chars()
        .enumerate()
        .take_while(|(i, c)| c.is_ascii_digit() || *c == '.' || (*i == 0 && *c == '-'))
        .map(|(_, c)| c)
        .collect();
    digits.parse().ok()
}

fn range(cell: &str) -> Option<(f64, f64)> {
    let inner = cell.split_once('[')?.1.split_once(']')?.0;
    let (lo, hi) = inner.split_once(['–', '-'])?;
    Some((number(lo)?, number(hi)?))
}

/// Every compared cell of `published` against `today`'s, rows matched by
/// the key columns.
pub fn compare(figure: &Figure, published: &Table, today: &Table) -> Vec<Comparison> {
    let key_of = |t: &Table, row: &[String]| -> String {
        let keys: Vec<&String> = if figure.key.is_empty() {
            t.header.iter().take(1).collect()
        } else {
            figure.key.iter().collect()
        };
        keys.iter()
            .filter_map(|k| t.header.iter().position(|h| h == *k))
            .map(|i| row.get(i).cloned().unwrap_or_default())
            .collect::<Vec<_>>()
            .join(" / ")
    };
    let cell = |t: &Table, row: &[String], name: &str| -> Option<String> {
        let i = t.header.iter().position(|h| h == name)?;
        row.get(i).cloned()
    };
    let mut out = Vec::new();
    for p in &published.rows {
        let key = key_of(published, p);
        let t = today.rows.iter().find(|r| key_of(today, r) == key);
        let mut push = |quantity: &str, pv, tv, lo, hi, moved| {
            out.push(Comparison {
                scene: String::new(),
                variant: key.clone(),
                quantity: quantity.to_string(),
                published: pv,
                today: tv,
                lo,
                hi,
                moved,
            })
        };
        let Some(t) = t else {
            push("row present", None, None, f64::NAN, f64::NAN, true);
            continue;
        };
        for (name, kind) in &figure.columns {
            let (pc, tc) = (cell(published, p, name), cell(today, t, name));
            let (pv, tv) = (
                pc.as_deref().and_then(number),
                tc.as_deref().and_then(number),
            );
            let tol = figure.speed_tolerance;
            let (pv, tv, lo, hi, moved) = match kind {
                Column::Exact => {
                    let moved = pc != tc;
                    (pv, tv, f64::NAN, f64::NAN, moved)
                }
                Column::Metric => match (pv, tv) {
                    (Some(a), Some(b)) => {
                        (pv, tv, b, b, (a - b).abs() > (0.02 * a.abs()).max(0.001))
                    }
                    _ => (pv, tv, f64::NAN, f64::NAN, pc != tc),
                },
                Column::Ratio => match (pv, tv) {
                    (Some(a), Some(b)) => {
                        let (l, h) = tc.as_deref().and_then(range).unwrap_or((b, b));
                        let (lo, hi) = (l * (1.0 - tol), h * (1.0 + tol));
                        (pv, tv, lo, hi, !(lo..=hi).contains(&a))
                    }
                    _ => (pv, tv, f64::NAN, f64::NAN, pc != tc),
                },
                Column::Time => {
                    // As a ratio to the first row's time of this run.
                    let base = |tb: &Table| {
                        tb.rows
                            .first()
                            .and_then(|r| cell(tb, r, name))
                            .as_deref()
                            .and_then(number)
                    };
                    match (pv, tv, base(published), base(today)) {
                        (Some(a), Some(b), Some(pa), Some(tb)) if pa > 0.0 && tb > 0.0 => {
                            let (a, b) = (a / pa, b / tb);
                            let (lo, hi) = (b * (1.0 - tol), b * (1.0 + tol));
                            (Some(a), Some(b), lo, hi, !(lo..=hi).contains(&a))
                        }
                        _ => (pv, tv, f64::NAN, f64::NAN, pc.is_some() != tc.is_some()),
                    }
                }
            };
            push(name, pv, tv, lo, hi, moved);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::published::registry::Kind;

    fn figure(columns: &[(&str, Column)]) -> Figure {
        Figure {
            id: "t".into(),
            page: "README.md".into(),
            command: vec!["cargo".into(), "bench".into()],
            kind: Kind::Table,
            key: vec!["segments".into()],
            columns: columns.iter().map(|(n, c)| (n.to_string(), *c)).collect(),
            measures: vec![],
            except: vec![],
            speed_tolerance: 0.10,
        }
    }

    const PRINTED: &str = "noise\n| a | b |\n|---|---|\n| 1 | 2 |\n\nthe run:\n\
        | segments | ms | ratio | holds? |\n|---:|---:|---:|---|\n\
        | 75,008 | 313 | 0.58× [0.55–0.60] | yes |\n| 150,016 | 445 | 0.60× [0.58–0.61] | yes |\ndone\n";

    #[test]
    fn the_last_table_is_the_figure_and_its_numbers_parse() {
        let (md, t) = last_table(PRINTED).unwrap();
        assert!(
            md.starts_with("| segments |") && md.ends_with("| yes |"),
            "{md}"
        );
        assert_eq!(t.header, ["segments", "ms", "ratio", "holds?"]);
        assert_eq!(t.rows[1][0], "150,016");
        assert_eq!(number("150,016"), Some(150016.0));
        assert_eq!(number("0.58× [0.55–0.60]"), Some(0.58));
        assert_eq!(range("0.58× [0.55–0.60]"), Some((0.55, 0.60)));
    }

    #[test]
    fn each_kind_of_column_moves_only_for_a_real_change() {
        let f = figure(&[
            ("ms", Column::Time),
            ("ratio", Column::Ratio),
            ("holds?", Column::Exact),
        ]);
        let (_, published) = last_table(PRINTED).unwrap();
        // Twice as slow a machine, same ratios: nothing moved.
        let slower = PRINTED
            .replace("| 313 |", "| 626 |")
            .replace("| 445 |", "| 890 |");
        let (_, today) = last_table(&slower).unwrap();
        let rows = compare(&f, &published, &today);
        assert!(rows.iter().all(|r| !r.moved), "{rows:?}");
        // The second row's time alone doubles; a ratio leaves its range; a
        // claim stops holding: each moves, nothing else.
        let changed = PRINTED
            .replace("| 445 |", "| 890 |")
            .replace("0.60× [0.58–0.61] | yes", "0.80× [0.78–0.82] | no");
        let (_, today) = last_table(&changed).unwrap();
        let moved: Vec<String> = compare(&f, &published, &today)
            .into_iter()
            .filter(|r| r.moved)
            .map(|r| format!("{} {}", r.variant, r.quantity))
            .collect();
        assert_eq!(moved, ["150,016 ms", "150,016 ratio", "150,016 holds?"]);
        // A row gone is a change too.
        let (_, today) =
            last_table(&PRINTED.replace("| 150,016 | 445 | 0.60× [0.58–0.61] | yes |\n", ""))
                .unwrap();
        assert!(
            compare(&f, &published, &today)
                .iter()
                .any(|r| r.moved && r.quantity == "row present")
        );
    }
}
