//! Strand coverage (issue 11, item 5): a strand thinner than a pixel weighs
//! its alpha by the part of the pixel it covers, in every blending technique.
//! Checked against the truth of anti-aliasing — the same pipeline rendered
//! 4 × 4 times larger and box-filtered down (`plait ab --supersample 4`) —
//! coverage must be closer to it than the one-pixel lines without coverage.

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (96, 72);
const SUPERSAMPLE: u32 = 4;

fn render(gpu: &Gpu, scene: &SceneData, sets: &[&str], size: (u32, u32)) -> image::RgbaImage {
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let prepared =
        prepare(gpu, &pipeline, &sets, scene, size).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
    prepared.renderer.render().expect("renders");
    prepared.image().expect("reads back")
}

/// RMSE against the 4× supersampled reference with coverage, and without.
fn errors(gpu: &Gpu, scene: &SceneData, transparency: &str) -> (f64, f64) {
    let technique = format!("techniques.transparency={transparency}");
    let big = (SIZE.0 * SUPERSAMPLE, SIZE.1 * SUPERSAMPLE);
    let reference = plait::ab::box_filter(&render(gpu, scene, &[&technique], big), SUPERSAMPLE);
    let with = render(gpu, scene, &[&technique], SIZE);
    let without = render(
        gpu,
        scene,
        &[&technique, "params.strand_coverage=false"],
        SIZE,
    );
    let rmse = |image| plait_compare::rmse(&reference, image).expect("same size");
    (rmse(&with), rmse(&without))
}

#[test]
fn coverage_is_closer_to_a_supersampled_render_in_every_blending_technique() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let mut failures = Vec::new();
    for transparency in [
        "occupancy_order",
        "weighted_average",
        "linked_list",
        "alpha_to_coverage",
    ] {
        let (with, without) = errors(&gpu, &scene, transparency);
        eprintln!(
            "{transparency}: RMSE against 4× supersampled: coverage {with:.4}, none {without:.4}"
        );
        if with >= without {
            failures.push(format!(
                "{transparency}: coverage {with:.4} is not closer than no coverage {without:.4}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The CPU mirror of the shader's coverage gives the mean fragment alpha of
/// order-based blending: smaller than the strands' alpha when they are
/// thinner than a pixel, equal with coverage off.
#[test]
fn mean_fragment_alpha_follows_coverage() {
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let on = scene.frame(SIZE, 0);
    let off = scene.frame(SIZE, 0).with_strand_coverage(false);
    assert_eq!(on.conventions[2], 1.0);
    assert_eq!(off.conventions[2], 0.0);
    assert!(
        on.hair_stats[0] < 0.5 * off.hair_stats[0],
        "0.01-thick strands at 96×72 cover far less than a pixel: ᾱ {} with coverage, {} without",
        on.hair_stats[0],
        off.hair_stats[0]
    );
    assert_eq!(off.with_strand_coverage(true).hair_stats, on.hair_stats);
}
