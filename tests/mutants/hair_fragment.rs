//! `shared/hair_fragment`: the fragment alpha of `shaders/lib/hair_fragment.wgsl`.

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{open_gpu, repo_root};

/// The default pipeline's image of `scene` with sorted lists blended over
/// (`linked_list`: occupancy order's weights are normalised, so a common
/// factor on every alpha nearly cancels there) and strand coverage off, so
/// a fragment's alpha is its strand's alpha × the material's, clamped to 1.
fn render(gpu: &Gpu, scene: &SceneData) -> image::RgbaImage {
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let sets = [
        "params.strand_coverage=false".to_string(),
        "techniques.transparency=linked_list".to_string(),
    ];
    let prepared = prepare(gpu, &pipeline, &sets, scene, (96, 72)).expect("prepares");
    prepared.render_unchecked().expect("renders");
    prepared.image().expect("reads back")
}

/// The largest difference of a channel between two images, out of 255, and
/// how many pixels differ at all.
fn differ(a: &image::RgbaImage, b: &image::RgbaImage) -> (u8, usize) {
    let worst = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| p.0.iter().zip(q.0).map(|(&x, y)| x.abs_diff(y)))
        .max()
        .expect("pixels");
    let changed = a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
    (worst, changed)
}

fn small_scene() -> SceneData {
    SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads")
}

/// A fragment's alpha is clamp(strand alpha × material alpha, 0, 1): the
/// material's alpha 0.5 renders as the strands' own alpha halved, within
/// 1/255; and strands of alpha 1.6 render as strands of alpha 1 (every
/// fragment opaque), exactly. The gallery's scenes leave the material's
/// alpha at 1 and their strands' at most 1, where neither shows. Kills, in
/// `shaders/lib/hair_fragment.wgsl`'s `fragment_alpha`,
/// `* frame.hair_color.a` → `/` (alpha 1.6 instead of 0.4 on the material)
/// and the clamp's upper bound 1.0 → 1.1 (fragments of alpha 1.1 subtract
/// the hair behind them).
#[test]
fn the_fragment_alpha_is_the_strand_alpha_times_the_material_alpha_at_most_one() {
    let (_lock, gpu) = open_gpu();
    let mut on_material = small_scene();
    on_material.scene.material.alpha = 0.5;
    let mut on_strands = small_scene();
    for a in &mut on_strands.strands.alpha {
        *a *= 0.5;
    }
    let (halved, _) = differ(&render(&gpu, &on_material), &render(&gpu, &on_strands));
    let (_, changed) = differ(&render(&gpu, &on_strands), &render(&gpu, &small_scene()));
    let with_alpha = |alpha: f32| {
        let mut scene = small_scene();
        scene.strands.alpha.iter_mut().for_each(|a| *a = alpha);
        render(&gpu, &scene)
    };
    let (past_one, _) = differ(&with_alpha(1.6), &with_alpha(1.0));
    let (_, opaque_changed) = differ(&with_alpha(1.0), &render(&gpu, &small_scene()));
    eprintln!(
        "alpha ½ on the material vs on the strands: {halved}/255 ({changed} pixels change); \
         strands of alpha 1.6 vs 1: {past_one}/255 ({opaque_changed} pixels change from 0.8 to 1)"
    );
    assert!(
        changed > 100 && opaque_changed > 100,
        "the alphas must change the hair"
    );
    assert!(
        halved <= 1,
        "material alpha ½ vs strands' alpha halved: {halved}/255"
    );
    assert_eq!(past_one, 0, "strands of alpha 1.6 vs 1: {past_one}/255");
}
