//! The tangent a hair fragment is shaded about is the smooth curve's through
//! the strand's points (issue 47: the path tracer is handed the natural
//! cubic spline through them, `plait export mitsuba`), not the segment's end
//! tangents interpolated linearly.
//!
//! One strand, a coarse wave facing the camera (`plait_tests::coarse_wave`) (each segment
//! turns by tens of degrees, through inflections), drawn by
//! `tests/fixtures/curve_tangent.toml`, which writes each fragment's
//! `shading_tangent` and its place along the strand. At every covered pixel
//! that tangent is compared with the spline's own at the same place (its
//! Hermite pieces with the spline's derivatives, `plait_hair::curve`).

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_hair::curve::{knot_derivatives, knot_directions};
use plait_tests::{coarse_wave, one_strand_scene, open_gpu, repo_root};

const SIZE: (u32, u32) = (160, 120);
/// Allowed angle between the fragment's tangent and the spline's: the
/// stored tangents lack the spline's lengths (plait_hair::curve::
/// segment_tangent), 2.5° at worst on this wave on the CPU.
const TOLERANCE_DEGREES: f64 = 3.0;

fn scene() -> SceneData {
    let text = r#"
[hair.procedural]
strands = 1
segments = 1
[camera]
eye = [0.0, 0.0, 6.0]
target = [0.0, 0.0, 0.0]
fov_y_degrees = 30.0
[light]
type = "directional"
direction = [-0.3, -0.4, -1.0]
intensity = 1.0
[background]
color = [0.0, 0.0, 0.0]
"#;
    one_strand_scene("curve_tangent.toml", text, &coarse_wave(), 0.005, 0.9)
}

/// The spline's unit tangent at `u` along segment `j` (its Hermite piece).
fn spline_tangent(p: &[Vec3], d: &[Vec3], j: usize, u: f32) -> Vec3 {
    let c = p[j + 1] - p[j];
    (6.0 * u * (1.0 - u) * c + (1.0 - u) * (1.0 - 3.0 * u) * d[j] + u * (3.0 * u - 2.0) * d[j + 1])
        .normalize()
}

fn degrees(a: Vec3, b: Vec3) -> f64 {
    f64::from(a.dot(b).clamp(-1.0, 1.0)).acos().to_degrees()
}

#[test]
fn fragments_shade_about_the_curves_tangent() {
    let (_lock, gpu) = open_gpu();
    let pipeline = repo_root().join("tests/fixtures/curve_tangent.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene(), SIZE).expect("the probe prepares");
    prepared.render_unchecked().expect("renders");
    let read = prepared.read_resource("tangent").expect("tangent");
    let p = coarse_wave();
    let (d, t) = (knot_derivatives(&p), knot_directions(&p));
    let (mut angles, mut lerp, mut segments) = (vec![], vec![], [0usize; 8]);
    for texel in read.bytes.chunks_exact(16) {
        let v: [f32; 4] = std::array::from_fn(|c| {
            f32::from_le_bytes(texel[4 * c..4 * c + 4].try_into().unwrap())
        });
        let shaded = Vec3::new(v[0], v[1], v[2]);
        if shaded == Vec3::ZERO {
            continue; // no fragment here
        }
        let j = v[3].floor() as usize;
        let u = v[3] - j as f32;
        assert!(j < 8, "segment {j}");
        segments[j] += 1;
        let exact = spline_tangent(&p, &d, j, u);
        angles.push(degrees(shaded.normalize(), exact));
        lerp.push(degrees(t[j].lerp(t[j + 1], u).normalize(), exact));
    }
    let worst = angles.iter().cloned().fold(0.0, f64::max);
    let worst_lerp = lerp.iter().cloned().fold(0.0, f64::max);
    let mean = angles.iter().sum::<f64>() / angles.len() as f64;
    let mean_lerp = lerp.iter().sum::<f64>() / lerp.len() as f64;
    println!(
        "{} fragments (per segment {segments:?}): shading tangent to the spline's: mean {mean:.3}°, \
         max {worst:.3}°; the end tangents interpolated linearly would be mean {mean_lerp:.3}°, max {worst_lerp:.3}°",
        angles.len()
    );
    assert!(
        segments.iter().all(|&n| n >= 10),
        "every segment drawn: {segments:?}"
    );
    assert!(
        worst < TOLERANCE_DEGREES,
        "max {worst:.3}° from the spline's tangent"
    );
    // The case must be one the linear interpolation fails.
    assert!(
        worst_lerp > 3.0 * TOLERANCE_DEGREES,
        "linear is only {worst_lerp:.3}° off"
    );
}
