//! The book's figures come from the `plait` binary itself — the same
//! commands a reader types (each page shows the command that made its
//! picture), so a page cannot describe a CLI that no longer exists.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::error::BookError;

/// One `plait` binary, run from the repository root.
#[derive(Clone, Debug)]
pub struct Plait {
    pub exe: PathBuf,
    pub repo: PathBuf,
}

impl Plait {
    /// Runs `plait ARGS…` and returns its stdout; a failure carries stderr.
    pub fn run(&self, args: &[String]) -> Result<String, BookError> {
        let shown = format!("plait {}", args.join(" "));
        // Renders take minutes in all on a software rasterizer: say each one,
        // so the build is never silent for long.
        if args.first().is_some_and(|a| a == "render") {
            eprintln!("book: {shown}");
        }
        let out = Command::new(&self.exe)
            .args(args)
            .current_dir(&self.repo)
            .output()
            .map_err(BookError::io(&self.exe))?;
        if !out.status.success() {
            return Err(BookError::Command {
                command: shown,
                status: out.status.to_string(),
                stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
            });
        }
        Ok(String::from_utf8_lossy(&out.stdout).into_owned())
    }

    /// `plait … --json`, parsed.
    pub fn json(&self, args: &[&str]) -> Result<serde_json::Value, BookError> {
        let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        let text = self.run(&args)?;
        serde_json::from_str(&text).map_err(|e| BookError::Command {
            command: format!("plait {}", args.join(" ")),
            status: "output is not JSON".into(),
            stderr: e.to_string(),
        })
    }
}

/// A render or graph the book shows, as the command a reader would type.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Figure {
    /// The pipeline, by the name the search path finds (`deep_opacity.toml`).
    pub pipeline: String,
    /// `--set` values (`techniques.shading=marschner`).
    pub sets: Vec<String>,
}

impl Figure {
    fn set_args(&self) -> Vec<String> {
        self.sets
            .iter()
            .flat_map(|s| ["--set".to_string(), s.clone()])
            .collect()
    }

    /// `render PIPELINE --scene SCENE --size WxH [--set …]`.
    pub fn render_args(&self, scene: &str, size: (u32, u32)) -> Vec<String> {
        let mut args = vec![
            "render".to_string(),
            self.pipeline.clone(),
            "--scene".into(),
            scene.to_string(),
            "--size".into(),
            format!("{}x{}", size.0, size.1),
        ];
        args.extend(self.set_args());
        args
    }

    /// `graph PIPELINE --format svg [--set …]`.
    pub fn graph_args(&self) -> Vec<String> {
        let mut args = vec![
            "graph".to_string(),
            self.pipeline.clone(),
            "--format".into(),
            "svg".into(),
        ];
        args.extend(self.set_args());
        args
    }

    /// Renders to `out` (PNG) and returns the command as shown on the page.
    pub fn render(
        &self,
        plait: &Plait,
        scene: &str,
        size: (u32, u32),
        out: &Path,
    ) -> Result<String, BookError> {
        run_to(plait, self.render_args(scene, size), out)
    }

    /// Writes the schedule's SVG to `out`; returns the command as shown.
    pub fn graph(&self, plait: &Plait, out: &Path) -> Result<String, BookError> {
        run_to(plait, self.graph_args(), out)
    }
}

/// Runs `plait ARGS --out OUT`; returns the command as a page shows it,
/// without the `--out` of this machine's stage.
fn run_to(plait: &Plait, mut args: Vec<String>, out: &Path) -> Result<String, BookError> {
    let shown = format!("plait {}", args.join(" "));
    args.push("--out".into());
    args.push(out.display().to_string());
    plait.run(&args)?;
    Ok(shown)
}
