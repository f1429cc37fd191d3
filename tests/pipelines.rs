//! The compiled schedule of every `pipelines/*.toml` is a committed text
//! snapshot (`tests/snapshots/<stem>.txt`), so a change to the compiler or to a
//! pipeline shows up as a reviewable diff (naga's `tests/in` → `tests/out`).
//! `PLAIT_BLESS=1 cargo test -p plait-tests --test pipelines` rewrites them.

use std::path::Path;

use plait::session::compile_checked;
use plait_graph::CompileOptions;
use plait_tests::{bless, line_diff, pipeline_files, rel, repo_root};

/// The snapshot text, independent of where the checkout lives: absolute
/// paths (pipeline files, shader files) become checkout-relative.
fn snapshot_of(path: &Path) -> Result<String, String> {
    let opts = CompileOptions {
        screen: (960, 720),
        ..Default::default()
    };
    let schedule = compile_checked(path, &[], &opts).map_err(|e| format!("{e}"))?;
    let text = plait_graph::schedule_text(&schedule);
    let root = repo_root();
    let mut roots = vec![format!("{}/", root.display())];
    if let Ok(c) = root.canonicalize() {
        roots.push(format!("{}/", c.display()));
    }
    // Longest first, so `/a/b/crates/../` is removed before `/a/b/`.
    roots.sort_by_key(|r| std::cmp::Reverse(r.len()));
    let mut text = roots.iter().fold(text, |t, r| t.replace(r.as_str(), ""));
    text = text.replace('\\', "/");
    Ok(text
        .lines()
        .map(normalize_dotdot)
        .collect::<Vec<_>>()
        .join("\n")
        + "\n")
}

/// `pipelines/../shaders/x.wgsl` → `shaders/x.wgsl` in every word of a line
/// (a shader named `../shaders/x.wgsl` from `pipelines/` and one named
/// `shaders/x.wgsl` from the root are the same file and snapshot alike).
fn normalize_dotdot(line: &str) -> String {
    line.split(' ')
        .map(|word| {
            if !word.contains("/../") {
                return word.to_owned();
            }
            let mut parts: Vec<&str> = Vec::new();
            for part in word.split('/') {
                if part == ".." && parts.last().is_some_and(|p| *p != "..") {
                    parts.pop();
                } else {
                    parts.push(part);
                }
            }
            parts.join("/")
        })
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn every_pipeline_compiles_and_matches_its_snapshot() {
    let mut failures = Vec::new();
    for path in pipeline_files() {
        let name = rel(&path);
        let stem = path
            .file_stem()
            .expect("file stem")
            .to_string_lossy()
            .into_owned();
        let snap_path = repo_root()
            .join("tests/snapshots")
            .join(format!("{stem}.txt"));
        let actual = match snapshot_of(&path) {
            Ok(t) => t,
            Err(e) => {
                failures.push(format!("{name} does not compile:\n{e}"));
                continue;
            }
        };
        if bless() {
            std::fs::write(&snap_path, &actual)
                .unwrap_or_else(|e| panic!("writing {}: {e}", snap_path.display()));
            eprintln!("blessed {}", rel(&snap_path));
            continue;
        }
        match std::fs::read_to_string(&snap_path) {
            Err(_) => failures.push(format!(
                "{name}: no snapshot {} — review this schedule and run with PLAIT_BLESS=1 to commit it:\n{actual}",
                rel(&snap_path)
            )),
            Ok(committed) if committed != actual => failures.push(format!(
                "{name}: schedule differs from {} (if intended, rerun with PLAIT_BLESS=1 and commit):\n{}",
                rel(&snap_path),
                line_diff(&committed, &actual)
            )),
            Ok(_) => {}
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// A snapshot without a pipeline is stale (renamed or deleted pipeline).
#[test]
fn every_snapshot_has_a_pipeline() {
    let stems: Vec<String> = pipeline_files()
        .iter()
        .map(|p| p.file_stem().expect("stem").to_string_lossy().into_owned())
        .collect();
    let dir = repo_root().join("tests/snapshots");
    let stale: Vec<String> = plait_tests::files_with_ext(&dir, "txt")
        .iter()
        .filter(|p| {
            !stems
                .iter()
                .any(|s| p.file_stem().is_some_and(|f| f.to_string_lossy() == *s))
        })
        .map(|p| rel(p))
        .collect();
    assert!(
        stale.is_empty(),
        "snapshots without a pipeline in pipelines/ (delete them): {}",
        stale.join(", ")
    );
}
