//! `plait render` loads, compiles and reads the pass library once per
//! render, with `--show` (an output added to the loaded pipeline, not a
//! second load) and `--frames` (one schedule for every frame) too. The
//! binary prints what it did with `PLAIT_COUNT=1`.

mod common;

use common::{root, text};

/// The counts line of `plait render ARGS` on the small scene.
fn counts(args: &[&str]) -> String {
    let dir = tempfile::tempdir().expect("tempdir");
    // A sequence's --out is a folder.
    let frames = args.contains(&"--frames");
    let out = dir.path().join(if frames { "seq" } else { "x.png" });
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .env("PLAIT_COUNT", "1")
        .args(["render", "--scene", "examples/scenes/small.toml"])
        .args(["--size", "32x24", "--set", "params.light_size=64"])
        .args(args)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("run plait");
    let stderr = text(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    stderr
        .lines()
        .find(|l| l.starts_with("counts: "))
        .unwrap_or_else(|| panic!("no counts line in: {stderr}"))
        .to_owned()
}

const ONCE: &str = "counts: loads=1 compiles=1 pass_library_reads=1";

#[test]
fn a_render_loads_and_compiles_once() {
    assert_eq!(counts(&[]), ONCE);
}

#[test]
fn show_adds_its_output_without_a_second_compile() {
    assert_eq!(counts(&["--show", "light_range"]), ONCE);
}

#[test]
fn a_sequence_compiles_once_for_all_its_frames() {
    assert_eq!(counts(&["--frames", "3"]), ONCE);
}
