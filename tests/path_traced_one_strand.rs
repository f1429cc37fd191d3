//! plait's path tracer (`pipelines/physical/path_traced.toml`, issue 48)
//! against Mitsuba 3 on one straight strand at max depth 2 (single
//! scattering), in CI.
//!
//! The scene (scripts/mitsuba/thick_strand.toml) is one straight fibre of
//! radius 0.1 across the whole 160×120 image, perpendicular to the camera,
//! under the measurement scene's directional light, nothing else: the
//! export's B-spline through its colinear points is the same line as
//! plait's capsules, so the geometry cannot differ and what is compared is
//! the fibre's scattering (Chiang et al. 2016: the lobes, their Fresnel and
//! tilts, the absorption from the colour) and the light's units. Each image
//! row is one offset h across the fibre, so a row's mean is the fibre's
//! response at that h.
//!
//! Per hair colour (blond, dark brown, black — tests/path_traced_gpu.rs'):
//! - the mean Rec. 709 luminance over the fully covered pixels (every
//!   camera ray of a separate plait render, its own seed, meets the strand)
//!   is within MEAN_BOUND of Mitsuba's;
//! - every fully covered row's mean is within ROW_BOUND of Mitsuba's.
//!
//! Measured (lavapipe, Mesa 25.0.7): blond 0.9950, dark brown 0.9947,
//! black 0.9939 of Mitsuba's mean, the worst row 0.9 % off (1.05 % over
//! four seed pairs); ~7 s a colour
//! with Mitsuba's two renders, ~1.7 s a colour once they are cached. It
//! fails for the wrong answer: a 5 % darker fibre NEE in path_trace.wgsl
//! read 0.944 (black; every row 4–6 % low); the TRT lobe dropped from its
//! fibre_term read black 0.984 and blond 0.954, the rows of one half of
//! the fibre (h from ≈ 0 to 1) 0.14–0.93 of Mitsuba's.
//!
//! Mitsuba's images (tests/fixtures/pt_one_strand.toml: 2 seeds × 256 spp)
//! are cached by content key in the build folder as `plait ab` caches them
//! (`plait::ab::default_cache`); the first run renders them (Mitsuba
//! installed by scripts/ensure-mitsuba.sh, as scripts/test.sh does).

use plait::ab::{AbOptions, HairColor};
use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, path_traced_plan, repo_root};

const SIZE: (u32, u32) = (160, 120);
/// plait's samples per pixel per seed (two seeds).
const SPP: u32 = 64;
/// The mean's bound (issue 48): 3 % of Mitsuba's.
const MEAN_BOUND: f64 = 0.03;
/// A row's bound. Measured (lavapipe, Mesa 25.0.7; seed pairs 0/1, 2/3,
/// 4/5, 10/11, three colours): the rows read within 1.05 % of Mitsuba's,
/// and plait's own row noise (half the relative difference of its two
/// seeds' row means) is at most 1.0 %, in the dim rows near h = ±1. 3 %
/// is about three times both; the smallest change of a lobe seen (TRT
/// dropped) moves rows by 7 % and more.
const ROW_BOUND: f64 = 0.03;
/// The render that picks the fully covered pixels: camera rays only, a seed
/// neither compared render uses.
const MASK_SPP: u32 = 32;
const MASK_SEED: u32 = 7;

fn luminance(p: &[f32; 4]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Mitsuba's image of the strand in `colour` (`NAME=R,G,B`) and the
/// recoloured scene plait renders.
fn mitsuba(colour: &str) -> (SceneData, image::Rgba32FImage) {
    let root = repo_root();
    let mut options = AbOptions::new(
        vec![root.join("pipelines/physical/path_traced.toml")],
        root.join("tests/fixtures/pt_one_strand.toml"),
    );
    options.scenes = vec![root.join("scripts/mitsuba/thick_strand.toml")];
    options.hair_colors = vec![HairColor::parse(colour).expect("a colour")];
    options.size = SIZE;
    let mut plan = path_traced_plan(options);
    let scene = plan.scenes.remove(0).data;
    (scene, plan.path_traced_images.remove(0).linear)
}

/// plait's luminance image and each pixel's hair coverage (the part of its
/// camera rays whose first hit is the strand).
fn plait_render(
    gpu: &plait_gpu::Gpu,
    scene: &SceneData,
    depth: u32,
    spp: u32,
    seed: u32,
) -> (Vec<f64>, Vec<f32>) {
    let sets = vec![
        format!("params.max_depth={depth}"),
        format!("params.spp={spp}"),
        format!("params.seed={seed}"),
    ];
    let pipeline = repo_root().join("pipelines/physical/path_traced.toml");
    let prepared = prepare(gpu, &pipeline, &sets, scene, SIZE).expect("prepares");
    prepared.render().expect("renders, no invocation cut short");
    let image = prepared.radiance().expect("reads the radiance");
    let lum = image.pixels().map(|p| luminance(&p.0)).collect();
    let sums: Vec<f32> =
        bytemuck::cast_slice(&prepared.read_buffer("pt_sum").expect("pt_sum")).to_vec();
    let hair = sums.chunks(8).map(|s| s[5] / s[4].max(1.0)).collect();
    (lum, hair)
}

/// The image rows every pixel of which the strand covers whole.
fn full_rows(hair: &[f32]) -> Vec<usize> {
    let w = SIZE.0 as usize;
    (0..SIZE.1 as usize)
        .filter(|&r| hair[r * w..(r + 1) * w].iter().all(|&c| c >= 1.0))
        .collect()
}

fn row_mean(image: &[f64], r: usize) -> f64 {
    let w = SIZE.0 as usize;
    image[r * w..(r + 1) * w].iter().sum::<f64>() / w as f64
}

/// Renders `colour` in both, prints what it measured, and fails naming
/// every bound it broke.
fn check(colour: &str) {
    let start = std::time::Instant::now();
    let (scene, reference) = mitsuba(colour);
    let reference: Vec<f64> = reference.pixels().map(|p| luminance(&p.0)).collect();
    let (_lock, gpu) = open_gpu();
    let (_, mask) = plait_render(&gpu, &scene, 1, MASK_SPP, MASK_SEED);
    let rows = full_rows(&mask);
    // ~34 rows at radius 0.1: fewer means the strand or the camera moved.
    assert!(rows.len() >= 30, "{} fully covered rows", rows.len());
    let (a, _) = plait_render(&gpu, &scene, 2, SPP, 0);
    let (b, _) = plait_render(&gpu, &scene, 2, SPP, 1);
    let mean: Vec<f64> = a.iter().zip(&b).map(|(x, y)| 0.5 * (x + y)).collect();
    let over = |img: &[f64]| rows.iter().map(|&r| row_mean(img, r)).sum::<f64>();
    let ratio = over(&mean) / over(&reference);
    let mut failures = Vec::new();
    if (ratio - 1.0).abs() > MEAN_BOUND {
        failures.push(format!(
            "mean {ratio:.4} of Mitsuba's, outside 1 ± {MEAN_BOUND}"
        ));
    }
    let mut worst = (0.0f64, 0usize);
    let mut noisiest = 0.0f64;
    for &r in &rows {
        let row = row_mean(&mean, r) / row_mean(&reference, r);
        let noise = 0.5 * (row_mean(&a, r) - row_mean(&b, r)).abs() / row_mean(&mean, r);
        noisiest = noisiest.max(noise);
        if (row - 1.0).abs() > worst.0 {
            worst = ((row - 1.0).abs(), r);
        }
        if (row - 1.0).abs() > ROW_BOUND {
            failures.push(format!(
                "row {r}: {row:.4} of Mitsuba's, outside 1 ± {ROW_BOUND}"
            ));
        }
    }
    println!(
        "{colour}: {} fully covered rows; mean luminance plait ÷ Mitsuba {ratio:.4}; \
         worst row {} at {:.4} off; plait's largest row noise {noisiest:.4}; {:.1} s",
        rows.len(),
        worst.1,
        worst.0,
        start.elapsed().as_secs_f64()
    );
    assert!(failures.is_empty(), "{colour}:\n{}", failures.join("\n"));
}

#[test]
fn one_blond_strand_matches_mitsuba_at_max_depth_2() {
    check("blond=0.85,0.65,0.40");
}

#[test]
fn one_dark_brown_strand_matches_mitsuba_at_max_depth_2() {
    check("dark_brown=0.32,0.20,0.11");
}

#[test]
fn one_black_strand_matches_mitsuba_at_max_depth_2() {
    check("black=0.02,0.02,0.02");
}
