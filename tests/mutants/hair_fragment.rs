//! `shared/hair_fragment`: the fragment alpha of `shaders/lib/hair_fragment.wgsl`,
//! and the opaque shadow `shaders/lib/hair_radiance.wgsl` applies.

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{one_strand_scene, open_gpu, repo_root};

use crate::SIDE_LIT;

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

/// Wisps (the strand texture, 32², 120 wisps) on the small scene with the
/// specular off, at 96×72: shaded per fragment, and in strand space with a
/// shading point per strand point (17), which `shade_hair` scales by the
/// strand texture's colour where the per-fragment path puts it into the
/// albedo: the two agree on every term linear in the albedo, here all of
/// them. Returns the RMSE of the colour channels over the hair pixels (0–1)
/// and how many pixels that is.
fn wisps_strand_space_against_fragment(gpu: &Gpu) -> (f64, usize) {
    let path = repo_root().join("examples/scenes/small.toml");
    let mut scene = SceneData::load(Some(&path)).expect("the small scene loads");
    scene.scene.material.specular = 0.0;
    let mut bare = SceneData::load(Some(&path)).expect("the small scene loads");
    bare.scene.material.specular = 0.0;
    bare.strands = plait_tests::hair_taken_away(&bare.strands);
    bare.guides = plait_hair::guides::Guides::default();
    let wisps = [
        "techniques.geometry=wisps",
        "params.wisp_texture_size=32",
        "params.wisp_count=120",
    ];
    let render = |scene: &SceneData, extra: &[&str]| {
        let pipeline = repo_root().join("pipelines/occupancy.toml");
        let sets: Vec<String> = wisps.iter().chain(extra).map(|s| s.to_string()).collect();
        let prepared = prepare(gpu, &pipeline, &sets, scene, (96, 72)).expect("prepares");
        prepared.render().expect("renders");
        prepared.image().expect("reads back")
    };
    let fragment = render(&scene, &[]);
    let strand = render(
        &scene,
        &[
            "techniques.shading_space=strand",
            "params.shading_points=17",
        ],
    );
    let no_hair = render(&bare, &[]);
    let (mut sum, mut n) = (0.0, 0usize);
    for ((a, b), o) in fragment.pixels().zip(strand.pixels()).zip(no_hair.pixels()) {
        let differs = |p: &image::Rgba<u8>| (0..3).any(|c| p.0[c].abs_diff(o.0[c]) > 2);
        if differs(a) || differs(b) {
            for c in 0..3 {
                let d = (a.0[c] as f64 - b.0[c] as f64) / 255.0;
                sum += d * d;
            }
            n += 1;
        }
    }
    ((sum / (3 * n.max(1)) as f64).sqrt(), n)
}

/// Twice the RMSE measured on lavapipe (0.00303 over 1837 hair pixels;
/// the `/ texel.rgb` mutant measures 0.01347).
const WISP_MARGIN: f64 = 0.006;

/// Wisps shaded in strand space (every strand point a shading point, no
/// specular) stay within an RMSE of WISP_MARGIN of per-fragment shading over
/// the hair pixels. Kills, in `shaders/lib/hair_fragment.wgsl`,
/// `shaded.rgb * texel.rgb` → `/` (the strand texture's colour divides the
/// strand-space radiance: the gallery's wisps never run in strand space).
#[test]
fn wisps_in_strand_space_match_fragment_shading_without_specular() {
    let (_lock, gpu) = open_gpu();
    let (rmse, pixels) = wisps_strand_space_against_fragment(&gpu);
    eprintln!("wisps, strand space against per fragment: RMSE {rmse:.5} over {pixels} hair pixels");
    assert!(pixels > 500, "only {pixels} hair pixels");
    assert!(
        rmse <= WISP_MARGIN,
        "wisps in strand space are {rmse:.5} from per-fragment shading, above {WISP_MARGIN}"
    );
}

/// A multiple-scattering technique adds light to the hair and takes none
/// away: the default pipeline with Chiang's fibre and Karis's provider
/// (whose term is ≥ 0 by its formula: √base, a mix of two saturated
/// non-negative terms, a positive tint) is at least as bright as the same
/// without multiple scattering at every pixel and channel, within 1e-3 of
/// the pixel (rgba16float), and brighter by > 1e-3 somewhere. No other test
/// of the hair-fragment stage renders with a multiple-scattering technique
/// (the gallery's is `none`, a term of 0). Kills, in
/// `shaders/lib/hair_radiance.wgsl`, the term dropped from the sum and added
/// → subtracted.
#[test]
fn multiple_scattering_adds_light_to_the_hair() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let render = |ms: &str| {
        let sets = [
            "techniques.shading=chiang".to_owned(),
            format!("techniques.multiple_scattering={ms}"),
        ];
        let prepared = prepare(&gpu, &pipeline, &sets, &scene, (64, 48)).expect("prepares");
        prepared.render().expect("renders");
        prepared.radiance().expect("reads back")
    };
    let (with, without) = (render("karis"), render("none"));
    let (mut most, mut least) = (0.0_f32, 0.0_f32);
    for (p, q) in with.pixels().zip(without.pixels()) {
        for c in 0..3 {
            let d = p.0[c] - q.0[c];
            most = most.max(d);
            least = least.min(d + 1e-3 * q.0[c].abs());
        }
    }
    eprintln!("Karis − none: largest {most:e}, least (with the tolerance) {least:e}");
    assert!(most > 1e-3, "multiple scattering adds nothing: {most}");
    assert!(least >= 0.0, "multiple scattering darkens a pixel: {least}");
}

/// The opaque shadow the hair-fragment stage applies (`plait::hair_radiance`)
/// at points swept in light depth through the opaque surface at the centre
/// texel of the light's map (`tests/fixtures/opaque_bias.wgsl`, the small
/// scene): the shaded term over the unshadowed one is the 3×3 comparison
/// at the bias 0.002 the stage states, within 1e-3, at every point not
/// within 1e-6 of a tie; the sweep runs from 1.6e-3 in front of the stored
/// depth to 4.8e-3 behind it in steps of 5e-5, so the centre texel's own
/// comparison turns at δ = 0.002 (required: the PCF falls there). Kills, in `shaders/lib/hair_radiance.wgsl`, the opaque
/// shadow's bias 0.002 → 0.0022 (31:51: points 2.05e-3…2.15e-3 behind the
/// surface lit) and → 0.0018.
#[test]
fn the_opaque_shadow_turns_at_its_bias_behind_the_surface() {
    const WIDTH: usize = 128;
    let read = plait_tests::fixture_texels("opaque_bias.toml", (WIDTH as u32, 2), &["cases"]);
    let stored = read[0][WIDTH][0];
    let cases = &read[0][..WIDTH];
    assert!(
        stored < 0.99,
        "the light map's centre texel holds no opaque surface (depth {stored})"
    );
    let mut failures = Vec::new();
    for (x, t) in cases.iter().enumerate() {
        let [shadow, want, delta, tie] = *t;
        if tie >= 1e-6 && (!shadow.is_finite() || (shadow - want).abs() > 1e-3) {
            failures.push(format!(
                "column {x}, δ {delta:.5}: shadow {shadow:.4}, the PCF at bias 0.002 {want:.4}"
            ));
        }
    }
    // The centre texel's own comparison turns at δ = 0.002: the PCF just
    // past it is below the PCF just before it, or the test tests nothing.
    let pcf_at = |d: f32| {
        cases
            .iter()
            .min_by(|a, b| (a[2] - d).abs().total_cmp(&(b[2] - d).abs()))
            .map(|t| t[1])
            .expect("cases")
    };
    let (before, past) = (pcf_at(0.00195), pcf_at(0.0021));
    eprintln!(
        "opaque bias: stored depth {stored}; PCF {before:.3} at δ 0.00195, {past:.3} at 0.0021; {} columns off",
        failures.len()
    );
    assert!(
        past < before,
        "the centre texel must turn at δ = 0.002: PCF {before} before, {past} past"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// One straight strand along x in the plane facing the camera, two pixels
/// wide (0.08 world units: 2.2 px at 160×120; the quad draw, whole pixels
/// along its middle), grey, under `SIDE_LIT`'s light; no self-shadow.
fn straight_strand_scene() -> SceneData {
    let points: Vec<glam::Vec3> = (0..9)
        .map(|i| glam::Vec3::new(-1.6 + 0.4 * i as f32, 0.0, 0.0))
        .collect();
    one_strand_scene(
        "multiple_scattering_stage.toml",
        SIDE_LIT,
        &points,
        0.08,
        0.8,
    )
}

/// Karis 2016's term per unit irradiance, unshadowed (v = 1: tint 1), in f64
/// (`techniques/multiple_scattering/karis`, as `tests/karis.rs` states it).
fn karis_unshadowed(
    t: glam::DVec3,
    l: glam::DVec3,
    e: glam::DVec3,
    base: glam::DVec3,
    scatter: f64,
) -> glam::DVec3 {
    let kajiya = 1.0 - t.dot(l).abs();
    let n = (e - t * e.dot(t)).normalize();
    let wrap = ((n.dot(l) + 1.0) / 4.0).clamp(0.0, 1.0);
    let diffuse = (1.0 / std::f64::consts::PI) * (wrap + (kajiya - wrap) * 0.33) * scatter;
    glam::DVec3::new(base.x.sqrt(), base.y.sqrt(), base.z.sqrt()) * diffuse
}

/// The hair-fragment stage hands the multiple-scattering provider the
/// fragment's tangent, the direction to the light and the direction to the
/// eye, in that order: on a straight strand along x (T known), Karis's
/// provider against `none`, the added radiance of every pixel the strand
/// covers at least half (premultiplied colour ÷ alpha) is the light's
/// irradiance × Karis's formula at T, L and the eye direction from the
/// pixel centre's point on the strand, within 1e-4 relative (measured at
/// 7ec7aa6: 1.1e-7, f32 rounding). Swapped, the formula's terms move by 30 % (T ↔ L: the
/// eye projected normal to L instead of T) to 3× (L ↔ E: 1 − |T·E| for
/// 1 − |T·L|). Kills, in `shaders/lib/hair_radiance.wgsl`, 38:47 and 38:56
/// (the provider's tangent ↔ light and light ↔ eye), which the test above,
/// whose term is only ≥ 0, let through.
#[test]
fn the_stage_gives_multiple_scattering_its_tangent_light_and_eye() {
    const SIZE: (u32, u32) = (160, 120);
    let (_lock, gpu) = open_gpu();
    let scene = straight_strand_scene();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let render = |ms: &str| {
        let sets = [
            "techniques.shading=chiang".to_owned(),
            "techniques.shading_space=fragment".to_owned(),
            "techniques.self_shadow=none".to_owned(),
            format!("techniques.multiple_scattering={ms}"),
            "pipeline.outputs=[\"final\", \"hair\"]".to_owned(),
        ];
        let prepared = prepare(&gpu, &pipeline, &sets, &scene, SIZE).expect("prepares");
        prepared.render().expect("renders");
        let hair = prepared.read_resource("hair").expect("hair");
        (0..(hair.width * hair.height) as usize)
            .map(|i| hair.texel(i))
            .collect::<Vec<[f32; 4]>>()
    };
    let (with, without) = (render("karis"), render("none"));
    let frame = scene.frame(SIZE, 0);
    let l = glam::Vec4::from(frame.light_direction)
        .truncate()
        .as_dvec3();
    let irradiance = glam::Vec4::from(frame.light_color).truncate().as_dvec3();
    let base = glam::Vec4::from(frame.hair_color).truncate().as_dvec3() * 0.8;
    let eye = glam::DVec3::new(0.0, 0.0, 6.0);
    let focal = f64::from(SIZE.1) / 2.0 / 15f64.to_radians().tan();
    let (mut pixels, mut worst) = (0usize, 0.0f64);
    for (i, (k, n)) in with.iter().zip(&without).enumerate() {
        if k[3] < 0.5 || n[3] < 0.5 {
            continue;
        }
        // The pixel centre's point on the strand (y = 0, z = 0).
        let column = (i % SIZE.0 as usize) as f64 + 0.5;
        let x = (column - f64::from(SIZE.0) / 2.0) / focal * 6.0;
        let e = (eye - glam::DVec3::new(x, 0.0, 0.0)).normalize();
        let want = irradiance * karis_unshadowed(glam::DVec3::X, l, e, base, 1.0);
        for c in 0..3 {
            let got = f64::from(k[c] / k[3] - n[c] / n[3]);
            worst = worst.max((got / want[c] - 1.0).abs());
        }
        pixels += 1;
    }
    eprintln!(
        "{pixels} pixels: Karis's added radiance against its formula at T, L, E: largest relative error {worst:.2e}"
    );
    assert!(
        pixels >= 100,
        "the strand covers {pixels} pixels at least half"
    );
    assert!(
        worst < 1e-4,
        "the added radiance is {worst:.4} from Karis's formula at T, L, E"
    );
}
