//! `tests/mutation.toml`: for each technique, the WGSL that is its own and the
//! checks and tests that guard it.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use indexmap::IndexMap;
use serde::Deserialize;

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plan {
    /// Keyed by `<point>/<name>` (a folder under `techniques/`) or by a name
    /// of a shared stage (then `files` lists all its WGSL).
    pub techniques: IndexMap<String, Technique>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Technique {
    /// WGSL outside the technique's folder that is its own (checkout-relative).
    #[serde(default)]
    pub files: Vec<String>,
    /// What `plait check` must accept for a mutant to count (else: invalid).
    pub check: Vec<Check>,
    /// The tests that guard it, cheapest first: a mutant is killed by the
    /// first that fails.
    pub tests: Vec<TestRun>,
    /// Mutants shown equivalent (id → why): not scored. Still run — one a
    /// test kills is reported, since it was not equivalent after all.
    #[serde(default)]
    pub equivalent: IndexMap<String, String>,
    /// A lower cap than `--max` for a technique whose tests are slow.
    pub max: Option<usize>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Check {
    pub pipeline: String,
    #[serde(default)]
    pub set: Vec<String>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TestRun {
    /// Cargo package of the test target (default `plait-tests`).
    #[serde(default = "default_package")]
    pub package: String,
    /// The test target (`goldens` for `tests/goldens.rs`; `lib` for unit tests).
    pub target: String,
    /// Exact test name(s) to run.
    pub names: Vec<String>,
    /// Environment for the run (e.g. `PLAIT_GOLDENS`).
    #[serde(default)]
    pub env: IndexMap<String, String>,
    /// Written to kill survivors of an earlier run: the table's "before"
    /// column is the score without the kills of these (they run last, so a
    /// mutant they kill passed every other test).
    #[serde(default)]
    pub added_for_mutants: bool,
}

fn default_package() -> String {
    "plait-tests".into()
}

impl TestRun {
    pub fn label(&self) -> String {
        format!("{}::{}", self.target, self.names.join("+"))
    }
}

impl Plan {
    pub fn load(path: &Path) -> Result<Plan> {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        toml::from_str(&text).with_context(|| format!("{}", path.display()))
    }
}

impl Technique {
    /// Its WGSL files, checkout-relative: its folder's, then `files`.
    pub fn wgsl_files(&self, root: &Path, name: &str) -> Result<Vec<String>> {
        let mut out = Vec::new();
        let folder = root.join("techniques").join(name);
        if folder.is_dir() {
            let mut own: Vec<PathBuf> = std::fs::read_dir(&folder)?
                .flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|e| e == "wgsl"))
                .collect();
            own.sort();
            for p in own {
                let rel = p.strip_prefix(root).unwrap_or(&p);
                out.push(rel.to_string_lossy().replace('\\', "/"));
            }
        }
        for f in &self.files {
            if !root.join(f).is_file() {
                bail!("tests/mutation.toml: {name}: no file {f}");
            }
            out.push(f.clone());
        }
        if out.is_empty() {
            bail!("tests/mutation.toml: {name}: no WGSL in its folder and no `files`");
        }
        Ok(out)
    }
}
