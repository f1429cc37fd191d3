//! Published figures: every measured table of the README and the book is a
//! *figure*, registered in `docs/figures.toml` with the `plait ab` command
//! that measures it and the files whose change can move it. What was
//! published is kept in `docs/figures/ID.json` — the commit it was measured
//! at, the adapter, the command line, every value at full precision and the
//! Markdown table the page shows between `<!-- figure:ID -->` and
//! `<!-- /figure:ID -->`. So a page's table is never typed by hand (a test
//! holds each block to its record), [`check`] re-measures a figure and says
//! which values moved beyond their spread, and [`stale`] says which
//! figures were measured before the last change to the files they measure.

pub mod check;
mod comments;
mod record;
mod registry;
pub mod stale;
pub mod table;

use std::path::{Path, PathBuf};

pub use record::{Made, Record, Row, Spread};
pub use registry::{Column, Figure, Kind, Registry};

use crate::error::BookError;

/// The registry, relative to the repository root.
pub const REGISTRY: &str = "docs/figures.toml";
/// The published records, one `ID.json` each.
pub const RECORDS: &str = "docs/figures";

/// Today's UTC date, `YYYY-MM-DD` (days since the epoch to the civil
/// calendar, Howard Hinnant's `civil_from_days`).
pub fn today() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let z = (secs / 86_400) as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}")
}

/// The record of `id` under `repo`.
pub fn record_path(repo: &Path, id: &str) -> PathBuf {
    repo.join(RECORDS).join(format!("{id}.json"))
}

/// The block's opening and closing markers.
pub fn markers(id: &str) -> (String, String) {
    (
        format!("<!-- figure:{id} -->"),
        format!("<!-- /figure:{id} -->"),
    )
}

/// The text between `id`'s markers in `page` (without the marker lines),
/// or why there is none.
pub fn block(page_text: &str, id: &str) -> Result<String, String> {
    let (open, close) = markers(id);
    let lines: Vec<&str> = page_text.lines().collect();
    let start = lines
        .iter()
        .position(|l| l.trim() == open)
        .ok_or_else(|| format!("no `{open}` marker"))?;
    let end = lines[start..]
        .iter()
        .position(|l| l.trim() == close)
        .map(|i| start + i)
        .ok_or_else(|| format!("`{open}` has no closing `{close}`"))?;
    Ok(lines[start + 1..end].join("\n"))
}

/// `page_text` with `id`'s block replaced by `body` (markers kept).
pub fn replace_block(page_text: &str, id: &str, body: &str) -> Result<String, String> {
    let (open, close) = markers(id);
    block(page_text, id)?;
    let mut out = String::with_capacity(page_text.len() + body.len());
    let mut skipping = false;
    for line in page_text.split_inclusive('\n') {
        let bare = line.trim();
        if bare == open {
            out.push_str(line);
            out.push_str(body.trim_end_matches('\n'));
            out.push('\n');
            skipping = true;
        } else if bare == close {
            skipping = false;
            out.push_str(line);
        } else if !skipping {
            out.push_str(line);
        }
    }
    Ok(out)
}

/// Every figure of the registry with its record, checked against each other
/// and against the page that publishes it: the page's block must be exactly
/// the record's table and provenance line. Returns the problems (empty: all
/// consistent).
pub fn consistency(repo: &Path) -> Result<Vec<String>, BookError> {
    let registry = Registry::load(repo)?;
    let mut problems = Vec::new();
    for figure in &registry.figures {
        let record = match Record::load(&record_path(repo, &figure.id)) {
            Ok(r) => r,
            Err(e) => {
                problems.push(format!("figure `{}`: {e}", figure.id));
                continue;
            }
        };
        if record.id != figure.id {
            problems.push(format!(
                "{}: its id is `{}`, its file name says `{}`",
                record_path(repo, &figure.id).display(),
                record.id,
                figure.id
            ));
        }
        let page = repo.join(&figure.page);
        let text = std::fs::read_to_string(&page).map_err(BookError::io(&page))?;
        match block(&text, &figure.id) {
            Ok(body) if body.trim() == record.block(figure).trim() => {}
            Ok(_) => problems.push(format!(
                "{}: the block of figure `{}` is not its record's table (edited by hand? \
                 regenerate it with `plait-figures write {}`)",
                figure.page, figure.id, figure.id
            )),
            Err(e) => problems.push(format!("{}: figure `{}`: {e}", figure.page, figure.id)),
        }
    }
    // A marker on a page that no figure registers is a table nobody can re-check.
    for page in registry.pages() {
        let path = repo.join(&page);
        let text = std::fs::read_to_string(&path).map_err(BookError::io(&path))?;
        for id in text
            .lines()
            .filter_map(|l| l.trim().strip_prefix("<!-- figure:"))
            .filter_map(|l| l.strip_suffix(" -->"))
        {
            if registry.figure(id).is_none() {
                problems.push(format!(
                    "{page}: figure `{id}` is not in {REGISTRY}{}",
                    registry.suggest(id)
                ));
            }
        }
    }
    Ok(problems)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replace_block_keeps_the_markers_and_the_rest() {
        let page = "a\n<!-- figure:x -->\nold\nold2\n<!-- /figure:x -->\nb\n";
        let new = replace_block(page, "x", "new\n").unwrap();
        assert_eq!(new, "a\n<!-- figure:x -->\nnew\n<!-- /figure:x -->\nb\n");
        assert_eq!(block(&new, "x").unwrap(), "new");
    }

    #[test]
    fn a_missing_or_unclosed_block_is_an_error() {
        assert!(
            block("a\n", "x")
                .unwrap_err()
                .contains("no `<!-- figure:x -->`")
        );
        assert!(
            block("<!-- figure:x -->\nold\n", "x")
                .unwrap_err()
                .contains("no closing")
        );
    }
}
