//! Terminal tables whose columns are as wide as their widest cell, so a long
//! pass-type name or variant label never pushes a row out of line. A table is
//! built row by row (a new row or column is one call) and printed at once.

/// How a column's cells line up.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Align {
    Left,
    Right,
}

#[derive(Debug)]
struct Row {
    cells: Vec<String>,
    /// Free text after the last column (`(culled: …)`), not counted in any width.
    note: Option<String>,
}

/// Columns with a header, rows of cells, widths computed from the content.
#[derive(Debug)]
pub struct Table {
    headers: Vec<String>,
    aligns: Vec<Align>,
    rows: Vec<Row>,
}

impl Table {
    /// A table with these columns, `(header, alignment)`.
    pub fn new(columns: &[(&str, Align)]) -> Self {
        Table {
            headers: columns.iter().map(|(h, _)| (*h).to_owned()).collect(),
            aligns: columns.iter().map(|(_, a)| *a).collect(),
            rows: Vec::new(),
        }
    }

    /// A row; missing cells at the end are left empty.
    pub fn row(&mut self, cells: Vec<String>) {
        self.rows.push(Row { cells, note: None });
    }

    /// A row followed by free text (not part of any column).
    pub fn row_with_note(&mut self, cells: Vec<String>, note: String) {
        self.rows.push(Row {
            cells,
            note: Some(note),
        });
    }

    /// The header line, then one line per row, columns two spaces apart.
    pub fn lines(&self) -> Vec<String> {
        let widths: Vec<usize> = (0..self.headers.len())
            .map(|c| {
                self.rows
                    .iter()
                    .filter_map(|r| r.cells.get(c))
                    .chain(std::iter::once(&self.headers[c]))
                    .map(|s| s.chars().count())
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let line = |cells: &[String], note: Option<&String>| {
            let mut parts: Vec<String> = (0..self.headers.len())
                .map(|c| {
                    let cell = cells.get(c).map_or("", String::as_str);
                    let w = widths[c];
                    match self.aligns[c] {
                        Align::Left => format!("{cell:<w$}"),
                        Align::Right => format!("{cell:>w$}"),
                    }
                })
                .collect();
            if let Some(note) = note {
                parts.push(note.clone());
            }
            parts.join("  ").trim_end().to_owned()
        };
        std::iter::once(line(&self.headers, None))
            .chain(self.rows.iter().map(|r| line(&r.cells, r.note.as_ref())))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_fit_the_widest_cell() {
        let mut t = Table::new(&[("pass", Align::Left), ("GPU ms", Align::Right)]);
        t.row(vec!["a".into(), "1.000".into()]);
        t.row(vec!["a_much_longer_name".into(), "12.500".into()]);
        t.row_with_note(vec!["c".into(), "culled".into()], "(why)".into());
        let lines = t.lines();
        assert_eq!(
            lines,
            [
                "pass                GPU ms",
                "a                    1.000",
                "a_much_longer_name  12.500",
                "c                   culled  (why)",
            ]
        );
    }

    #[test]
    fn missing_cells_are_empty() {
        let mut t = Table::new(&[("a", Align::Left), ("b", Align::Right)]);
        t.row(vec!["total".into()]);
        assert_eq!(t.lines(), ["a      b", "total"]);
    }
}
