//! Which published figures were measured before the last change to the
//! files they measure: `git log RECORD_COMMIT..HEAD -- MEASURES`, less the
//! commits that changed only comments there (`comments.rs`).

use std::path::Path;
use std::process::Command;

use super::{Record, Registry, comments, record_path};
use crate::error::BookError;

/// One figure's state.
#[derive(Clone, Debug)]
pub struct Freshness {
    pub id: String,
    pub page: String,
    pub commit: String,
    pub date: String,
    /// Commits after the figure's that touch what it measures (`hash subject`).
    pub changed_since: Vec<String>,
    /// Commits after the figure's that changed only comments in what it
    /// measures (`hash subject`): listed, not counted as a change.
    pub comments_only: Vec<String>,
    /// Why staleness could not be told (no git, commit not in this history).
    pub unknown: Option<String>,
}

impl Freshness {
    pub fn is_stale(&self) -> bool {
        !self.changed_since.is_empty()
    }
}

/// Every registered figure's freshness.
pub fn freshness(repo: &Path) -> Result<Vec<Freshness>, BookError> {
    let registry = Registry::load(repo)?;
    let mut out = Vec::new();
    for figure in &registry.figures {
        let record = match Record::load(&record_path(repo, &figure.id)) {
            Ok(r) => r,
            Err(e) => {
                out.push(Freshness {
                    id: figure.id.clone(),
                    page: figure.page.clone(),
                    commit: String::new(),
                    date: String::new(),
                    changed_since: Vec::new(),
                    comments_only: Vec::new(),
                    unknown: Some(format!("never published ({e})")),
                });
                continue;
            }
        };
        let mut args = vec![
            "log".to_string(),
            "--format=%h %s".to_string(),
            format!("{}..HEAD", record.commit),
            "--".to_string(),
        ];
        let pathspecs = figure.pathspecs();
        args.extend(pathspecs.iter().cloned());
        let (touching, unknown) = match Command::new("git").args(&args).current_dir(repo).output() {
            Ok(o) if o.status.success() => (
                String::from_utf8_lossy(&o.stdout)
                    .lines()
                    .map(str::to_owned)
                    .collect(),
                None,
            ),
            Ok(o) => (
                Vec::new(),
                Some(String::from_utf8_lossy(&o.stderr).trim().to_string()),
            ),
            Err(e) => (Vec::new(), Some(format!("git: {e}"))),
        };
        let (comments_only, changed_since): (Vec<String>, Vec<String>) =
            touching.into_iter().partition(|line| {
                let hash = line.split_whitespace().next().unwrap_or("");
                comments::comment_only(repo, hash, &pathspecs)
            });
        out.push(Freshness {
            id: figure.id.clone(),
            page: figure.page.clone(),
            commit: record.commit.clone(),
            date: record.date.clone(),
            changed_since,
            comments_only,
            unknown,
        });
    }
    Ok(out)
}

/// The book's page on the published figures: each with its page, command,
/// commit and whether what it measures changed since.
pub fn page(repo: &Path) -> Result<String, BookError> {
    let registry = Registry::load(repo)?;
    let fresh = freshness(repo)?;
    let mut md = String::from(
        "# Published figures\n\n\
         Every measured table of the README and this book is a *figure*: registered in \
         `docs/figures.toml` with the `plait ab` command that measures it and the files it \
         measures, its values kept at full precision in `docs/figures/ID.json`, and its table \
         written by `plait-figures write ID`, never by hand. `bash scripts/bench.sh --check` \
         re-measures every figure and prints, per value, the published value, today's value \
         and today's spread, and flags what moved. This page is made when the book builds: a \
         figure measured before the last change to the files it measures is marked **stale**.\n\n\
         | figure | page | measured at | on | what it measures changed since |\n\
         |---|---|---|---|---|\n",
    );
    for f in &fresh {
        let changed = match (&f.unknown, f.changed_since.len()) {
            (Some(why), _) => format!("unknown: {why}"),
            (None, 0) => "no (fresh)".to_string(),
            (None, n) => format!(
                "**stale**: {n} commit{} ({})",
                if n == 1 { "" } else { "s" },
                f.changed_since
                    .iter()
                    .take(3)
                    .map(|c| format!("`{}`", c.split_whitespace().next().unwrap_or("")))
                    .collect::<Vec<_>>()
                    .join(", ")
                    + if n > 3 { ", …" } else { "" }
            ),
        };
        let at = if f.commit.is_empty() {
            "—".to_string()
        } else {
            format!("`{}`", &f.commit[..f.commit.len().min(10)])
        };
        md.push_str(&format!(
            "| `{}` | {} | {at} | {} | {} |\n",
            f.id, f.page, f.date, changed
        ));
    }
    md.push_str("\nThe commands, one per figure:\n\n");
    for figure in &registry.figures {
        md.push_str(&format!("- `{}`: `{}`\n", figure.id, figure.command_line()));
    }
    let rest = unregistered(repo)?;
    md.push_str(&format!(
        "\n## Tables not yet re-checkable ({})\n\n\
         These tables of measurements were made by the command their page names (a benchmark \
         or an older script) but are not registered figures, so `--check` cannot re-measure \
         them and nothing says when they go stale: read each with the commit it was last \
         written at.\n\n| page | line | header | last written at |\n|---|---:|---|---|\n",
        rest.len()
    ));
    for u in &rest {
        md.push_str(&format!(
            "| {} | {} | `{}` | `{}` |\n",
            u.page,
            u.line,
            u.header.replace('`', "").replace('|', "\\|"),
            u.written_at
        ));
    }
    Ok(md)
}

/// A table of measurements on a page that is not a registered figure: what
/// `--check` cannot re-measure yet.
#[derive(Clone, Debug)]
pub struct Unregistered {
    pub page: String,
    /// 1-based line of its header row.
    pub line: usize,
    pub header: String,
    /// The newest commit among its lines (`git blame`), short, or why unknown.
    pub written_at: String,
}

/// Words of a header row that make a table one of measurements.
const MEASURED_HEADERS: [&str; 9] = [
    " ms", "RMSE", "FLIP", "SSIM", "MiB", "×", "|ΔV|", "ratio", "fps",
];

/// Every table of measurements on the README and the guide's pages that
/// sits outside a figure block.
pub fn unregistered(repo: &Path) -> Result<Vec<Unregistered>, BookError> {
    let mut pages = vec!["README.md".to_string()];
    let guide = repo.join("book/src/guide");
    let mut guide_pages: Vec<String> = std::fs::read_dir(&guide)
        .map_err(BookError::io(&guide))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("book/src/guide/{n}"))
        .collect();
    guide_pages.sort();
    pages.extend(guide_pages);
    let mut out = Vec::new();
    for page in pages {
        let path = repo.join(&page);
        let text = std::fs::read_to_string(&path).map_err(BookError::io(&path))?;
        let lines: Vec<&str> = text.lines().collect();
        let mut in_figure = false;
        let mut i = 0;
        while i < lines.len() {
            let l = lines[i].trim();
            if l.starts_with("<!-- figure:") {
                in_figure = true;
            } else if l.starts_with("<!-- /figure:") {
                in_figure = false;
            }
            let starts_table = l.starts_with('|')
                && lines
                    .get(i + 1)
                    .is_some_and(|n| n.trim().starts_with("|--") || n.trim().starts_with("|:-"));
            if !starts_table {
                i += 1;
                continue;
            }
            let end = (i..lines.len())
                .find(|&j| !lines[j].trim().starts_with('|'))
                .unwrap_or(lines.len());
            let has_numbers = lines[i + 2..end]
                .iter()
                .any(|r| r.chars().any(|c| c.is_ascii_digit()));
            if !in_figure && has_numbers && MEASURED_HEADERS.iter().any(|h| l.contains(h)) {
                out.push(Unregistered {
                    page: page.clone(),
                    line: i + 1,
                    header: l.to_string(),
                    written_at: newest_commit(repo, &page, i + 1, end),
                });
            }
            i = end;
        }
    }
    Ok(out)
}

/// The newest commit among lines `from..=to` of `page`, by `git blame`.
fn newest_commit(repo: &Path, page: &str, from: usize, to: usize) -> String {
    let out = Command::new("git")
        .args([
            "blame",
            "--porcelain",
            "-L",
            &format!("{from},{to}"),
            "--",
            page,
        ])
        .current_dir(repo)
        .output();
    let Some(out) = out.ok().filter(|o| o.status.success()) else {
        return "unknown (no git history)".to_string();
    };
    let text = String::from_utf8_lossy(&out.stdout);
    let mut best: Option<(u64, String)> = None;
    let mut hash = String::new();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some(w) if w.len() == 40 && w.chars().all(|c| c.is_ascii_hexdigit()) => {
                hash = w.to_string();
            }
            Some("committer-time") => {
                let t: u64 = words.next().and_then(|t| t.parse().ok()).unwrap_or(0);
                if best.as_ref().is_none_or(|(b, _)| t > *b) {
                    best = Some((t, hash[..10].to_string()));
                }
            }
            _ => {}
        }
    }
    best.map_or_else(|| "uncommitted".to_string(), |(_, h)| h)
}
