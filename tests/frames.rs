//! Frames on the GPU: state across frames (a persistent buffer accumulates
//! over three frames, a pass reads last frame's version of a resource with a
//! history: `tests/fixtures/history/history.toml`) and the head animation
//! of `examples/scenes/head_turn.toml`.

use plait::frames::render_sequence;
use plait::session::{SceneData, SessionError, prepare};
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
    let mut prepared =
        prepare(&gpu, &pipeline, &[], &scene, size).unwrap_or_else(|e| panic!("history.toml: {e}"));
    for frame in 0..3u32 {
        prepared.set_frame(&scene.frame(size, frame));
        prepared.render().expect("renders");
        let read = |name: &str| words(&prepared.read_buffer(name).expect(name));
        let expected_total: Vec<u32> = (0..4).map(|i| (frame + 1) * (i + 1)).collect();
        assert_eq!(read("total"), expected_total, "total after frame {frame}");
        // Last frame's values; zero before the first frame.
        let expected_seen: Vec<u32> = (0..4)
            .map(|i| if frame == 0 { 0 } else { (frame - 1) * 10 + i })
            .collect();
        assert_eq!(read("seen"), expected_seen, "seen in frame {frame}");
        // The texture's history, one and two frames back (zero before).
        let back = |k: u32| -> Vec<u32> {
            (0..4)
                .map(|i| if frame < k { 0 } else { (frame - k) * 100 + i })
                .collect()
        };
        assert_eq!(
            read("seen_texels"),
            [back(1), back(2)].concat(),
            "texels seen in frame {frame}"
        );
        assert_eq!(
            read("frame_value.previous"),
            (0..4).map(|i| frame * 10 + i).collect::<Vec<_>>(),
            "after frame {frame} the engine has aged frame_value into .previous"
        );
    }
}

/// The head turns and comes back: the turned frame differs from the first
/// (head and hair moved), the frame back at rest equals the first exactly.
#[test]
fn the_head_turn_moves_head_and_hair_and_comes_back() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/head_turn.toml")))
        .expect("head_turn.toml loads");
    let pipeline = plait::session::resolve_pipeline(None);
    let size = (64, 48);
    let sets = ["params.light_size=128".to_owned()];
    let mut prepared = prepare(&gpu, &pipeline, &sets, &scene, size).expect("prepares");
    // 2 fps: frames at 0 s, 0.5 s, 1 s (turned 45°), 1.5 s, 2 s (back at rest).
    let mut images = Vec::new();
    let reports = render_sequence(&mut prepared, &scene, size, 5, 2.0, |_, _, image| {
        images.push(image);
        Ok::<(), SessionError>(())
    })
    .expect("renders");
    assert_eq!(reports.len(), 5);
    let differing = |a: &image::RgbaImage, b: &image::RgbaImage| {
        a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count()
    };
    let turned = differing(&images[0], &images[2]);
    assert!(
        turned > (size.0 * size.1 / 20) as usize,
        "only {turned} pixels changed with the head turned 45°"
    );
    assert_eq!(
        differing(&images[0], &images[4]),
        0,
        "back at rest, the frame must equal the first"
    );
}
