//! The quad draw of a wide segment near the eye (`shaders/lib/strand_coverage.wgsl`,
//! `quad_place`). A quad corner's across direction is perpendicular to the
//! screen direction from the hair vertex to a point "ahead" along the
//! strand. Where that point lies behind the eye (its projection flips), the
//! shader takes the point of the same line halfway to the eye plane instead.
//! No gallery strand runs that close to the eye, so no other test reaches
//! that branch.
//!
//! A straight strand heading towards the eye, its near end 0.3 in front of
//! it: at that end the point one segment ahead lies behind the eye. The same
//! strand drawn the other way round (near end first) never takes the branch:
//! its points ahead run away from the eye. The two quads have the same
//! corners, so the two images must match. Only the shading could differ with
//! the tangent's sign, and it doesn't: the light is off and there is no
//! specular, so the uniform ambient is the only light.

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{one_strand_scene, open_gpu, repo_root};

const SIZE: (u32, u32) = (96, 72);

/// A camera at (0, 0, 5) facing −z with its near plane at 0.01, so that a
/// strand 0.3 from the eye is still drawn. A uniform ambient, no light and
/// no specular, a black background.
const NEAR_EYE: &str = r#"
ambient = 0.5
[hair.procedural]
strands = 1
segments = 1
[camera]
eye = [0.0, 0.0, 5.0]
target = [0.0, 0.0, 0.0]
fov_y_degrees = 30.0
near = 0.01
[light]
type = "directional"
direction = [-0.3, -0.4, -1.0]
intensity = 0.0
[background]
color = [0.0, 0.0, 0.0]
[material]
specular = 0.0
"#;

/// The red channel of the linear radiance, occupancy_order, no self-shadow.
fn render(gpu: &Gpu, scene: &SceneData) -> Vec<f32> {
    let sets = [
        "techniques.transparency=occupancy_order".to_owned(),
        "techniques.self_shadow=none".to_owned(),
    ];
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let prepared = prepare(gpu, &pipeline, &sets, scene, SIZE).expect("prepares");
    prepared.render_unchecked().expect("renders");
    let image = prepared.radiance().expect("reads back");
    image.pixels().map(|p| p.0[0]).collect()
}

/// One segment from depth 2 (w = 2) to depth 0.3 (w = 0.3), 0.005 thick:
/// 0.34 px wide at its far end, 2.2 px at its near end, so it is drawn as a
/// quad. At the near end the point one segment ahead is at w = −1.4. With
/// `0.5 * clip.w` → `0.5 / clip.w` (132:21), the "halfway" point lies at
/// w = 0.3 − 0.5/0.3 < 0 (it only stays in front where clip.w > √0.5). So
/// its projection flips, the across direction turns over, and the quad's
/// near corners swap: a bowtie. With `ahead_world − world` → `+` (133:73)
/// the point is off the strand's line, so the direction is wrong.
///
/// Kills, in `shaders/lib/strand_coverage.wgsl`, 132:21 and 133:73.
#[test]
fn a_wide_strand_towards_the_eye_is_the_same_quad_drawn_either_way() {
    let (_lock, gpu) = open_gpu();
    let far = Vec3::new(-0.5, -0.2, 3.0);
    let near = Vec3::new(0.06, 0.02, 4.7);
    let scene = |points: &[Vec3]| {
        one_strand_scene("strand_towards_the_eye.toml", NEAR_EYE, points, 0.005, 0.9)
    };
    let towards = render(&gpu, &scene(&[far, near]));
    let away = render(&gpu, &scene(&[near, far]));
    let lit = away.iter().filter(|&&v| v > 0.0).count();
    let sum = |image: &[f32]| image.iter().map(|&v| f64::from(v)).sum::<f64>();
    let worst = towards
        .iter()
        .zip(&away)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    let peak = away.iter().copied().fold(0.0f32, f32::max);
    eprintln!(
        "{lit} pixels lit; Σ towards {:.4}, away {:.4}; worst pixel {worst:.2e} of a peak {peak:.4}",
        sum(&towards),
        sum(&away)
    );
    assert!(lit > 40, "the strand must be drawn: {lit} pixels lit");
    assert!(
        worst <= 0.02 * peak,
        "the strand drawn towards the eye differs from it drawn away by {worst} (peak {peak})"
    );
}
