//! `plait-figures`: the README's and the book's measured tables, re-measured
//! and rewritten by one command each (`scripts/bench.sh --check` runs
//! `check`). See `plait_book::published`.
//!
//!   plait-figures check [ID…]        re-measure; per value: published, today, spread; exit 1 if any moved
//!   plait-figures write ID… [--from DIR]   measure (or take a finished run) and publish: record + page block
//!   plait-figures stale              which figures were measured before a change to what they measure

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand};
use plait_book::published::{self, Figure, Kind, Record, Registry, check, stale, table};

/// `println!` that ends the program quietly when standard output is gone
/// (`plait-figures stale | head`), instead of panicking on the broken pipe.
macro_rules! say {
    ($($t:tt)*) => {
        if writeln!(std::io::stdout(), $($t)*).is_err() {
            std::process::exit(0)
        }
    };
}

#[derive(Parser)]
#[command(about = "Re-measure and rewrite plait's published figures (docs/figures.toml)")]
struct Args {
    /// The `plait` binary that measures (default: the build's own, beside this one).
    #[arg(long, global = true)]
    plait: Option<PathBuf>,
    /// Where each run's `plait ab` report goes (DIR/ID).
    #[arg(long, global = true, default_value = "target/figures")]
    runs: PathBuf,
    #[command(subcommand)]
    command: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Re-measure figures (all without IDs) and compare with what was published.
    Check { ids: Vec<String> },
    /// Measure figures and publish them: `docs/figures/ID.json` and the page's block.
    Write {
        #[arg(required = true)]
        ids: Vec<String>,
        /// Take this finished `plait ab` run (its report.json and report.md) instead of running.
        #[arg(long, value_name = "DIR")]
        from: Option<PathBuf>,
    },
    /// Which figures were measured before the last change to the files they measure.
    Stale,
}

fn main() -> ExitCode {
    match run() {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn run() -> Result<ExitCode> {
    let args = Args::parse();
    let repo = std::env::current_dir()?;
    let registry = Registry::load(&repo)?;
    match &args.command {
        Cmd::Stale => {
            let mut stale_count = 0;
            for f in stale::freshness(&repo)? {
                match (&f.unknown, f.is_stale()) {
                    (Some(why), _) => say!("{}: unknown ({why})", f.id),
                    (None, false) => say!("{}: fresh (measured at {})", f.id, short(&f.commit)),
                    (None, true) => {
                        stale_count += 1;
                        say!(
                            "{}: STALE — measured at {}; changed since by:\n    {}",
                            f.id,
                            short(&f.commit),
                            f.changed_since.join("\n    ")
                        );
                    }
                }
                if !f.comments_only.is_empty() {
                    say!(
                        "    (not counted, comments only:\n    {})",
                        f.comments_only.join("\n    ")
                    );
                }
            }
            say!("{stale_count} stale");
            let rest = stale::unregistered(&repo)?;
            say!(
                "{} tables of measurements are not registered figures (not re-checkable):",
                rest.len()
            );
            for u in rest {
                say!(
                    "  {}:{}  {}  (last written at {})",
                    u.page,
                    u.line,
                    u.header,
                    u.written_at
                );
            }
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Check { ids } => {
            let figures = registry.select(ids).map_err(anyhow::Error::msg)?;
            let plait = plait_binary(&args)?;
            let mut moved = 0;
            for figure in figures {
                let published = Record::load(&published::record_path(&repo, &figure.id))?;
                let dir = measure(&plait, figure, &args.runs)?;
                let today = record_of(&repo, figure, &dir)?;
                let rows = check::compare(figure, &published, &today);
                moved += rows.iter().filter(|r| r.moved).count();
                say!("{}", check::table(figure, &published, &rows));
            }
            if moved > 0 {
                say!(
                    "{moved} published values moved beyond their spread: regenerate them with \
                     `plait-figures write ID` (after finding why they moved)"
                );
                return Ok(ExitCode::from(1));
            }
            say!("every published value holds");
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Write { ids, from } => {
            let figures = registry.select(ids).map_err(anyhow::Error::msg)?;
            if from.is_some() && figures.len() != 1 {
                bail!("--from takes one figure's run; name one ID");
            }
            let plait = if from.is_none() {
                Some(plait_binary(&args)?)
            } else {
                None
            };
            for figure in figures {
                let dir = match (from, &plait) {
                    (Some(dir), _) => dir.clone(),
                    (None, Some(plait)) => measure(plait, figure, &args.runs)?,
                    (None, None) => unreachable!("a binary when not --from"),
                };
                publish(&repo, figure, &dir)?;
            }
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// Runs the figure's command into `runs/ID` and returns that folder: a
/// `plait ab` report, or a table figure's standard output (`stdout.txt`).
fn measure(plait: &Path, figure: &Figure, runs: &Path) -> Result<PathBuf> {
    let dir = runs.join(&figure.id);
    if figure.kind == Kind::Table {
        eprintln!("measuring {}: {}", figure.id, figure.command_line());
        let out = Command::new(&figure.command[0])
            .args(&figure.command[1..])
            .stderr(std::process::Stdio::inherit())
            .output()
            .with_context(|| format!("running {}", figure.command[0]))?;
        let stdout = String::from_utf8_lossy(&out.stdout);
        eprint!("{stdout}");
        if !out.status.success() {
            bail!(
                "figure `{}`: `{}` failed ({})",
                figure.id,
                figure.command_line(),
                out.status
            );
        }
        std::fs::create_dir_all(&dir)?;
        std::fs::write(dir.join("stdout.txt"), stdout.as_bytes())?;
        return Ok(dir);
    }
    eprintln!(
        "measuring {}: {} --out {}",
        figure.id,
        figure.command_line(),
        dir.display()
    );
    let status = Command::new(plait)
        .args(&figure.command)
        .arg("--out")
        .arg(&dir)
        .status()
        .with_context(|| format!("running {}", plait.display()))?;
    if !status.success() {
        bail!(
            "figure `{}`: `{}` failed ({status})",
            figure.id,
            figure.command_line()
        );
    }
    Ok(dir)
}

/// Writes the record, then the page's block from it.
fn publish(repo: &Path, figure: &Figure, dir: &Path) -> Result<()> {
    let record = record_of(repo, figure, dir)?;
    let page = repo.join(&figure.page);
    let text = std::fs::read_to_string(&page).with_context(|| page.display().to_string())?;
    let new = published::replace_block(&text, &figure.id, &record.block(figure))
        .map_err(|e| anyhow::anyhow!("{}: {e}", figure.page))?;
    record.save(&published::record_path(repo, &figure.id))?;
    let tmp = page.with_extension("md.tmp");
    std::fs::write(&tmp, new)?;
    std::fs::rename(&tmp, &page)?;
    say!(
        "wrote {} and its block in {}",
        published::record_path(repo, &figure.id).display(),
        figure.page
    );
    Ok(())
}

/// The record of a measurement in `dir`, as the figure's kind reads it.
fn record_of(repo: &Path, figure: &Figure, dir: &Path) -> Result<Record> {
    let made = made(repo, figure)?;
    Ok(match figure.kind {
        Kind::Ab => Record::from_run(figure, dir, made)?,
        Kind::Table => {
            let path = dir.join("stdout.txt");
            let text =
                std::fs::read_to_string(&path).with_context(|| path.display().to_string())?;
            table::record(figure, &text, made)?
        }
    })
}

/// The commit and date a measurement of `figure` made now belongs to; dirty
/// when a file it measures has uncommitted changes (a page the same run
/// already rewrote is not measured, so it does not count).
fn made(repo: &Path, figure: &Figure) -> Result<published::Made> {
    let git = |args: &[&str]| -> Result<String> {
        let o = Command::new("git").args(args).current_dir(repo).output()?;
        if !o.status.success() {
            bail!(
                "git {}: {}",
                args.join(" "),
                String::from_utf8_lossy(&o.stderr).trim()
            );
        }
        Ok(String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    Ok(published::Made {
        commit: git(&["rev-parse", "HEAD"])?,
        dirty: {
            let specs = figure.pathspecs();
            let mut args = vec!["status", "--porcelain", "--untracked-files=no", "--"];
            args.extend(specs.iter().map(String::as_str));
            !git(&args)?.is_empty()
        },
        date: published::today(),
    })
}

fn short(commit: &str) -> &str {
    &commit[..commit.len().min(10)]
}

fn plait_binary(args: &Args) -> Result<PathBuf> {
    let path = match &args.plait {
        Some(p) => p.clone(),
        None => std::env::current_exe()?.with_file_name("plait"),
    };
    if !path.is_file() {
        bail!(
            "--plait: no `plait` binary at {} (build it: cargo build --locked -p plait-cli)",
            path.display()
        );
    }
    Ok(path)
}
