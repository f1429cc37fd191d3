//! Running the `plait` binary from the tests of this crate.
#![allow(dead_code)] // each test file uses a different part

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The checkout root, where `pipelines/` and `examples/` are.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("checkout root")
}

/// `plait ARGS...`, run from the checkout root.
pub fn plait(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .args(args)
        .output()
        .expect("run plait")
}

pub fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// `plait ARGS` from the checkout with `PLAIT_PATH` = `library`, then the
/// checkout (so only what `library` adds or replaces differs).
pub fn with_library(library: &Path, args: &[&str]) -> Output {
    let path = std::env::join_paths([library.to_path_buf(), root()]).expect("join paths");
    Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .env("PLAIT_PATH", path)
        .args(args)
        .output()
        .expect("run plait")
}
