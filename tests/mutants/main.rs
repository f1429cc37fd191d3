//! Tests written to kill mutants that survived the techniques' own tests
//! (`bash scripts/mutate.sh`, `tests/mutation.toml`; book: Reliability,
//! "Mutation score"). Each names the mutants it kills. One module per
//! technique where it has more than one such test.

mod chiang;
mod compute_raster;
mod cylinders;
mod density_clustering;
mod density_occlusion;
mod depth_only;
mod dual_scattering;
mod exact;
mod hair_fragment;
mod kajiya_kay;
mod lighting;
mod linked_list;
mod marschner;
mod occupancy;
mod occupancy_order;
mod path_traced;
mod ray_traced;
mod ray_traced_dots;
mod strand_coverage;
mod tone_mapping;

use plait::session::{SceneData, prepare};

/// A one-strand test scene's settings (`plait_tests::one_strand_scene`): a
/// camera at (0, 0, 6) facing the plane z = 0, a white directional light from
/// nearly along that plane (so that the diffuse term sin(T, L) follows the
/// tangent steeply), no ambient, a black background.
const SIDE_LIT: &str = r#"
ambient = 0.0
[hair.procedural]
strands = 1
segments = 1
[camera]
eye = [0.0, 0.0, 6.0]
target = [0.0, 0.0, 0.0]
fov_y_degrees = 30.0
[light]
type = "directional"
direction = [-1.0, -0.15, -0.2]
intensity = 2.0
[background]
color = [0.0, 0.0, 0.0]
"#;
use plait_tests::{open_gpu, repo_root};

/// The cases of `tests/fixtures/wa_cases.wgsl` and `wa_count.wgsl`, one per
/// band of 16 columns: (n, Σα), every fragment of colour `COLOUR`.
const WA_CASES: [(f64, f64); 7] = [
    (0.0, 0.0),
    (1.0, 0.0),
    (1.0, 0.5),
    (3.0, 3.0),
    (4.0, 2.0),
    (2.0, 1.9),
    (1.0, 1.0),
];
const COLOUR: [f64; 3] = [0.8, 0.4, 0.2];

/// The resolve of Bavoil & Myers 2008 as Sintorn & Assarsson 2009 §2.2
/// describe it, on the CPU: n fragments of the mean colour C and mean alpha
/// ᾱ = Σα / n blended, premultiplied (C · (1 - (1-ᾱ)ⁿ), 1 - (1-ᾱ)ⁿ); nothing
/// where no fragment or no alpha was summed.
fn wa_resolve(n: f64, alpha_sum: f64) -> [f64; 4] {
    if n == 0.0 || alpha_sum == 0.0 {
        return [0.0; 4];
    }
    let coverage = 1.0 - (1.0 - (alpha_sum / n).clamp(0.0, 1.0)).powf(n);
    [
        COLOUR[0] * coverage,
        COLOUR[1] * coverage,
        COLOUR[2] * coverage,
        coverage,
    ]
}

/// `weighted_average_resolve` on known sums equals the closed form, within
/// 1/255 (rgba16float sums): red, green and alpha, which `wa_show.wgsl`
/// writes as the opaque image's red, green and blue. Kills, in `shaders/passes/weighted_average_resolve.wgsl`:
/// `n < 0.5 || s.a <= 1e-6` → `&&` (a pixel of zero-alpha fragments, such as
/// faded tips, divides 0 by 0: a NaN shown magenta here, black over the scene);
/// the clamp of ᾱ to 1.0 → 0.9 (opaque fragments let the background through).
#[test]
fn weighted_average_resolve_matches_its_closed_form_on_known_sums() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/wa_resolve.toml");
    let size = (16 * WA_CASES.len() as u32, 4);
    let prepared = prepare(&gpu, &pipeline, &[], &scene, size).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let image = prepared.image().expect("reads back");
    let mut failures = Vec::new();
    for (k, &(n, alpha_sum)) in WA_CASES.iter().enumerate() {
        let [r, g, _, a] = wa_resolve(n, alpha_sum).map(|c| (c * 255.0).round());
        let want = [r, g, a];
        let p = image.get_pixel(16 * k as u32 + 8, 2).0;
        let got = [p[0], p[1], p[2]];
        let off = got
            .iter()
            .zip(want)
            .any(|(&g, w)| (g as f64 - w).abs() > 1.0);
        eprintln!("n {n}, Σα {alpha_sum}: {got:?}, closed form {want:?}");
        if off {
            failures.push(format!(
                "n {n}, Σα {alpha_sum}: got {got:?}, closed form {want:?}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Kajiya-Kay as `shaders/lib/kajiya_kay.wgsl` states it (Halén & Wester
/// 2007 §3.2.1), on the CPU in f64: (kd sin(T,L), ks max(0, cos(T,L) cos(θ)
/// + sin(T,L) sin(θ))^p) with θ the angle between T and E plus the shift.
fn kajiya_kay(t: [f64; 3], l: [f64; 3], e: [f64; 3], exponent: f64, shift: f64) -> [f64; 2] {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cos_tl = dot(t, l).clamp(-1.0, 1.0);
    let sin_tl = (1.0 - cos_tl * cos_tl).max(0.0).sqrt();
    let angle_te = dot(t, e).clamp(-1.0, 1.0).acos() + shift;
    let spec_base = (cos_tl * angle_te.cos() + sin_tl * angle_te.sin()).max(0.0);
    [sin_tl, spec_base.powf(exponent)]
}

/// `plait::kajiya_kay` for a tangent turning through the light and the eye
/// (`tests/fixtures/kk_cases.wgsl`) equals the closed form within 2/255,
/// including where the tangent points almost at the eye, which the gallery's
/// strands rarely do. Kills, in `shaders/lib/kajiya_kay.wgsl`, the clamp of
/// cos(T,E) to 1.0 → 0.9 (the highlight of near-aligned strands moves).
#[test]
fn kajiya_kay_matches_its_closed_form_where_the_tangent_meets_the_eye() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/kk.toml");
    let width = 64;
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (width, 2)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let image = prepared.image().expect("reads back");
    let mut failures = Vec::new();
    for x in 0..width {
        let angle = std::f64::consts::PI * (x as f64 + 0.5) / width as f64;
        let t = [angle.cos(), angle.sin(), 0.0];
        let want =
            kajiya_kay(t, [0.6, 0.8, 0.0], [1.0, 0.0, 0.0], 8.0, 0.1).map(|c| (c * 255.0).round());
        let p = image.get_pixel(x, 1).0;
        if (p[0] as f64 - want[0]).abs() > 2.0 || (p[1] as f64 - want[1]).abs() > 2.0 {
            failures.push(format!(
                "column {x} (T at {angle:.3} rad): (diffuse, specular) {:?}, closed form {want:?}",
                [p[0], p[1]]
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The scene's hair colour (`[hair] color`, the frame's `hair_color`) tints
/// every strand's own colour: the default pipeline renders a tint of
/// (0.5, 0.7, 0.9) on the material as it renders the same tint baked into
/// every strand's colour, within 1/255. The gallery's scenes leave the tint
/// at 1, where multiplying and dividing by it agree. Kills, in
/// `shaders/lib/hair_radiance.wgsl`, `color * frame.hair_color.rgb` → `/`.
#[test]
fn the_hair_colour_tints_the_strands_as_their_own_colour_would() {
    let (_lock, gpu) = open_gpu();
    let path = repo_root().join("examples/scenes/small.toml");
    let tint = glam::Vec3::new(0.5, 0.7, 0.9);
    let render = |scene: &SceneData| {
        let pipeline = repo_root().join("pipelines/occupancy.toml");
        let prepared = prepare(&gpu, &pipeline, &[], scene, (96, 72)).expect("prepares");
        prepared.render_unchecked().expect("renders");
        prepared.image().expect("reads back")
    };
    let mut on_material = SceneData::load(Some(&path)).expect("the small scene loads");
    let m = &mut on_material.scene.material;
    m.color = (glam::Vec3::from(m.color) * tint).into();
    let mut on_strands = SceneData::load(Some(&path)).expect("the small scene loads");
    for c in &mut on_strands.strands.color {
        *c *= tint;
    }
    let (a, b) = (render(&on_material), render(&on_strands));
    let worst = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| p.0.iter().zip(q.0).map(|(&x, y)| x.abs_diff(y)))
        .max()
        .expect("pixels");
    let changed = b
        .pixels()
        .zip(render(&SceneData::load(Some(&path)).expect("loads")).pixels())
        .filter(|(p, q)| p != q)
        .count();
    assert!(
        changed > 100,
        "the tint must change the hair: {changed} pixels differ"
    );
    assert!(
        worst <= 1,
        "tint on the material vs on the strands: a channel differs by {worst}/255"
    );
}
