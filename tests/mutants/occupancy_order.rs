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

/// `order_slices` is any multiple of 32 and `order_slabs` any count of
/// counters (technique.toml): at 32 slices (one word per pixel) and at one
/// slab, the order estimate still blends the small scene (paper strands,
/// alpha 0.8) near the exact order of per-pixel lists: its RMSE against them
/// within 2× the defaults' (128 slices, 4 slabs; the three printed). Kills,
/// in `techniques/transparency/occupancy_order/hair.wgsl`'s `camera_order`,
/// the no-maps test `words == 0u` → `1u` (67:40: every fragment's order 0
/// at one word), `max(words, 1u)` → `2u` and `max(slabs, 1u)` → `2u` (50:98:
/// a slice or a counter read past the pixel's own), which the defaults
/// never reach.
#[test]
fn one_word_of_camera_slices_or_one_slab_still_orders_the_fragments() {
    let (_lock, gpu) = open_gpu();
    let scene = one_alpha(0.8);
    let off = "params.strand_coverage=false";
    let exact = render(&gpu, &scene, &[off, "techniques.transparency=linked_list"]);
    let rmse = |slices: u32, slabs: u32| {
        let slices = format!("params.order_slices={slices}");
        let slabs = format!("params.order_slabs={slabs}");
        let sets = [off, slices.as_str(), slabs.as_str()];
        plait_compare::rmse(&exact, &render(&gpu, &scene, &sets)).expect("same size")
    };
    let default = rmse(128, 4);
    let mut failures = Vec::new();
    for (slices, slabs) in [(32, 4), (128, 1)] {
        let e = rmse(slices, slabs);
        eprintln!(
            "RMSE against linked lists: {slices} slices, {slabs} slabs {e:.6} (128, 4: {default:.6})"
        );
        if e > 2.0 * default {
            failures.push(format!(
                "{slices} slices, {slabs} slabs: RMSE {e}, defaults {default}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
