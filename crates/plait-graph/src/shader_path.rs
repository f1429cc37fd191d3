//! Where a pass's `shader = "…"` file is: resolved once, outside the
//! parsing and merging of the pipeline tree.

use std::path::{Path, PathBuf};

use crate::error::Location;

/// A shader path is relative to the file that wrote it; failing that, to the
/// repository root (the first ancestor holding `shaders/`), so pipelines can
/// say `shader = "shaders/x.wgsl"`; failing that, on the library search path
/// (`plait_assets::find_named`), so a pipeline copied out of the repository
/// still finds the library's shaders. The first candidate that exists wins; if
/// none does, the file-relative path is kept for the error message of
/// whoever opens it.
pub fn resolve_shader(written: &str, location: &Location) -> PathBuf {
    let base_dir = match location {
        Location::File { path, .. } => path.parent().map(Path::to_path_buf).unwrap_or_default(),
        _ => std::env::current_dir().unwrap_or_default(),
    };
    let next_to_file = base_dir.join(written);
    if plait_assets::exists(&next_to_file) {
        return next_to_file;
    }
    // Lexical ancestors first, so relative inputs give relative (stable,
    // snapshot-friendly) paths; then the canonical ones, for `x.toml` run
    // from inside `pipelines/`.
    let absolute_base = std::fs::canonicalize(&base_dir).unwrap_or_else(|_| base_dir.clone());
    // A built-in copy has no disk ancestors (its last lexical one, "", would
    // be the working directory).
    let ancestors = if plait_assets::is_builtin(&base_dir) {
        vec![]
    } else {
        vec![&base_dir, &absolute_base]
    };
    for base in ancestors {
        let root = base.ancestors().find(|a| a.join("shaders").is_dir());
        if let Some(root) = root {
            let candidate = root.join(written);
            if candidate.exists() {
                return candidate;
            }
        }
    }
    plait_assets::find_named(written, "shaders").unwrap_or(next_to_file)
}
