//! State across frames on the GPU: a persistent buffer accumulates over
//! three frames, and a pass reads last frame's version of a resource with a
//! history (`tests/fixtures/history/history.toml`).

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

fn words(bytes: &[u8]) -> Vec<u32> {
    bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

#[test]
fn a_persistent_buffer_accumulates_and_previous_holds_last_frame() {
    let (_lock, gpu) = open_gpu();
    let pipeline = repo_root().join("tests/fixtures/history/history.toml");
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let size = (8, 8);
    let prepared =
        prepare(&gpu, &pipeline, &[], &scene, size).unwrap_or_else(|e| panic!("history.toml: {e}"));
    for frame in 0..3u32 {
        prepared.renderer.set_frame(&scene.frame(size, frame));
        prepared.renderer.render().expect("renders");
        let read = |name: &str| words(&prepared.renderer.read_buffer(name).expect(name));
        let expected_total: Vec<u32> = (0..4).map(|i| (frame + 1) * (i + 1)).collect();
        assert_eq!(read("total"), expected_total, "total after frame {frame}");
        // Last frame's values; zero before the first frame.
        let expected_seen: Vec<u32> = (0..4)
            .map(|i| if frame == 0 { 0 } else { (frame - 1) * 10 + i })
            .collect();
        assert_eq!(read("seen"), expected_seen, "seen in frame {frame}");
        assert_eq!(
            read("frame_value.previous"),
            (0..4).map(|i| frame * 10 + i).collect::<Vec<_>>(),
            "after frame {frame} the engine has aged frame_value into .previous"
        );
    }
}
