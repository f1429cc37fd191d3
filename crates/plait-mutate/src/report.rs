//! The run's table (Markdown, for the book's Reliability page) and every
//! result with its diff (JSON).

use std::path::Path;
use std::process::Command;

use anyhow::Result;

use crate::technique::{Outcome, Result1};

/// What the table was measured at and with.
#[derive(Debug, serde::Serialize)]
pub struct Header {
    pub commit: String,
    pub command: String,
    pub max: usize,
    pub seed: u64,
}

impl Header {
    pub fn now(
        root: &Path,
        techniques: &[String],
        only: &[String],
        max: usize,
        seed: u64,
    ) -> Result<Header> {
        let git = |args: &[&str]| -> Result<String> {
            let out = Command::new("git").args(args).current_dir(root).output()?;
            Ok(String::from_utf8_lossy(&out.stdout).trim().to_owned())
        };
        let mut commit = git(&["rev-parse", "--short=10", "HEAD"])?;
        if !git(&["status", "--porcelain", "--untracked-files=no"])?.is_empty() {
            commit += " (with uncommitted changes)";
        }
        let command = format!(
            "bash scripts/mutate.sh {} --max {max} --seed {seed}",
            techniques.join(" ")
        )
        .replace("  ", " ");
        let only: String = only.iter().map(|id| format!(" --only {id}")).collect();
        let command = command + &only;
        Ok(Header {
            commit,
            command,
            max,
            seed,
        })
    }
}

#[derive(Debug, Default, serde::Serialize)]
struct Counts {
    /// Killed or hung.
    killed: usize,
    hung: usize,
    /// Killed by a test written for survivors (`added_for_mutants`).
    killed_by_added: usize,
    /// Survived and not shown equivalent.
    survived: usize,
    /// Survived and shown equivalent in `tests/mutation.toml`: not scored.
    equivalent: usize,
    invalid: usize,
}

fn counts(results: &[Result1]) -> Counts {
    let mut c = Counts::default();
    for r in results {
        match (&r.outcome, &r.equivalent) {
            (Outcome::Killed { added, .. } | Outcome::Hung { added, .. }, _) => {
                c.killed += 1;
                c.hung += usize::from(matches!(r.outcome, Outcome::Hung { .. }));
                c.killed_by_added += usize::from(*added);
            }
            (Outcome::Survived { .. }, Some(_)) => c.equivalent += 1,
            (Outcome::Survived { .. }, None) => c.survived += 1,
            (Outcome::Invalid { .. }, _) => c.invalid += 1,
        }
    }
    c
}

fn percent(part: usize, whole: usize) -> String {
    if whole == 0 {
        "–".to_owned()
    } else {
        format!("{:.0} %", 100.0 * part as f64 / whole as f64)
    }
}

pub fn table(header: &Header, all: &[(String, Vec<Result1>)]) -> String {
    let mut md = format!(
        "Measured at commit `{}` with `{}`.\n\n\
         | technique | mutants | invalid WGSL | killed (hung) | equivalent | survived | score | score without the added tests |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|\n",
        header.commit, header.command
    );
    for (name, results) in all {
        let c = counts(results);
        let scored = c.killed + c.survived;
        md += &format!(
            "| `{name}` | {} | {} | {} ({}) | {} | {} | {} | {} |\n",
            results.len(),
            c.invalid,
            c.killed,
            c.hung,
            c.equivalent,
            c.survived,
            percent(c.killed, scored),
            percent(c.killed - c.killed_by_added, scored),
        );
    }
    let survivors = |equivalent: bool| {
        all.iter().flat_map(|(_, rs)| rs).filter(move |r| {
            matches!(r.outcome, Outcome::Survived { .. }) && r.equivalent.is_some() == equivalent
        })
    };
    md += "\nSurvivors (not shown equivalent):\n\n";
    for r in survivors(false) {
        md += &format!("- `{}`\n\n```diff\n{}```\n\n", r.id, r.diff);
    }
    md += "Equivalent mutants (`tests/mutation.toml` says why):\n\n";
    for r in survivors(true) {
        let why = r.equivalent.as_deref().unwrap_or_default();
        md += &format!("- `{}`: {why}\n", r.id);
    }
    for r in all.iter().flat_map(|(_, rs)| rs) {
        if r.equivalent.is_some()
            && matches!(r.outcome, Outcome::Killed { .. } | Outcome::Hung { .. })
        {
            md += &format!("\n**Claimed equivalent but killed:** `{}`\n", r.id);
        }
    }
    md
}

pub fn write(work: &Path, header: &Header, all: &[(String, Vec<Result1>)]) -> Result<()> {
    let md = table(header, all);
    std::fs::write(work.join("mutation.md"), &md)?;
    let json: Vec<serde_json::Value> = all
        .iter()
        .map(|(name, results)| {
            serde_json::json!({ "technique": name, "counts": counts(results), "results": results })
        })
        .collect();
    let json = serde_json::json!({ "header": header, "techniques": json });
    std::fs::write(
        work.join("mutation.json"),
        serde_json::to_string_pretty(&json)?,
    )?;
    eprintln!(
        "plait-mutate: wrote {} and {}",
        work.join("mutation.md").display(),
        work.join("mutation.json").display()
    );
    Ok(())
}
