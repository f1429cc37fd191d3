//! Running one mutant: written over the checkout's file (plait reads its
//! shaders from the checkout at run time, and a pipeline's own `techniques/`
//! shadows `PLAIT_PATH`, so a copy on the search path would not reach the
//! gallery's tests), checked by `plait check`, then the technique's tests,
//! and the file put back — content and modification time, so cargo sees no
//! change — whatever happens, Ctrl-C included.

use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;
use std::time::{Duration, Instant, SystemTime};

use anyhow::{Context, Result, bail};

use crate::build::Binaries;
use crate::plan::{Check, TestRun};

/// The file a mutant is written over, and how to put it back.
struct Original {
    path: PathBuf,
    text: String,
    modified: SystemTime,
    backup: PathBuf,
}

/// The file currently mutated: restored by [`restore`] and by Ctrl-C.
static CURRENT: Mutex<Option<Original>> = Mutex::new(None);

fn put_back(o: &Original) -> std::io::Result<()> {
    std::fs::write(&o.path, &o.text)?;
    File::options()
        .write(true)
        .open(&o.path)?
        .set_modified(o.modified)?;
    std::fs::remove_file(&o.backup)
}

/// Put the mutated file back, if any.
pub fn restore() -> Result<()> {
    let mut cur = CURRENT.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(o) = cur.take() {
        put_back(&o).with_context(|| format!("restoring {}", o.path.display()))?;
    }
    Ok(())
}

/// Restore on Ctrl-C before exiting, and undo a run that died mid-mutant
/// (its backup, `<work>/backup`, names the file and holds the original).
pub fn install_guard(work: &Path) -> Result<()> {
    std::fs::create_dir_all(work)?;
    let backup = work.join("backup");
    if let Ok(text) = std::fs::read_to_string(&backup) {
        let (path, original) = text.split_once('\n').context("malformed backup")?;
        std::fs::write(path, original)?;
        std::fs::remove_file(&backup)?;
        eprintln!("plait-mutate: restored {path} left mutated by an interrupted run");
    }
    ctrlc::set_handler(|| {
        let _ = restore();
        std::process::exit(130);
    })
    .context("installing the Ctrl-C handler")
}

/// Write `mutated` over `path` (checkout file), keeping what to restore.
pub fn write_mutant(work: &Path, path: &Path, mutated: &str) -> Result<()> {
    restore()?;
    let text = std::fs::read_to_string(path)?;
    let modified = std::fs::metadata(path)?.modified()?;
    let backup = work.join("backup");
    std::fs::write(&backup, format!("{}\n{text}", path.display()))?;
    *CURRENT.lock().unwrap_or_else(|p| p.into_inner()) = Some(Original {
        path: path.to_path_buf(),
        text,
        modified,
        backup,
    });
    std::fs::write(path, mutated).with_context(|| format!("writing {}", path.display()))
}

/// `plait check` of every entry: `Err(first line of the message)` if one is refused.
pub fn check(bins: &Binaries, root: &Path, checks: &[Check]) -> Result<Result<(), String>> {
    for c in checks {
        let mut cmd = Command::new(&bins.plait);
        cmd.arg("check").arg(&c.pipeline).current_dir(root);
        for s in &c.set {
            cmd.args(["--set", s]);
        }
        let out = cmd
            .env_remove("PLAIT_PATH")
            .output()
            .context("running plait check")?;
        if !out.status.success() {
            let err = String::from_utf8_lossy(&out.stderr);
            let first = err.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
            return Ok(Err(format!("{}: {first}", c.pipeline)));
        }
    }
    Ok(Ok(()))
}

/// How one test run ended.
#[derive(Debug)]
pub enum Ended {
    Passed { tests: usize, secs: f64 },
    Failed { secs: f64 },
    TimedOut { secs: f64 },
}

/// Run one plan entry, its output to `log`, killed after `timeout`.
pub fn run_test(bins: &Binaries, t: &TestRun, timeout: Duration, log: &Path) -> Result<Ended> {
    let Some(bin) = bins.tests.get(&t.target) else {
        bail!(
            "tests/mutation.toml names test target `{}`, which cargo did not build",
            t.target
        );
    };
    let out = File::create(log)?;
    let mut cmd = Command::new(&bin.exe);
    cmd.args(&t.names)
        .args(["--exact", "--test-threads=1"])
        .envs(&t.env)
        .env_remove("PLAIT_PATH")
        .env("RUST_BACKTRACE", "0")
        .current_dir(&bin.cwd)
        .stdout(out.try_clone()?)
        .stderr(out);
    let start = Instant::now();
    let mut child = cmd
        .spawn()
        .with_context(|| format!("running {}", bin.exe.display()))?;
    loop {
        if let Some(status) = child.try_wait()? {
            let secs = start.elapsed().as_secs_f64();
            if !status.success() {
                return Ok(Ended::Failed { secs });
            }
            return Ok(Ended::Passed {
                tests: tests_run(log)?,
                secs,
            });
        }
        if start.elapsed() > timeout {
            child.kill()?;
            child.wait()?;
            return Ok(Ended::TimedOut {
                secs: start.elapsed().as_secs_f64(),
            });
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// How many tests libtest says it ran (`running N tests`), summed.
fn tests_run(log: &Path) -> Result<usize> {
    let text = std::fs::read_to_string(log)?;
    Ok(text
        .lines()
        .filter_map(|l| l.strip_prefix("running "))
        .filter_map(|l| l.split_whitespace().next()?.parse::<usize>().ok())
        .sum())
}
