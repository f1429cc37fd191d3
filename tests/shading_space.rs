//! Strand-space shading (`techniques.shading_space = "strand"`, Tafuri 2019):
//! a golden image on the small scene that the per-fragment image cannot pass
//! for, the limit case K = the strand's points held close to per-fragment
//! shading, the shading-point count checked against the scene, tip fading,
//! and every provider's w a constant (what keeps strand space a saving).

use std::sync::MutexGuard;

use image::RgbaImage;
use plait::session::{SceneData, prepare};
use plait_gpu::{Gpu, ShaderLibrary};
use plait_tests::golden_images::{check_golden, check_no_hair, compare};
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (256, 192);
const SMALL: &str = "examples/scenes/small.toml";
/// Points per strand of the small scene (16 segments).
const SMALL_POINTS: usize = 17;

fn gpu() -> (MutexGuard<'static, ()>, Gpu) {
    open_gpu()
}

fn small() -> SceneData {
    SceneData::load(Some(&repo_root().join(SMALL))).expect("small scene")
}

fn render(gpu: &Gpu, sets: &[String], scene: &SceneData) -> RgbaImage {
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let prepared =
        prepare(gpu, &pipeline, sets, scene, SIZE).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
    prepared.render_unchecked().expect("render");
    prepared.image().expect("read back")
}

fn strand(points: usize) -> Vec<String> {
    vec![
        "techniques.shading_space=strand".into(),
        format!("params.shading_points={points}"),
    ]
}

/// The small scene without its hair: which pixels are hair.
fn mask(gpu: &Gpu) -> RgbaImage {
    let mut bare = small();
    bare.strands = plait_tests::hair_taken_away(&bare.strands);
    bare.guides = plait_hair::guides::Guides::default();
    let image = render(gpu, &[], &bare);
    check_no_hair("no_hair_small", &image).unwrap_or_else(|e| panic!("{e}"));
    image
}

/// RMSE over the colour channels of the pixels `mask` calls hair, in 0..=1.
fn hair_rmse(a: &RgbaImage, b: &RgbaImage, bare: &RgbaImage) -> f64 {
    let (mut sum, mut n) = (0.0, 0u64);
    for ((pa, pb), pn) in a.pixels().zip(b.pixels()).zip(bare.pixels()) {
        let hair = plait_tests::golden_images::pixel_diff(pa, pn) > 2
            || plait_tests::golden_images::pixel_diff(pb, pn) > 2;
        if hair {
            for c in 0..3 {
                let d = (pa.0[c] as f64 - pb.0[c] as f64) / 255.0;
                sum += d * d;
            }
            n += 3;
        }
    }
    (sum / n.max(1) as f64).sqrt()
}

/// The default 16 shading points per strand on the small scene match their
/// golden, and the per-fragment image fails that golden's comparison: the
/// golden tells the two shading spaces apart.
#[test]
fn strand_space_matches_its_golden_and_fragment_shading_fails_it() {
    let (_lock, gpu) = gpu();
    let scene = small();
    let bare = mask(&gpu);
    let strand_image = render(&gpu, &strand(16), &scene);
    check_golden("shading_space_strand_small", &strand_image, &bare)
        .unwrap_or_else(|e| panic!("{e}"));
    let fragment_image = render(&gpu, &[], &scene);
    let c = compare(&fragment_image, &strand_image, &bare);
    println!("fragment as strand (K = 16): {}", c.summary());
    assert!(
        !c.passes(),
        "per-fragment shading passes as strand space's golden: {}",
        c.summary()
    );
}

/// With as many shading points as the strand has points, every hair vertex
/// is shaded once and fragments interpolate between the two vertices of
/// their segment (Gouraud shading along the strand): the image stays within
/// a stated margin of per-fragment shading — an RMSE over the hair pixels of
/// at most 0.016 (measured 0.0130 on lavapipe, × 1.25; what is left is the
/// narrow Kajiya-Kay highlight and shadow edges inside a segment, which
/// shrink with shorter segments: 0.0046 → 0.0029 over the whole frame from
/// 16 to 64 segments per strand) — while 4 shading points are beyond the
/// margin (measured 0.045), so the margin tells a coarse shading apart.
#[test]
fn strand_space_with_a_shading_point_per_strand_point_matches_fragment_shading() {
    const MARGIN: f64 = 0.016;
    let (_lock, gpu) = gpu();
    let scene = small();
    let bare = mask(&gpu);
    let fragment_image = render(&gpu, &[], &scene);
    let every_point = hair_rmse(
        &render(&gpu, &strand(SMALL_POINTS), &scene),
        &fragment_image,
        &bare,
    );
    let four = hair_rmse(&render(&gpu, &strand(4), &scene), &fragment_image, &bare);
    println!(
        "hair RMSE against per-fragment shading: K = {SMALL_POINTS}: {every_point:.5}, K = 4: {four:.5}"
    );
    assert!(
        every_point <= MARGIN,
        "K = {SMALL_POINTS} (every point) is {every_point:.5} from per-fragment shading, above {MARGIN}"
    );
    assert!(
        four > MARGIN,
        "4 shading points ({four:.5}) pass the margin {MARGIN}: it would not catch a coarse shading"
    );
}

/// Zero shading points, or more than the scene's strands have points: an
/// error naming the param and the flag that set it, before any frame.
#[test]
fn shading_points_out_of_range_are_errors_naming_the_param_and_flag() {
    let (_lock, gpu) = gpu();
    let scene = small();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    for points in [0, SMALL_POINTS + 1] {
        let sets = strand(points);
        let message = match prepare(&gpu, &pipeline, &sets, &scene, (64, 48)) {
            Ok(_) => panic!("shading_points = {points} was accepted"),
            Err(e) => e.to_string(),
        };
        println!("{message}");
        assert!(
            message.contains(&format!("--set params.shading_points={points}"))
                && message.contains("`shading_points`"),
            "shading_points = {points}: {message}"
        );
    }
    // The largest count the scene allows renders.
    let ok = prepare(&gpu, &pipeline, &strand(SMALL_POINTS), &scene, (64, 48));
    assert!(ok.is_ok(), "{:?}", ok.err().map(|e| e.to_string()));
}

/// One straight strand of 9 points in front of the head, from its root on
/// the left to its tip on the right, nothing else: hair to measure the tip
/// fading on, where no strand hides another.
fn one_strand() -> SceneData {
    let mut scene = small();
    let mut strands = plait_hair::Strands::new();
    let (root, step) = (
        glam::Vec3::new(-1.2, 1.3, 2.5),
        glam::Vec3::new(0.3, 0.0, 0.0),
    );
    let points: Vec<glam::Vec3> = (0..9).map(|k| root + step * k as f32).collect();
    strands.push_strand(&points, |_| 0.01, |_| 0.8, glam::Vec3::new(0.9, 0.2, 0.1));
    scene.strands = strands;
    scene.guides = plait_hair::guides::Guides::default();
    scene
}

/// Per image column, the alpha `resource` (channel `channel`) holds after a
/// frame of `pipeline` with strand-space shading and `sets`.
fn column_alpha(
    gpu: &Gpu,
    pipeline: &str,
    resource: &str,
    channel: usize,
    sets: &[&str],
    scene: &SceneData,
) -> Vec<f64> {
    let mut all: Vec<String> = strand(9);
    all.extend(sets.iter().map(|s| s.to_string()));
    all.push(format!("pipeline.outputs=[\"final\", \"{resource}\"]"));
    let prepared = prepare(gpu, &repo_root().join(pipeline), &all, scene, (160, 120))
        .unwrap_or_else(|e| panic!("{pipeline} {all:?}: {e}"));
    prepared.render_unchecked().expect("render");
    let texels = prepared.read_resource(resource).expect("read back");
    let width = texels.width as usize;
    let mut columns = vec![0.0; width];
    for i in 0..width * texels.height as usize {
        columns[i % width] += f64::from(texels.texel(i)[channel]);
    }
    columns
}

/// Tip fading (`tip_scale`, `tip_scale_offset`; the taper of Unity's hair
/// package) scales the coverage of every hair draw alike: the hardware lines
/// of linked_list, the compute rasterizer's segments, occupancy order's hair
/// pass and its per-pixel mean alpha (alpha_sum). With the taper from half
/// the strand (vertex 4 of 8) to 0 at the tip, the root's third of the
/// strand on screen keeps its alpha (within 2 %), the last tenth keeps at
/// most a quarter, and the total falls to 0.70–0.80 of the unfaded
/// strand's (measured 0.72: a linear taper over half the strand leaves 3/4
/// of an evenly drawn strand, a little less here, where the tip is nearer
/// the eye and drawn longer) — the same fraction, within 0.01, in every
/// draw, so the shaded image and the mean alpha that weighs it agree. The
/// same holds for a wisp following that strand, drawn by the hardware and
/// by the compute rasterizer (0.78–0.88; measured 0.83). The wrong answers
/// fail: no fading leaves 1.0, a taper from the root fades the root's third.
#[test]
fn tip_fading_scales_the_coverage_of_every_hair_draw_alike() {
    let (_lock, gpu) = gpu();
    let scene = one_strand();
    let faded = ["params.tip_scale=0", "params.tip_scale_offset=0.5"];
    let strands: &[&str] = &[];
    let wisps: &[&str] = &["techniques.geometry=wisps"];
    let draws = [
        ("pipelines/linked_list.toml", "hair", 3, strands),
        ("pipelines/compute_raster.toml", "hair", 3, strands),
        ("pipelines/occupancy.toml", "hair", 3, strands),
        ("pipelines/occupancy.toml", "camera_alpha", 0, strands),
        ("pipelines/linked_list.toml", "hair", 3, wisps),
        ("pipelines/compute_raster.toml", "hair", 3, wisps),
    ];
    let mut totals = Vec::new();
    for (pipeline, resource, channel, geometry) in draws {
        let thin_sets = [geometry, &faded[..]].concat();
        let whole = column_alpha(&gpu, pipeline, resource, channel, geometry, &scene);
        let thin = column_alpha(&gpu, pipeline, resource, channel, &thin_sets, &scene);
        let drawn: Vec<usize> = (0..whole.len()).filter(|&x| whole[x] > 1e-3).collect();
        let (first, last) = (drawn[0], *drawn.last().expect("the strand is drawn"));
        let span = (last - first) as f64;
        let sum = |v: &[f64], from: f64, to: f64| -> f64 {
            (first..=last)
                .filter(|&x| (x - first) as f64 >= from * span && (x - first) as f64 <= to * span)
                .map(|x| v[x])
                .sum()
        };
        let root = sum(&thin, 0.0, 1.0 / 3.0) / sum(&whole, 0.0, 1.0 / 3.0);
        let tip = sum(&thin, 0.9, 1.0) / sum(&whole, 0.9, 1.0);
        let total = sum(&thin, 0.0, 1.0) / sum(&whole, 0.0, 1.0);
        println!(
            "{pipeline} {resource} {geometry:?}: columns {first}..={last}; faded / whole: root third {root:.4}, last tenth {tip:.4}, all {total:.4}"
        );
        assert!(
            (root - 1.0).abs() < 0.02,
            "{pipeline} {resource}: the root's third × {root}"
        );
        assert!(tip < 0.25, "{pipeline} {resource}: the tip keeps × {tip}");
        // A wisp's strand texture already thins its last quarter (its
        // strands end at 0.75–1 of its length), so less of it is left to fade.
        let expected = if geometry.is_empty() {
            0.70..=0.80
        } else {
            0.78..=0.88
        };
        assert!(
            expected.contains(&total),
            "{pipeline} {resource} {geometry:?}: × {total}"
        );
        totals.push((geometry, total));
    }
    for geometry in [strands, wisps] {
        let of: Vec<f64> = totals
            .iter()
            .filter(|t| t.0 == geometry)
            .map(|t| t.1)
            .collect();
        let spread = of.iter().cloned().fold(f64::MIN, f64::max)
            - of.iter().cloned().fold(f64::MAX, f64::min);
        assert!(
            spread < 0.01,
            "the draws of {geometry:?} fade differently: {of:?}"
        );
    }
}

/// Tip fading's params out of 0 … 1: an error naming the param and the
/// flag, before any frame.
#[test]
fn tip_fading_out_of_range_is_an_error_naming_the_param_and_flag() {
    let (_lock, gpu) = gpu();
    let scene = small();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    for set in ["params.tip_scale=1.5", "params.tip_scale_offset=-0.1"] {
        let mut sets = strand(16);
        sets.push(set.into());
        let message = match prepare(&gpu, &pipeline, &sets, &scene, (64, 48)) {
            Ok(_) => panic!("{set} was accepted"),
            Err(e) => e.to_string(),
        };
        println!("{message}");
        let param = set.trim_start_matches("params.").split('=').next().unwrap();
        assert!(
            message.contains(&format!("--set {set}")) && message.contains(&format!("`{param}`")),
            "{set}: {message}"
        );
    }
}

/// Whether expression `e` of `f` is known when the shader is compiled.
fn is_constant(f: &naga::Function, e: naga::Handle<naga::Expression>) -> bool {
    use naga::Expression as E;
    match &f.expressions[e] {
        E::Literal(_) | E::Constant(_) | E::ZeroValue(_) => true,
        E::Compose { components, .. } => components.iter().all(|&c| is_constant(f, c)),
        E::Splat { value, .. } | E::Unary { expr: value, .. } => is_constant(f, *value),
        _ => false,
    }
}

/// The expression of the last component (w) of the vec4 expression `e`.
fn w_of(f: &naga::Function, e: naga::Handle<naga::Expression>) -> naga::Handle<naga::Expression> {
    match &f.expressions[e] {
        naga::Expression::Compose { components, .. } if !components.is_empty() => {
            w_of(f, components[components.len() - 1])
        }
        _ => e,
    }
}

/// Every value a block of `f` returns, nested blocks included.
fn returns(block: &naga::Block, out: &mut Vec<Option<naga::Handle<naga::Expression>>>) {
    for statement in block.iter() {
        match statement {
            naga::Statement::Return { value } => out.push(*value),
            naga::Statement::Block(b) => returns(b, out),
            naga::Statement::If { accept, reject, .. } => {
                returns(accept, out);
                returns(reject, out);
            }
            naga::Statement::Loop {
                body, continuing, ..
            } => {
                returns(body, out);
                returns(continuing, out);
            }
            naga::Statement::Switch { cases, .. } => {
                cases.iter().for_each(|c| returns(&c.body, out))
            }
            _ => {}
        }
    }
}

/// Every shading_space provider returns a constant w. The hair draws branch
/// on it (shade here when w < 0, else take the provider's rgb), and only a
/// branch the compiler decides drops the path not taken: llvmpipe runs both
/// sides of any other, so when w carried the tip fading, strand space cost
/// per-fragment shading plus its interpolation — slower than per-fragment
/// shading instead of a saving (measured side by side with `plait ab`,
/// docs/design.md "The fragment stage asks first"). A provider computing w
/// fails here, naming it.
#[test]
fn every_shading_space_providers_w_is_a_constant() {
    let mut library =
        ShaderLibrary::new(&plait_gpu::library::Library::read(&[]).expect("the library is found"))
            .unwrap_or_else(|e| panic!("{}", e.message));
    let providers = plait_passes::shading_space::providers(&plait_passes::read_library(&[]));
    assert!(providers.len() >= 2, "providers found: {providers:?}");
    for name in &providers {
        let probe = format!(
            "#import plait::shading_space::{name}::strand_radiance\n\
             fn probe(s: u32, g: u32, a: f32) -> vec4<f32> {{ return strand_radiance(s, g, a); }}\n"
        );
        let module = library
            .compose(std::path::Path::new("probe.wgsl"), &probe, &[])
            .unwrap_or_else(|e| panic!("{name}: {}", e.message));
        let (_, f) = module
            .functions
            .iter()
            .find(|(_, f)| {
                f.name
                    .as_deref()
                    .is_some_and(|n| n.starts_with("strand_radiance"))
            })
            .unwrap_or_else(|| panic!("{name}: no strand_radiance in the composed module"));
        let mut values = Vec::new();
        returns(&f.body, &mut values);
        assert!(
            !values.is_empty(),
            "{name}: strand_radiance returns nothing"
        );
        for value in values {
            let value = value.unwrap_or_else(|| panic!("{name}: a return without a value"));
            let w = w_of(f, value);
            assert!(
                is_constant(f, w),
                "shading_space provider `{name}`: strand_radiance's w is computed at run time ({:?}); it must be a constant",
                f.expressions[w]
            );
        }
    }
}
