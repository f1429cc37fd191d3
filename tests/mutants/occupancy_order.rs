//! `transparency/occupancy_order`: the camera order estimate at one word of
//! slices, and the frame's mean alpha where it binds its clamp.

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (160, 120);

fn render(gpu: &Gpu, scene: &SceneData, sets: &[&str]) -> image::RgbaImage {
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let prepared =
        prepare(gpu, &pipeline, &sets, scene, SIZE).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
    prepared.render().expect("renders");
    prepared.image().expect("reads back")
}

/// The small scene with every strand of one alpha and no strand coverage:
/// §3.4's one alpha for every fragment.
fn one_alpha(alpha: f32) -> SceneData {
    let mut scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    scene.strands.alpha.fill(alpha);
    scene
}

/// With opaque strands (every fragment's alpha 1, coverage off) the frame's
/// mean alpha and the pixel's are both 1, clamped to 0.999 (so (1-ᾱ)^o
/// stays finite and above 0 for the Λ correction): `mean_alpha = "frame"`
/// renders the image `"pixel"` does, within RMSE 1e-4 (measured: printed).
/// `tests/coverage.rs` checks the same at alpha 0.8, where the clamp does
/// not bind. Kills, in `techniques/transparency/occupancy_order/hair.wgsl`,
/// the frame branch's clamp 0.999 → 0.8991 (31:43): the fragments behind the
/// first then weigh 0.1 each instead of 0.001.
#[test]
fn with_opaque_strands_frame_and_pixel_mean_alpha_agree() {
    let (_lock, gpu) = open_gpu();
    let scene = one_alpha(1.0);
    let off = "params.strand_coverage=false";
    let pixel = render(&gpu, &scene, &[off, "params.mean_alpha=pixel"]);
    let frame = render(&gpu, &scene, &[off, "params.mean_alpha=frame"]);
    let rmse = plait_compare::rmse(&pixel, &frame).expect("same size");
    eprintln!("opaque strands: per-pixel vs frame ᾱ image RMSE {rmse:.6}");
    assert!(rmse < 1e-4, "RMSE {rmse}");
}

/// `order_slices` is any multiple of 32 (technique.toml): at 32, one word per
/// pixel, the order estimate still blends the small scene (paper strands,
/// alpha 0.8) near the exact order of per-pixel lists: its RMSE against
/// them within 2× the default 128 slices' (measured 0.000622 and 0.000395,
/// printed). Kills, in
/// `techniques/transparency/occupancy_order/hair.wgsl`'s `camera_order`, the
/// no-maps test `words == 0u` → `1u` (67:40: every fragment's order 0 at one
/// word) and `max(words, 1u)` → `2u` (50:98: slices read past the pixel's
/// one word), which the default 128 slices (4 words) never reach.
#[test]
fn one_word_of_camera_slices_still_orders_the_fragments() {
    let (_lock, gpu) = open_gpu();
    let scene = one_alpha(0.8);
    let off = "params.strand_coverage=false";
    let exact = render(&gpu, &scene, &[off, "techniques.transparency=linked_list"]);
    let rmse = |slices: &str| {
        let sets = [off, slices];
        plait_compare::rmse(&exact, &render(&gpu, &scene, &sets)).expect("same size")
    };
    let (at_128, at_32) = (
        rmse("params.order_slices=128"),
        rmse("params.order_slices=32"),
    );
    eprintln!("RMSE against linked lists: 128 slices {at_128:.6}, 32 slices {at_32:.6}");
    assert!(
        at_32 <= 2.0 * at_128,
        "32 slices: RMSE {at_32} against the lists, 128 slices: {at_128}"
    );
}
