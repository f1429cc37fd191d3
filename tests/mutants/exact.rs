//! `self_shadow/exact`: the overflow words of `shaders/passes/depth_lists.wgsl`.

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

fn words(bytes: &[u8]) -> Vec<u32> {
    bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// Lists of 4 fragments on the small scene overflow, and the overflow words
/// say by how much, exactly as the texels' counters (every fragment's
/// atomicAdd, stored or not) imply: [0] the fragments past 4 summed over the
/// texels, [1] the texels past 4, [2] the longest list. The gallery's
/// capacity (96) never overflows there, so no other test reads them. Kills,
/// in `shaders/passes/depth_lists.wgsl`, each word's index + 1 (27:33,
/// 29:37, 33:29) and `slot + 1u` → `slot + 2u` (the longest list one too
/// long).
#[test]
fn exact_lists_report_their_overflow_as_their_counters_imply() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("pipelines/exact_shadow.toml");
    let capacity = 4u32;
    let sets = [
        format!("params.exact_capacity={capacity}"),
        "params.light_size=128".to_string(),
    ];
    let prepared = prepare(&gpu, &pipeline, &sets, &scene, (64, 48)).expect("prepares");
    prepared.render_unchecked().expect("renders");
    let counts = words(&prepared.read_buffer("light_counts").expect("counts"));
    let overflow = words(&prepared.read_buffer("light_overflow").expect("overflow"));
    let dropped: u32 = counts.iter().map(|&c| c.saturating_sub(capacity)).sum();
    let texels = counts.iter().filter(|&&c| c > capacity).count() as u32;
    let longest = counts.iter().copied().max().unwrap_or(0);
    eprintln!(
        "capacity {capacity}: overflow words {:?}; from the counters: dropped {dropped}, texels {texels}, longest {longest}",
        &overflow[..3]
    );
    assert!(
        texels > 10,
        "the lists must overflow: {texels} texels past {capacity}"
    );
    assert_eq!(overflow[..3], [dropped, texels, longest]);
}

/// The small scene's image under exact self-shadowing with lists of
/// `capacity` (`self_shadow` = exact; none: no self-shadow), strand coverage off (every fragment a whole texel, share 1)
/// and the strands invisible to the camera (alpha 0; the light lists count
/// them all the same): only the opaque head and ground, shadowed by the hair.
fn shadowed_opaque(gpu: &plait_gpu::Gpu, capacity: u32, self_shadow: &str) -> image::RgbaImage {
    shadowed_opaque_with(
        gpu,
        capacity,
        self_shadow,
        &["params.strand_coverage=false"],
    )
}

/// `shadowed_opaque` with `extra` sets in place of coverage off.
fn shadowed_opaque_with(
    gpu: &plait_gpu::Gpu,
    capacity: u32,
    self_shadow: &str,
    extra: &[&str],
) -> image::RgbaImage {
    let mut scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    scene.strands.alpha.iter_mut().for_each(|a| *a = 0.0);
    let pipeline = repo_root().join("pipelines/exact_shadow.toml");
    let mut sets = vec![
        format!("techniques.self_shadow={self_shadow}"),
        "params.light_size=128".to_string(),
    ];
    sets.extend(extra.iter().map(|s| s.to_string()));
    if self_shadow == "exact" {
        sets.push(format!("params.exact_capacity={capacity}"));
    }
    let prepared = prepare(gpu, &pipeline, &sets, &scene, (96, 72)).expect("prepares");
    prepared.render_unchecked().expect("renders");
    prepared.image().expect("reads back")
}

/// Past its capacity a list stands for its dropped fragments by scaling the
/// stored ones by total / stored. An opaque point has every stored fragment
/// of its light texel in front of it (the lists keep only hair in front of
/// the opaque depth), so with shares of 1 the scaled count is the total,
/// exactly the count of lists long enough: lists of 4 shadow the head and
/// ground as lists of 96 do, within 1/255 (f32 rounding of
/// stored · total / stored). Kills, in
/// `techniques/self_shadow/exact/self_shadow.wgsl`, `out.count *= scale` →
/// `/=`, `total / stored` → `*`, and `min(total, capacity)` → `max` (reads
/// past the texel's list).
#[test]
fn exact_lists_past_their_capacity_still_count_every_fragment_in_front_of_the_opaque() {
    let (_lock, gpu) = open_gpu();
    let short = shadowed_opaque(&gpu, 4, "exact");
    let long = shadowed_opaque(&gpu, 96, "exact");
    let unshadowed = shadowed_opaque(&gpu, 0, "none");
    let diff = |a: &image::RgbaImage, b: &image::RgbaImage| {
        a.pixels()
            .zip(b.pixels())
            .map(|(p, q)| {
                p.0.iter()
                    .zip(q.0)
                    .map(|(&x, y)| x.abs_diff(y))
                    .max()
                    .unwrap_or(0)
            })
            .collect::<Vec<u8>>()
    };
    let worst = diff(&short, &long).into_iter().max().unwrap_or(0);
    let shadowed = diff(&long, &unshadowed).iter().filter(|&&d| d > 8).count();
    eprintln!("lists of 4 vs 96: {worst}/255; {shadowed} pixels shadowed by the hair");
    assert!(
        shadowed > 100,
        "the hair must shadow the opaque: {shadowed} pixels"
    );
    assert!(worst <= 1, "lists of 4 vs 96 on the opaque: {worst}/255");
}

/// Per-pixel largest channel difference of two images (0–255).
fn channel_diff(a: &image::RgbaImage, b: &image::RgbaImage) -> Vec<i16> {
    a.pixels()
        .zip(b.pixels())
        .map(|(p, q)| {
            (0..3)
                .map(|c| i16::from(p.0[c]) - i16::from(q.0[c]))
                .max_by_key(|d| d.abs())
                .unwrap_or(0)
        })
        .collect()
}

/// With fibres opaque to light (`shadow_opaque = 1`: the texel's open part
/// Π (1 − share) in front, strand coverage on so shares lie below 1), a list
/// past its capacity stands for its dropped fragments by raising the stored
/// ones' open part to total / stored. On the opaque head and ground, lists
/// of 4 then shadow as lists of 96 do within 12/255 (measured at e95672a: 5,
/// mean 0.009, over 256 pixels the hair shadows by more than 8), and nothing
/// is lit more than without self-shadowing (within 1/255). Kills, in
/// `techniques/self_shadow/exact/self_shadow.wgsl`, the open part's
/// `pow(open, scale)` → `pow(scale, open)` (57:31: an open part above 1, 20/255
/// brighter than unshadowed, 76 from the long lists) and `open <= 0` → `>`
/// (57:63: every overflowing texel's open part 0, 43 from the long lists),
/// which the test above, whose shares of 1 leave no open part, let through.
#[test]
fn opaque_fibres_past_their_capacity_keep_the_open_part_of_every_fragment() {
    let (_lock, gpu) = open_gpu();
    let opaque = ["params.strand_coverage=true", "params.shadow_opaque=1"];
    let short = shadowed_opaque_with(&gpu, 4, "exact", &opaque);
    let long = shadowed_opaque_with(&gpu, 96, "exact", &opaque);
    let unshadowed = shadowed_opaque_with(&gpu, 0, "none", &opaque[..1]);
    let brighter = channel_diff(&short, &unshadowed)
        .into_iter()
        .max()
        .unwrap_or(0);
    let shadowed = channel_diff(&long, &unshadowed)
        .iter()
        .filter(|&&d| d < -8)
        .count();
    let worst = channel_diff(&short, &long)
        .iter()
        .map(|x| x.abs())
        .max()
        .unwrap_or(0);
    eprintln!(
        "opaque fibres: lists of 4 vs 96 {worst}/255; brighter than unshadowed by {brighter}/255; {shadowed} pixels shadowed by the hair"
    );
    assert!(
        shadowed > 100,
        "the hair must shadow the opaque: {shadowed} pixels"
    );
    assert!(
        brighter <= 1,
        "self-shadowing lit a pixel {brighter}/255 more than none"
    );
    assert!(worst <= 12, "lists of 4 vs 96 on the opaque: {worst}/255");
}
