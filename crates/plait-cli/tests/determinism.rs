//! Determinism across processes (issue 14): two `plait render` runs of the
//! same pipeline, scene and size write byte-identical PNGs. The in-process
//! checks of every pipeline, and why per-pixel fragment lists are
//! deterministic only while their node pool holds every fragment, are in
//! `tests/determinism.rs` at the checkout root.

mod common;
use common::{plait, text};

#[test]
fn two_processes_write_identical_images() {
    let dir = tempfile::tempdir().expect("tempdir");
    // The default pipeline, and the two whose images come from the order
    // of atomics (fragment lists) or from float sums (weighted average).
    for pipeline in [
        "pipelines/occupancy.toml",
        "pipelines/linked_list.toml",
        "pipelines/weighted_average.toml",
    ] {
        let mut images = Vec::new();
        for run in 0..2 {
            let out = dir.path().join(format!("run{run}.png"));
            let o = plait(&[
                "render",
                pipeline,
                "--scene",
                "examples/scenes/small.toml",
                "--size",
                "64x48",
                "--out",
                out.to_str().expect("utf-8"),
            ]);
            assert!(o.status.success(), "{pipeline}: {}", text(&o.stderr));
            images.push(std::fs::read(&out).expect("image written"));
        }
        assert!(images[0] == images[1], "{pipeline}: the two runs differ");
    }
}
