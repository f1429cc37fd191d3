//! Running the `plait` binary from the tests of this crate.
#![allow(dead_code)] // each test file uses a different part

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Duration;

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

/// Writes `text` to `base/relative`, creating its folders.
pub fn write(base: &Path, relative: &str, text: &str) {
    let path = base.join(relative);
    std::fs::create_dir_all(path.parent().expect("a parent")).expect("mkdir");
    std::fs::write(path, text).expect("write");
}

pub fn assert_ok(what: &str, o: &Output) {
    assert!(
        o.status.success(),
        "{what}: exit {:?}\n--- stderr:\n{}",
        o.status.code(),
        text(&o.stderr)
    );
}

/// Exit 2, every `wanted` text in stderr, and no panic.
pub fn assert_refused(what: &str, o: &Output, wanted: &[&str]) {
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{what}: {stderr}");
    for w in wanted {
        assert!(stderr.contains(w), "{what}: no `{w}` in\n{stderr}");
    }
    assert!(!stderr.contains("panicked"), "{what}: {stderr}");
}

/// Runs a copy of the `plait` binary. A test thread forking a child while
/// another still has a fresh copy open for writing lends the child that
/// descriptor until its exec: running the copy then fails with ETXTBSY for
/// a moment. Retried briefly.
pub fn run_copied(cmd: &mut Command) -> Output {
    for _ in 0..50 {
        match cmd.output() {
            Err(e) if e.kind() == std::io::ErrorKind::ExecutableFileBusy => {
                std::thread::sleep(Duration::from_millis(100))
            }
            result => return result.expect("run the copied plait"),
        }
    }
    panic!("the copied plait stayed busy (ETXTBSY) for 5 s")
}
