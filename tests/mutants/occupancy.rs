//! `self_shadow/occupancy`: the order estimate of `shaders/lib/occupancy.wgsl`.

use plait::session::{SceneData, prepare};
use plait_passes::occupancy::{TexelMaps, fragment_order, order_estimate};
use plait_tests::{open_gpu, repo_root};

/// The texels of `tests/fixtures/occupancy_cases.wgsl`: each has a set bit
/// in its last slice.
fn texels() -> [TexelMaps; 2] {
    [
        TexelMaps {
            bits: vec![0x8000_0001],
            counts: vec![4],
        },
        TexelMaps {
            bits: vec![0x0000_0101, 0, 0, 0xC000_0000],
            counts: vec![3, 0, 0, 5],
        },
    ]
}

/// The fixture's relative depths: the middle or the last twentieth of each
/// 128th (a slice's fraction past 0.9), then in front,
/// at the front edge, at the back edge and behind.
fn depths() -> Vec<f32> {
    let mut d: Vec<f32> = (0..128)
        .map(|k| (k as f32 + if k % 2 == 1 { 0.95 } else { 0.5 }) / 128.0)
        .collect();
    d.extend([-0.5, 0.0, 1.0, 1.5]);
    d
}

/// `order_estimate` and `fragment_order` on the GPU equal their CPU mirror
/// (`plait_passes::occupancy`, whose accuracy its own tests check) on texels
/// with hair in their last slice, for fragments in it and behind the texel's
/// range. Two values checked by hand: texel 0 at rel 127.5/128 (slice 31,
/// 7/8 into it; 2 fragments per set bit) is 2 + 2 · 7/8 = 3.75 in front of a
/// point, and a fragment behind the range has the other 3 in front of it.
/// The readers of words (`slab_position`, `word_bits`, `order_in_slab`, as
/// the occupancy technique's passes read them) give the same order inside
/// the range, and `relative_depth` maps a texel's range to [0, 1].
/// Kills, in `shaders/lib/occupancy.wgsl`: `slab_position`'s clamp of the
/// fraction into its slice to 1.0 → 0.9 (a point 0.95 into its slice), `relative_depth`'s (near, far)
/// swapped, the last slice's clamp
/// `slices - 1u` → `slices - 2u` (a point in the last slice reads the slice
/// before it: 2 instead of 3.75) and `total_fragments(maps) - own` → `+`
/// (5 instead of 3).
#[test]
fn order_estimate_matches_its_cpu_mirror_in_the_last_slice_and_behind_the_range() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/occupancy_cases.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (4, 4)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let bytes = prepared.read_buffer("orders").expect("orders");
    let got: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let (texels, depths) = (texels(), depths());
    assert_eq!(got.len(), 4 * texels.len() * depths.len());
    let mut failures = Vec::new();
    for (t, maps) in texels.iter().enumerate() {
        for (k, &rel) in depths.iter().enumerate() {
            let at = 4 * (t * depths.len() + k);
            let inside = rel > 0.0 && rel < 1.0;
            let want = [
                order_estimate(maps, rel),
                fragment_order(maps, rel),
                if inside {
                    order_estimate(maps, rel)
                } else {
                    -1.0
                },
                (rel - 0.25) / 0.5,
            ];
            for (name, g, w) in [
                ("order_estimate", got[at], want[0]),
                ("fragment_order", got[at + 1], want[1]),
                ("word-wise order", got[at + 2], want[2]),
                ("relative_depth in [0.25, 0.75]", got[at + 3], want[3]),
            ] {
                if (g - w).abs() > 1e-4 * w.abs().max(1.0) {
                    failures.push(format!("texel {t}, rel {rel}: {name} GPU {g}, CPU {w}"));
                }
            }
        }
    }
    assert_eq!(order_estimate(&texels[0], 127.5 / 128.0), 3.75);
    assert_eq!(fragment_order(&texels[0], 1.5), 3.0);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
