//! `transparency/linked_list`: the hair pass's overflow words
//! (`techniques/transparency/linked_list/hair_lists.wgsl`) and the resolve
//! (`shaders/passes/linked_list_resolve.wgsl`) on hand-built lists.

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

fn words(bytes: &[u8]) -> Vec<u32> {
    bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// A pool of one node per pixel (a user-set `nodes_per_pixel` is a cap, not
/// grown) overflows on the small scene, and the counter says by exactly how
/// much: word 1 (dropped) = word 0 (asked for) − the pool's nodes. The
/// session grows the default pool until nothing drops, so no other test
/// reads word 1 with anything in it. Kills, in `hair_lists.wgsl`, the
/// pool's capacity `/ 4u` → `/ 5u` (a fifth of the pool dropped too) and
/// the drop count `+ 1u` → `+ 2u`.
#[test]
fn linked_lists_drop_exactly_what_their_pool_cannot_hold() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("pipelines/linked_list.toml");
    let (w, h) = (64u32, 48u32);
    let sets = ["params.nodes_per_pixel=1".to_string()];
    let prepared = prepare(&gpu, &pipeline, &sets, &scene, (w, h)).expect("prepares");
    prepared.render_unchecked().expect("renders");
    let counter = words(&prepared.read_buffer("list_counter").expect("counter"));
    let capacity = w * h;
    eprintln!("pool {capacity} nodes: counter words {counter:?}");
    assert!(
        counter[0] > capacity + 100,
        "the pool must overflow: {} asked for, {capacity} held",
        counter[0]
    );
    assert_eq!(counter[1], counter[0] - capacity, "dropped = asked − pool");
}

/// The resolve on three hand-built lists (`tests/fixtures/ll_lists.wgsl`,
/// a pool of 24 nodes), the nearest 2 kept, equals their front-to-back blend
/// (Sintorn & Assarsson 2009 §2.2) within 1e-3 (half floats) and reports no
/// pixel incomplete. Pixel 0 meets red (0.5), green (0.2), blue (0.3): the
/// nearest two blended are green then blue, (0, 0.5, 0.25, 0.75); pixel 1
/// is its one fragment, (0.25, 0.25, 0.25, 0.25); pixel 2 meets 19 red at
/// 0.9, then white at 0.1 (each α 0.5): white then red, (0.75, 0.5, 0.5,
/// 0.75). Kills, in `linked_list_resolve.wgsl`, the full heap's test
/// against its root `heap[0]` → `heap[1]` (pixel 0 keeps red over blue) and
/// the walk's bound `/ 4u` → `/ 5u` (96 words: a bound of 19 nodes, pixel
/// 2's white never met, two reds blended).
#[test]
fn linked_list_resolve_blends_the_nearest_of_hand_built_lists() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/ll_lists.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (3, 1)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let counter = words(&prepared.read_buffer("counter").expect("counter"));
    let hair = prepared.read_resource("hair").expect("hair");
    let texel = |x: usize| -> [f32; 4] {
        std::array::from_fn(|c| {
            let o = 16 * x + 4 * c;
            f32::from_le_bytes(hair.bytes[o..o + 4].try_into().expect("4 bytes"))
        })
    };
    let want = [
        [0.0, 0.5, 0.25, 0.75],
        [0.25, 0.25, 0.25, 0.25],
        [0.75, 0.5, 0.5, 0.75],
    ];
    let mut failures = Vec::new();
    for (x, w) in want.iter().enumerate() {
        let got = texel(x);
        eprintln!("pixel {x}: {got:?}, front to back {w:?}");
        if got.iter().zip(w).any(|(g, w)| (g - w).abs() > 1e-3) {
            failures.push(format!("pixel {x}: {got:?}, want {w:?}"));
        }
    }
    eprintln!("counter words {counter:?}");
    if counter != [0, 0, 0] {
        failures.push(format!("counter words {counter:?}, want none"));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
