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
    pub fn now(root: &Path, techniques: &[String], max: usize, seed: u64) -> Result<Header> {
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
    killed: usize,
    hung: usize,
    survived: usize,
    invalid: usize,
}

fn counts(results: &[Result1]) -> Counts {
    let mut c = Counts::default();
    for r in results {
        match r.outcome {
            Outcome::Killed { .. } => c.killed += 1,
            Outcome::Hung { .. } => c.hung += 1,
            Outcome::Survived { .. } => c.survived += 1,
            Outcome::Invalid { .. } => c.invalid += 1,
        }
    }
    c
}

pub fn table(header: &Header, all: &[(String, Vec<Result1>)]) -> String {
    let mut md = format!(
        "Measured at commit `{}` with `{}`.\n\n\
         | technique | mutants | killed | of which hung | survived | invalid WGSL | score |\n\
         |---|---:|---:|---:|---:|---:|---:|\n",
        header.commit, header.command
    );
    for (name, results) in all {
        let c = counts(results);
        let scored = c.killed + c.hung + c.survived;
        let score = if scored == 0 {
            "–".to_owned()
        } else {
            format!(
                "{:.0} %",
                100.0 * (c.killed + c.hung) as f64 / scored as f64
            )
        };
        md += &format!(
            "| `{name}` | {} | {} | {} | {} | {} | {score} |\n",
            results.len(),
            c.killed + c.hung,
            c.hung,
            c.survived,
            c.invalid
        );
    }
    md += "\nSurvivors:\n\n";
    for (_, results) in all {
        for r in results {
            if matches!(r.outcome, Outcome::Survived { .. }) {
                md += &format!("- `{}`\n\n```diff\n{}```\n\n", r.id, r.diff);
            }
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
    print!("{md}");
    eprintln!(
        "plait-mutate: wrote {} and {}",
        work.join("mutation.md").display(),
        work.join("mutation.json").display()
    );
    Ok(())
}
