//! The executables a run needs, built once: the test binaries the plan names
//! (`cargo test --no-run`) and `plait` itself (for `plait check`). Mutants
//! then run these directly, with no rebuild: plait reads its shaders from the
//! checkout at run time.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context, Result, bail};
use indexmap::IndexMap;

use crate::plan::Plan;

/// A built test target: its executable and the folder cargo runs it from.
#[derive(Clone, Debug)]
pub struct TestBinary {
    pub exe: PathBuf,
    pub cwd: PathBuf,
}

#[derive(Debug)]
pub struct Binaries {
    pub plait: PathBuf,
    /// Keyed by cargo target name (`goldens`, `plait_passes` for a lib).
    pub tests: IndexMap<String, TestBinary>,
}

pub fn build(root: &Path, plan: &Plan, techniques: &[String]) -> Result<Binaries> {
    let packages: BTreeSet<&str> = techniques
        .iter()
        .flat_map(|t| plan.techniques[t].tests.iter())
        .map(|r| r.package.as_str())
        .collect();
    let mut args = vec!["test", "--locked", "--no-run", "--message-format=json"];
    for p in &packages {
        args.extend(["-p", p]);
    }
    let tests = artifacts(root, &args)?
        .into_iter()
        .filter(|a| a.test)
        .map(|a| {
            (
                a.name,
                TestBinary {
                    exe: a.exe,
                    cwd: a.cwd,
                },
            )
        })
        .collect();
    let plait = artifacts(
        root,
        &[
            "build",
            "--locked",
            "-p",
            "plait-cli",
            "--bin",
            "plait",
            "--message-format=json",
        ],
    )?
    .into_iter()
    .find(|a| a.name == "plait")
    .context("cargo built no `plait` executable")?
    .exe;
    Ok(Binaries { plait, tests })
}

struct Artifact {
    name: String,
    exe: PathBuf,
    cwd: PathBuf,
    test: bool,
}

/// The executables one cargo command produced (its JSON messages).
fn artifacts(root: &Path, args: &[&str]) -> Result<Vec<Artifact>> {
    eprintln!("plait-mutate: cargo {}", args.join(" "));
    let out = Command::new("cargo")
        .args(args)
        .current_dir(root)
        .stderr(std::process::Stdio::inherit())
        .output()
        .context("running cargo")?;
    if !out.status.success() {
        bail!("cargo {} failed ({})", args.join(" "), out.status);
    }
    let mut found = Vec::new();
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        let Ok(msg) = serde_json::from_str::<serde_json::Value>(line) else {
            continue;
        };
        let Some(exe) = msg["executable"].as_str() else {
            continue;
        };
        let manifest = PathBuf::from(msg["manifest_path"].as_str().unwrap_or_default());
        found.push(Artifact {
            name: msg["target"]["name"]
                .as_str()
                .unwrap_or_default()
                .to_owned(),
            exe: exe.into(),
            cwd: manifest.parent().unwrap_or(root).to_path_buf(),
            test: msg["profile"]["test"].as_bool() == Some(true),
        });
    }
    Ok(found)
}
