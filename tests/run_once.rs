//! `run = "once"`: a precompute pass records on an executor's first frame
//! only, and what it wrote is still there on every later frame.

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (32, 32);

fn words(bytes: &[u8]) -> Vec<u32> {
    bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

#[test]
fn a_run_once_pass_records_on_the_first_frame_only_and_its_output_is_kept() {
    let (_lock, gpu) = open_gpu();
    let pipeline = repo_root().join("tests/fixtures/run_once.toml");
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let mut prepared = prepare(&gpu, &pipeline, &[], &scene, SIZE)
        .unwrap_or_else(|e| panic!("run_once.toml: {e}"));
    let schedule = prepared.schedule();
    let once = schedule
        .resources
        .iter()
        .find(|r| r.name == "once")
        .expect("`once` is scheduled");
    assert!(
        once.kept,
        "what a run-once pass writes is kept across frames"
    );
    assert_eq!(
        schedule.physical[once.physical].users.len(),
        1,
        "a kept resource shares no allocation"
    );
    for frame in 0..3u32 {
        prepared.set_frame(&scene.frame(SIZE, frame));
        let report = prepared.render_unchecked().expect("renders");
        let tally = report
            .passes
            .iter()
            .find(|p| p.name == "tally_once")
            .expect("tally_once timed");
        assert_eq!(tally.cached, frame > 0, "frame {frame}: cached flag");
        let out = words(&prepared.read_buffer("out").expect("out"));
        // The tally writes frame index + 1: 1 means it last ran on frame 0.
        assert!(
            out.iter().all(|&w| w == 1),
            "frame {frame}: `out` should hold frame 0's tally (1), found {:?}",
            &out[..4]
        );
    }
}
