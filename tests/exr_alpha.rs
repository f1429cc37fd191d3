//! The linear image's alpha (issue 47, `plait render --out x.exr`): the part
//! of each pixel covered by anything in front of the background
//! (docs/formats.md, "The display transform and linear images"). One
//! straight strand thinner than a pixel over a black background, no head, no
//! ground, seen from above: the background reads alpha 0 exactly, and the
//! strand's pixels its coverage, width ÷ pixel (one pixel per column of a
//! horizontal line), in the EXR as `plait render --out x.exr` writes it
//! (`plait::linear::encode_exr`), read back with the `image` crate.

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (160, 120);
const EYE: f32 = 2.0;
const FOV_Y_DEGREES: f32 = 13.0;
const LENGTH: f32 = 0.4;

fn scene(thickness: f32) -> SceneData {
    let text = format!(
        r#"
ambient = 0.5
[hair.procedural]
strands = 1
segments = 1
[camera]
eye = [0.0, {EYE}, 0.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
fov_y_degrees = {FOV_Y_DEGREES}
[light]
type = "directional"
direction = [0.0, -1.0, -0.5]
intensity = 1.0
[background]
color = [0.0, 0.0, 0.0]
"#
    );
    let path = repo_root().join("tests/exr_alpha.toml");
    let scene = plait_hair::Scene::from_toml_str(&text, &path).expect("the scene parses");
    let mut data = SceneData::new(scene).expect("the scene loads");
    data.meshes.clear();
    data.strands = plait_hair::Strands::new();
    let points: Vec<glam::Vec3> = (0..=8)
        .map(|k| glam::Vec3::new(LENGTH * (k as f32 / 8.0 - 0.5), 0.0, 0.0))
        .collect();
    data.strands
        .push_strand(&points, |_| thickness, |_| 1.0, glam::Vec3::splat(0.9));
    data
}

/// The EXR of `pipeline`'s render, decoded.
fn exr_of(gpu: &Gpu, pipeline: &str, scene: &SceneData) -> image::Rgba32FImage {
    let path = repo_root().join(format!("pipelines/{pipeline}.toml"));
    let prepared = prepare(gpu, &path, &[], scene, SIZE).unwrap_or_else(|e| panic!("{e}"));
    prepared.render().expect("renders");
    let radiance = prepared.radiance().expect("reads back");
    let bytes = plait::linear::encode_exr(&radiance).expect("encodes");
    let decoded = image::load_from_memory_with_format(&bytes, image::ImageFormat::OpenExr)
        .expect("decodes")
        .to_rgba32f();
    assert_eq!(decoded, radiance, "the EXR holds the radiance as rendered");
    decoded
}

/// Background pixels alpha 0; the strand's pixels its coverage (median
/// within 3 %), and Σ alpha the strand's area in pixels within 5 %; for a
/// transparency technique that composes with (1 − ᾱ)^n (occupancy order)
/// and one that composes premultiplied layers (depth peeling).
#[test]
fn exr_alpha_is_the_coverage_of_the_pixel() {
    let (_lock, gpu) = open_gpu();
    let pixel =
        2.0 * EYE as f64 * ((FOV_Y_DEGREES as f64).to_radians() / 2.0).tan() / SIZE.1 as f64;
    let mut failures = Vec::new();
    for pipeline in ["occupancy", "depth_peeling"] {
        for thickness in [0.001f32, 0.002] {
            let image = exr_of(&gpu, pipeline, &scene(thickness));
            let coverage = thickness as f64 / pixel;
            let area = thickness as f64 * LENGTH as f64 / (pixel * pixel);
            let alphas: Vec<f64> = image.pixels().map(|p| p.0[3] as f64).collect();
            let background = image
                .pixels()
                .filter(|p| p.0[..3] == [0.0, 0.0, 0.0])
                .collect::<Vec<_>>();
            let background_alpha = background.iter().map(|p| p.0[3]).fold(0.0f32, f32::max);
            let mut hair: Vec<f64> = alphas.iter().copied().filter(|&a| a > 0.0).collect();
            hair.sort_by(f64::total_cmp);
            let median = hair.get(hair.len() / 2).copied().unwrap_or(0.0);
            let sum: f64 = alphas.iter().sum();
            eprintln!(
                "{pipeline} thickness {thickness}: {} background pixels, max alpha {background_alpha}; \
                 {} hair pixels, median alpha {median:.4} (coverage {coverage:.4}), Σ alpha {sum:.2} (area {area:.2} px)",
                background.len(),
                hair.len()
            );
            if background.len() < alphas.len() / 2 || background_alpha != 0.0 {
                failures.push(format!(
                    "{pipeline} {thickness}: background alpha {background_alpha}"
                ));
            }
            if (median / coverage - 1.0).abs() > 0.03 || (sum / area - 1.0).abs() > 0.05 {
                failures.push(format!(
                    "{pipeline} {thickness}: median {median:.4} of {coverage:.4}, Σ {sum:.2} of {area:.2}"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
