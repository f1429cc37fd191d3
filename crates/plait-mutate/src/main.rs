//! `plait-mutate`: a mutation score for every technique (scripts/mutate.sh).
//!
//! Each technique's WGSL (its folder's and the files `tests/mutation.toml`
//! names) is mutated one change at a time — a comparison flipped, an
//! operator swapped, a term dropped, a constant ×1.1 / ×0.9, two call
//! arguments swapped, a loop bound moved, a return made zero — and the
//! technique's own golden, claims and unit tests run against each mutant.
//! A mutant that `plait check` refuses is reported as invalid and not
//! scored: it says nothing about the tests.

mod build;
mod operators;
mod plan;
mod report;
mod run;
mod technique;
mod tokens;

use std::path::PathBuf;

use anyhow::{Result, bail};
use clap::Parser;

#[derive(Parser)]
#[command(about = "Mutation score of plait's techniques against their own tests")]
struct Args {
    /// Techniques (`<point>/<name>`, keys of the plan); none: all of them.
    techniques: Vec<String>,
    /// Valid mutants run per technique (a seeded sample).
    #[arg(long, default_value_t = 20)]
    max: usize,
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Run only these mutant ids (repeatable), e.g. to check a new test.
    #[arg(long)]
    only: Vec<String>,
    /// List the mutants (id and diff) without running anything.
    #[arg(long)]
    list: bool,
    #[arg(long, default_value = "tests/mutation.toml")]
    plan: PathBuf,
    /// Where the table (`mutation.md`) and every result (`mutation.json`) go.
    #[arg(long, default_value = "target/mutate")]
    out: PathBuf,
}

fn main() -> Result<()> {
    let args = Args::parse();
    let root = std::env::current_dir()?;
    let plan = plan::Plan::load(&root.join(&args.plan))?;
    let names: Vec<String> = if args.techniques.is_empty() {
        plan.techniques.keys().cloned().collect()
    } else {
        args.techniques.clone()
    };
    for n in &names {
        if !plan.techniques.contains_key(n) {
            bail!("{} has no technique `{n}`", args.plan.display());
        }
    }
    if args.list {
        return list(&root, &plan, &names);
    }
    let work = root.join(&args.out);
    run::install_guard(&work)?;
    let bins = build::build(&root, &plan, &names)?;
    let o = technique::Options {
        root: &root,
        work: &work,
        bins: &bins,
        max: args.max,
        seed: args.seed,
        only: &args.only,
    };
    let header = report::Header::now(&root, &args.techniques, &args.only, args.max, args.seed)?;
    let mut all = Vec::new();
    for n in &names {
        eprintln!("plait-mutate: {n}");
        let results = technique::run(&o, n, &plan.techniques[n]);
        run::restore()?;
        all.push((n.clone(), results?));
        // After each technique, so an interrupted run keeps what it measured.
        report::write(&work, &header, &all)?;
    }
    print!("{}", report::table(&header, &all));
    // A misspelt `--only` id runs nothing: say so rather than report success.
    let ran: Vec<&str> = all
        .iter()
        .flat_map(|(_, rs)| rs)
        .map(|r| r.id.as_str())
        .collect();
    let missing: Vec<&String> = args
        .only
        .iter()
        .filter(|id| !ran.contains(&id.as_str()))
        .collect();
    if !missing.is_empty() {
        bail!("--only names no mutant of these techniques: {missing:?}");
    }
    Ok(())
}

fn list(root: &std::path::Path, plan: &plan::Plan, names: &[String]) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    for n in names {
        for f in plan.techniques[n].wgsl_files(root, n)? {
            let src = std::fs::read_to_string(root.join(&f))?;
            for m in operators::mutants(&f, &src) {
                // A closed pipe (`| head`) ends the listing, not in a panic.
                if writeln!(out, "{n} {}\n{}", m.id(), m.diff(&src)).is_err() {
                    return Ok(());
                }
            }
        }
    }
    Ok(())
}
