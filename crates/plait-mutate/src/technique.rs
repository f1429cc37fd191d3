//! One technique's run: its tests on the unmutated checkout (they must pass,
//! each running the tests it names), then a seeded sample of its mutants.

use std::path::Path;
use std::time::Duration;

use anyhow::{Result, bail};

use crate::build::Binaries;
use crate::operators::{Mutant, mutants};
use crate::plan::Technique;
use crate::run::{Ended, check, restore, run_test, write_mutant};

/// What became of one mutant.
#[derive(Debug, serde::Serialize)]
#[serde(tag = "outcome", rename_all = "snake_case")]
pub enum Outcome {
    /// A test failed: the first one that did (`added`: a test written for
    /// survivors, `added_for_mutants`).
    Killed {
        by: String,
        added: bool,
        secs: f64,
    },
    /// A test ran past its timeout (counted as killed).
    Hung {
        by: String,
        added: bool,
        secs: f64,
    },
    Survived {
        secs: f64,
    },
    /// `plait check` refused it: says nothing about the tests, not scored.
    Invalid {
        message: String,
    },
}

#[derive(Debug, serde::Serialize)]
pub struct Result1 {
    pub id: String,
    #[serde(flatten)]
    pub mutant: Mutant,
    pub diff: String,
    #[serde(flatten)]
    pub outcome: Outcome,
    /// Why it is equivalent, when `tests/mutation.toml` says it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub equivalent: Option<String>,
}

/// Options shared by every technique of a run.
#[derive(Debug)]
pub struct Options<'a> {
    pub root: &'a Path,
    pub work: &'a Path,
    pub bins: &'a Binaries,
    pub max: usize,
    pub seed: u64,
    /// Run only these mutant ids (empty: a sample of `max`).
    pub only: &'a [String],
}

/// Every mutant of the technique's files, in a seeded order.
pub fn candidates(o: &Options, name: &str, t: &Technique) -> Result<Vec<(Mutant, String)>> {
    let mut all = Vec::new();
    for f in t.wgsl_files(o.root, name)? {
        let src = std::fs::read_to_string(o.root.join(&f))?;
        for m in mutants(&f, &src) {
            all.push((m, src.clone()));
        }
    }
    // An equivalence claimed for no mutant is a stale or misspelt id.
    for id in t.equivalent.keys() {
        if !all.iter().any(|(m, _)| m.id() == *id) {
            bail!("tests/mutation.toml: {name}: `{id}` is claimed equivalent but is no mutant");
        }
    }
    if !o.only.is_empty() {
        all.retain(|(m, _)| o.only.contains(&m.id()));
        return Ok(all);
    }
    shuffle(&mut all, o.seed);
    Ok(all)
}

/// Fisher–Yates with xorshift64*: the same seed, the same order, on any machine.
fn shuffle<T>(v: &mut [T], seed: u64) {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    for i in (1..v.len()).rev() {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        let r = s.wrapping_mul(0x2545_F491_4F6C_DD1D);
        v.swap(i, (r % (i as u64 + 1)) as usize);
    }
}

/// The technique's tests on the unmutated checkout: each must pass and run
/// as many tests as it names (a misspelt name runs none and would pass
/// every mutant). Returns each run's timeout.
pub fn baseline(o: &Options, name: &str, t: &Technique) -> Result<Vec<Duration>> {
    if let Err(e) = check(o.bins, o.root, &t.check)? {
        bail!("{name}: plait check refuses the unmutated checkout: {e}");
    }
    let mut timeouts = Vec::new();
    for r in &t.tests {
        let log = o.work.join("baseline.log");
        match run_test(o.bins, r, Duration::from_secs(3600), &log)? {
            Ended::Passed { tests, secs } if tests == r.names.len() => {
                eprintln!("  baseline {}: passed in {secs:.1} s", r.label());
                timeouts.push(Duration::from_secs_f64(3.0 * secs + 30.0));
            }
            Ended::Passed { tests, .. } => bail!(
                "{name}: {} ran {tests} tests, not {} (names must be exact)",
                r.label(),
                r.names.len()
            ),
            other => bail!(
                "{name}: {} fails without a mutant ({other:?}); see {}",
                r.label(),
                log.display()
            ),
        }
    }
    Ok(timeouts)
}

/// Run the sample: mutants are taken in seeded order until `max` valid ones
/// have run (invalid ones are recorded but do not use up the sample).
pub fn run(o: &Options, name: &str, t: &Technique) -> Result<Vec<Result1>> {
    let timeouts = baseline(o, name, t)?;
    let mut results = Vec::new();
    let mut valid = 0;
    for (m, src) in candidates(o, name, t)? {
        if o.only.is_empty() && valid >= t.max.map_or(o.max, |m| m.min(o.max)) {
            break;
        }
        let path = o.root.join(&m.file);
        write_mutant(o.work, &path, &m.apply(&src))?;
        let outcome = match check(o.bins, o.root, &t.check)? {
            Err(message) => Outcome::Invalid { message },
            Ok(()) => {
                valid += 1;
                tests(o, t, &timeouts, &m.id())?
            }
        };
        restore()?;
        eprintln!("  {:<60} {}", m.id(), short(&outcome));
        results.push(Result1 {
            equivalent: t.equivalent.get(&m.id()).cloned(),
            id: m.id(),
            diff: m.diff(&src),
            mutant: m,
            outcome,
        });
    }
    Ok(results)
}

/// The tests against the mutant in place; each run's output kept in
/// `<work>/logs/<id>.log` (the last one: what killed it, with its numbers).
fn tests(o: &Options, t: &Technique, timeouts: &[Duration], id: &str) -> Result<Outcome> {
    let logs = o.work.join("logs");
    std::fs::create_dir_all(&logs)?;
    let log = logs.join(format!("{}.log", id.replace(['/', ':'], "_")));
    let mut total = 0.0;
    for (r, &timeout) in t.tests.iter().zip(timeouts) {
        match run_test(o.bins, r, timeout, &log)? {
            Ended::Passed { secs, .. } => total += secs,
            Ended::Failed { secs } => {
                return Ok(Outcome::Killed {
                    by: r.label(),
                    added: r.added_for_mutants,
                    secs: total + secs,
                });
            }
            Ended::TimedOut { secs } => {
                return Ok(Outcome::Hung {
                    by: r.label(),
                    added: r.added_for_mutants,
                    secs: total + secs,
                });
            }
        }
    }
    Ok(Outcome::Survived { secs: total })
}

fn short(o: &Outcome) -> String {
    match o {
        Outcome::Killed { by, secs, .. } => format!("killed by {by} ({secs:.0} s)"),
        Outcome::Hung { by, secs, .. } => format!("hung in {by} ({secs:.0} s)"),
        Outcome::Survived { secs } => format!("SURVIVED ({secs:.0} s)"),
        Outcome::Invalid { message } => {
            format!("invalid: {}", message.chars().take(80).collect::<String>())
        }
    }
}
