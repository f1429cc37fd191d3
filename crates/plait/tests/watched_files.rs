//! `session::watched_files`: what the viewer and `render --watch` watch.

use std::path::{Path, PathBuf};

use plait::session::watched_files;
use plait::source::PipelineSource;

/// The library-read counter is per process: the tests of this file take
/// turns, so one's read is not counted in another's.
static TURN: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("checkout")
}

fn has(files: &[PathBuf], tail: &str) -> bool {
    files.iter().any(|f| f.ends_with(tail))
}

#[test]
fn a_pipeline_watches_its_chain_techniques_shaders_and_scene() {
    let _turn = TURN.lock().unwrap_or_else(|e| e.into_inner());
    let root = root();
    let scene = root.join("examples/scenes/small.toml");
    let source = PipelineSource::new(&root.join("pipelines/occupancy_no_slab.toml"), &[]);
    // The watch set comes from the library value the render holds: listing
    // it reads no second library.
    let reads = plait_passes::library_reads();
    let files = watched_files(&source, Some(&scene));
    assert_eq!(
        plait_passes::library_reads(),
        reads,
        "watched_files read a library of its own"
    );
    for tail in [
        "pipelines/occupancy_no_slab.toml",
        "pipelines/occupancy.toml",                          // extended
        "techniques/self_shadow/occupancy/technique.toml",   // chosen
        "techniques/self_shadow/light_range.toml",           // included by it
        "shaders/passes/depth_range.wgsl",                   // a pass type's own
        "techniques/transparency/occupancy_order/hair.wgsl", // a technique's own
        "shaders/lib/frame.wgsl",                            // the library
        "examples/scenes/small.toml",
    ] {
        assert!(has(&files, tail), "{tail} is not watched: {files:#?}");
    }
    assert!(files.iter().all(|f| !plait_assets::is_builtin(f)));
}

#[test]
fn a_pipeline_that_does_not_load_still_watches_itself_and_what_its_errors_name() {
    let _turn = TURN.lock().unwrap_or_else(|e| e.into_inner());
    let dir = tempfile::tempdir().expect("temp dir");
    let broken = dir.path().join("broken.toml");
    std::fs::write(&broken, "[pipeline\nname = 1\n").expect("write");
    let files = watched_files(&PipelineSource::new(&broken, &[]), None);
    assert!(files.contains(&broken), "{files:?}");
    assert!(has(&files, "shaders/lib/frame.wgsl"));
}
