//! GPU tier: the `geometry` choice point. `lod` (coverage-preserving strand
//! reduction, `techniques/geometry/lod/technique.toml`) has a golden image at
//! a near and a far camera, each of which fails against `strands` at the
//! same camera, and where the groom fills the fraction it is the strands
//! image to the bit; its widening brings the image closer to every strand than
//! the same strands dropped without it; a screen fraction out of range is an
//! error naming the param. `wisps` has goldens too, follows the hair as it
//! moves, takes strand-space shading, and draws fewer, wider wisps far away.

use image::RgbaImage;
use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::golden_images::{Comparison, check_golden, check_no_hair, compare};
use plait_tests::{open_gpu, repo_root, strands_subset};

/// The goldens' size (tests/goldens.rs).
const SIZE: (u32, u32) = (256, 192);
/// Every strand is drawn from a groom as tall as the screen: at the near
/// camera (a bounding sphere ~0.7 of the screen's height) most strands stay,
/// at the far one (~0.35) about a third.
const FRACTION: &str = "params.lod_screen_fraction=1.0";

fn load_scene(relative: &str) -> SceneData {
    SceneData::load(Some(&repo_root().join(relative)))
        .unwrap_or_else(|e| panic!("loading {relative}: {e}"))
}

fn render(gpu: &Gpu, sets: &[&str], scene: &SceneData) -> RgbaImage {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let prepared = prepare(gpu, &pipeline, &sets, scene, SIZE)
        .unwrap_or_else(|e| panic!("preparing {sets:?}: {e}"));
    prepared
        .render_unchecked()
        .unwrap_or_else(|e| panic!("{e}"));
    prepared.image().unwrap_or_else(|e| panic!("{e}"))
}

/// The scene without hair, held to its own golden: the mask of the others.
fn no_hair(gpu: &Gpu, relative: &str, stem: &str) -> RgbaImage {
    let mut bare = load_scene(relative);
    bare.strands = plait_tests::hair_taken_away(&bare.strands);
    bare.guides = plait_hair::guides::Guides::default();
    let image = render(gpu, &[], &bare);
    check_no_hair(stem, &image).unwrap_or_else(|e| panic!("{e}"));
    image
}

/// The kept fraction `plait::geometry::lod` computes for this frame.
fn kept_fraction(scene: &SceneData, screen_fraction: f32) -> f32 {
    plait::strand_lod::kept_fraction(&scene.frame(SIZE, 0), screen_fraction)
}

use plait::strand_lod::kept;

fn report(what: &str, c: &Comparison) -> String {
    format!("{what}: {}", c.summary())
}

#[test]
fn lod_matches_its_golden_at_a_near_and_a_far_camera_and_fails_as_strands() {
    let (_lock, gpu) = open_gpu();
    let mut failures = Vec::new();
    for camera in ["near", "far"] {
        let relative = format!("tests/fixtures/golden_{camera}.toml");
        let scene = load_scene(&relative);
        let k = kept_fraction(&scene, 1.0);
        eprintln!("{camera}: lod keeps {:.3} of the strands", k);
        assert!(
            k < 0.9,
            "{camera}: lod must drop strands at this camera (kept fraction {k})"
        );
        let mask = no_hair(&gpu, &relative, &format!("no_hair_{camera}"));
        let lod = render(&gpu, &["techniques.geometry=lod", FRACTION], &scene);
        let strands = render(&gpu, &[], &scene);
        if let Err(e) = check_golden(&format!("lod_{camera}"), &lod, &mask) {
            failures.push(e);
        }
        // The golden must tell lod from every strand at the same camera.
        let c = compare(&lod, &strands, &mask);
        eprintln!("{}", report(&format!("{camera}: lod as strands"), &c));
        if c.passes() {
            failures.push(report(
                &format!("{camera}: lod passes as the strands image"),
                &c,
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Coverage preservation: the kept strands drawn as `lod` draws them
/// (widened: alpha 1 − (1 − a)^w) are closer to every strand than the same
/// strands drawn as themselves. Far camera, where a third are kept.
#[test]
fn widening_the_kept_strands_keeps_the_hair_closer_to_every_strand_than_dropping_alone() {
    let (_lock, gpu) = open_gpu();
    let relative = "tests/fixtures/golden_far.toml";
    let scene = load_scene(relative);
    let mask = no_hair(&gpu, relative, "no_hair_far");
    let all = render(&gpu, &[], &scene);
    let lod = render(&gpu, &["techniques.geometry=lod", FRACTION], &scene);
    let k = kept_fraction(&scene, 1.0);
    let mut dropped = load_scene(relative);
    dropped.strands = strands_subset(&scene.strands, |s| kept(s as u32, k));
    let kept_count = dropped.strands.strand_count();
    let total = scene.strands.strand_count();
    // The kept count is k·N within a few strands (a low-discrepancy order).
    let expected = k * total as f32;
    assert!(
        (kept_count as f32 - expected).abs() <= 4.0,
        "kept {kept_count} of {total}, expected {expected:.1}"
    );
    let only_dropped = render(&gpu, &[], &dropped);
    let widened = compare(&lod, &all, &mask);
    let thinned = compare(&only_dropped, &all, &mask);
    eprintln!("{}", report("lod (widened) vs strands", &widened));
    eprintln!(
        "{}",
        report("kept strands, not widened, vs strands", &thinned)
    );
    assert!(
        widened.hair_mean < thinned.hair_mean * 0.75,
        "widening must bring the hair closer to every strand: {} vs {}",
        widened.summary(),
        thinned.summary()
    );
}

/// Where the groom on screen is at least the screen fraction, lod keeps every
/// strand at weight 1: its image is the strands image to the bit (near
/// camera, fraction 0.5 of a groom ~0.7 of the screen). A kept fraction
/// capped below 1 (`geometry.wgsl`'s clamp to 0.9) drops a tenth of the
/// strands there and widens the rest, and fails this.
#[test]
fn a_groom_larger_than_the_fraction_is_drawn_whole() {
    let (_lock, gpu) = open_gpu();
    let scene = load_scene("tests/fixtures/golden_near.toml");
    let k = kept_fraction(&scene, 0.5);
    assert!(
        k >= 1.0,
        "the near groom must fill 0.5 of the screen (kept fraction {k})"
    );
    let lod = render(
        &gpu,
        &["techniques.geometry=lod", "params.lod_screen_fraction=0.5"],
        &scene,
    );
    let strands = render(&gpu, &[], &scene);
    let differing = lod
        .pixels()
        .zip(strands.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "{differing} pixels differ from every strand's image"
    );
}

/// A screen fraction out of range is an error naming the param, at the flag.
#[test]
fn a_screen_fraction_out_of_range_names_the_param() {
    let (_lock, gpu) = open_gpu();
    let scene = load_scene("tests/fixtures/golden_far.toml");
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    for bad in ["0", "1.5", "-0.2"] {
        let sets = vec![
            "techniques.geometry=lod".to_owned(),
            format!("params.lod_screen_fraction={bad}"),
        ];
        let e = match prepare(&gpu, &pipeline, &sets, &scene, SIZE) {
            Ok(_) => panic!("lod_screen_fraction = {bad} must be refused"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains("lod_screen_fraction"), "{e}");
        assert!(e.contains("out of range"), "{e}");
    }
}

/// The strands vanish in one fixed order: a strand kept at a kept fraction is
/// kept at every larger one, and the count follows k · N closely.
#[test]
fn the_kept_strands_are_nested_and_their_count_follows_the_fraction() {
    let n = 2000u32;
    let mut previous: Vec<u32> = Vec::new();
    for step in 1..=20 {
        let k = step as f32 / 20.0;
        let now: Vec<u32> = (0..n).filter(|&i| kept(i, k)).collect();
        assert!(
            previous.iter().all(|i| now.contains(i)),
            "a strand kept at {} is dropped at {k}",
            (step - 1) as f32 / 20.0
        );
        assert!(
            (now.len() as f32 - k * n as f32).abs() <= 4.0,
            "k = {k}: {} kept of {n}",
            now.len()
        );
        previous = now;
    }
}

/// `lod` composes with every self-shadowing and every transparency technique
/// (the combination test renders all pairs with the default fraction; here
/// each one with strands actually dropped): each renders, and each image
/// differs from the same choice with every strand.
#[test]
fn lod_drops_strands_under_every_self_shadowing_and_transparency_technique() {
    let (_lock, gpu) = open_gpu();
    let mut scene = load_scene("examples/scenes/small.toml");
    let step = (scene.strands.strand_count() / 200).max(1);
    scene.strands = strands_subset(&scene.strands, |s| s % step == 0);
    // Three times as far: a small groom on screen.
    let camera = &mut scene.scene.camera;
    let (eye, target) = (
        glam::Vec3::from(camera.eye),
        glam::Vec3::from(camera.target),
    );
    camera.eye = (target + (eye - target) * 3.0).to_array();
    let k = kept_fraction(&scene, 1.0);
    assert!(k < 0.8, "the far small scene must drop strands (kept {k})");
    let roots = plait_graph::techniques::TechniqueRoots::at(repo_root().join("techniques"));
    let mut failures = Vec::new();
    for point in ["self_shadow", "transparency"] {
        for name in roots.choices(point) {
            let choice = format!("techniques.{point}={name}");
            let pipeline = repo_root().join("pipelines/occupancy.toml");
            let image = |sets: Vec<String>| -> Result<RgbaImage, String> {
                let p =
                    prepare(&gpu, &pipeline, &sets, &scene, (96, 72)).map_err(|e| e.to_string())?;
                p.render_unchecked().map_err(|e| e.to_string())?;
                p.image().map_err(|e| e.to_string())
            };
            let lod = image(vec![
                choice.clone(),
                "techniques.geometry=lod".into(),
                FRACTION.into(),
            ]);
            let all = image(vec![choice.clone()]);
            match (lod, all) {
                (Ok(lod), Ok(all)) => {
                    let differing = lod
                        .pixels()
                        .zip(all.pixels())
                        .filter(|(a, b)| a != b)
                        .count();
                    eprintln!("{choice}: {differing} pixels differ from every strand");
                    if differing == 0 {
                        failures.push(format!("{choice}: lod changed nothing"));
                    }
                }
                (lod, all) => failures.push(format!(
                    "{choice}: lod {:?}, strands {:?}",
                    lod.err(),
                    all.err()
                )),
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `wisps` (polygon wisps with a strand texture, Halén & Wester 2007
/// §2.2–2.4, `techniques/geometry/wisps/technique.toml`): a golden image at
/// the near and the far camera (where the wisps' default level of detail
/// draws fewer, wider wisps), each of which fails against `strands` and
/// against `lod` at the same camera.
#[test]
fn wisps_match_their_golden_at_a_near_and_a_far_camera_and_fail_as_strands_and_lod() {
    let (_lock, gpu) = open_gpu();
    let mut failures = Vec::new();
    for camera in ["near", "far"] {
        let relative = format!("tests/fixtures/golden_{camera}.toml");
        let scene = load_scene(&relative);
        let mask = no_hair(&gpu, &relative, &format!("no_hair_{camera}"));
        // A small strand texture: the golden is about the wisps, and the
        // texture's pass runs in the test's time.
        let wisps = render(
            &gpu,
            &["techniques.geometry=wisps", "params.wisp_texture_size=64"],
            &scene,
        );
        if let Err(e) = check_golden(&format!("wisps_{camera}"), &wisps, &mask) {
            failures.push(e);
        }
        let strands = render(&gpu, &[], &scene);
        let lod = render(&gpu, &["techniques.geometry=lod", FRACTION], &scene);
        for (other, image) in [("strands", &strands), ("lod", &lod)] {
            let c = compare(&wisps, image, &mask);
            eprintln!("{}", report(&format!("{camera}: wisps as {other}"), &c));
            if c.passes() {
                failures.push(report(
                    &format!("{camera}: wisps pass as the {other} image"),
                    &c,
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Small renders for the wisps' own tests (seconds each on lavapipe).
const SMALL: (u32, u32) = (96, 72);
/// A small strand texture and fewer wisps: these tests are about where the
/// wisps are and how they are shaded, not about the texture.
const WISPS: [&str; 3] = [
    "techniques.geometry=wisps",
    "params.wisp_texture_size=32",
    "params.wisp_count=120",
];

fn prepare_small<'g>(
    gpu: &'g Gpu,
    sets: &[&str],
    scene: &SceneData,
    size: (u32, u32),
) -> plait::session::Prepared<'g> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    prepare(gpu, &pipeline, &sets, scene, size)
        .unwrap_or_else(|e| panic!("preparing {sets:?}: {e}"))
}

/// Σα per pixel of the visible hair fragments (the occupancy pipeline's
/// `camera_alpha`, red), after the last render.
fn alpha_sums(prepared: &plait::session::Prepared) -> Vec<f32> {
    let texels = prepared
        .read_resource("camera_alpha")
        .unwrap_or_else(|e| panic!("{e}"));
    (0..(texels.width * texels.height) as usize)
        .map(|i| texels.texel(i)[0])
        .collect()
}

/// The Σα-weighted centre of the hair on screen (pixels) and the total Σα.
fn hair_centre(sums: &[f32], width: u32) -> (glam::Vec2, f32) {
    let mut total = 0.0f64;
    let (mut x, mut y) = (0.0f64, 0.0f64);
    for (i, &a) in sums.iter().enumerate() {
        let a = a as f64;
        total += a;
        x += a * (i as u32 % width) as f64;
        y += a * (i as u32 / width) as f64;
    }
    assert!(total > 0.0, "no hair on screen");
    (
        glam::Vec2::new((x / total) as f32, (y / total) as f32),
        total as f32,
    )
}

/// Mean |a − b| over the RGB channels of two images (0–255).
fn mean_difference(a: &RgbaImage, b: &RgbaImage) -> f64 {
    let sum: u64 = a
        .pixels()
        .zip(b.pixels())
        .map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c]) as u64).sum::<u64>())
        .sum();
    sum as f64 / (3 * a.width() * a.height()) as f64
}

/// Wisps move with the hair (Halén & Wester 2007 §2, §4: the wisps are the
/// geometry that moves): every wisp vertex follows the hair vertex it stands
/// for in `hair_vertices`, which the head's animation rewrites each frame
/// (on the CPU) and the simulation's guide interpolation rewrites (on the
/// GPU). In the head-turn scene (45° at t = 1 s) the hair's on-screen centre
/// (Σα weighted) moves as far with wisps as with strands: rigidly with the
/// head and, with `simulation = verlet` on a groom of guide strands (the
/// wisps then follow guides moved to their centres, offset from the strand
/// they stand for), lagging behind it. Wisps built once at rest and drawn
/// from there would not move at all.
#[test]
fn wisps_follow_the_hair_when_the_head_turns() {
    let (_lock, gpu) = open_gpu();
    let path = repo_root().join("examples/scenes/head_turn.toml");
    let text = std::fs::read_to_string(&path).expect("head_turn.toml");
    let guided = text.replace("strands = 400\n", "strands = 400\nguides = 60\n");
    assert_ne!(guided, text, "head_turn.toml's groom has 400 strands");
    let guided = plait_hair::Scene::from_toml_str(&guided, &path).expect("parses");
    let cases = [
        (
            "animation",
            load_scene("examples/scenes/head_turn.toml"),
            vec![],
        ),
        (
            "verlet, guides",
            SceneData::new(guided).expect("loads"),
            vec!["techniques.simulation=verlet", "params.light_size=16"],
        ),
    ];
    for (what, scene, extra) in cases {
        let mut shifts = Vec::new();
        for geometry in [&[][..], &WISPS[..]] {
            let mut sets = extra.clone();
            sets.extend_from_slice(geometry);
            let mut prepared = prepare_small(&gpu, &sets, &scene, SMALL);
            let mut centre = Vec::new();
            for frame in 0..=30 {
                prepared
                    .render_frame(&scene, SMALL, frame, 30.0)
                    .unwrap_or_else(|e| panic!("{e}"));
                if frame % 30 == 0 {
                    centre.push(hair_centre(&alpha_sums(&prepared), SMALL.0).0);
                }
            }
            eprintln!(
                "{what}: {geometry:?}: hair centre {} → {}",
                centre[0], centre[1]
            );
            shifts.push(centre[1] - centre[0]);
        }
        let (strands, wisps) = (shifts[0], shifts[1]);
        assert!(
            strands.length() > 4.0,
            "{what}: the strands must move on screen for this test to tell anything: {strands}"
        );
        // Wisps are wider and fewer than the strands, so their centre is not
        // the strands' — but it moves with the hair: within a fifth of the
        // strands' motion (and a pixel).
        assert!(
            (wisps - strands).length() < 0.2 * strands.length() + 1.0,
            "{what}: the wisps moved {wisps} px on screen, the strands {strands} px"
        );
    }
}

/// `shading_space = strand` shades wisp fragments too: a wisp fragment reads
/// the radiance shaded at the hair vertex it stands for, interpolated along
/// the strand. With one shading point per strand (its middle) every wisp is
/// shaded flat, far from per-fragment shading; with a shading point at every
/// hair vertex (Gouraud along the strand) it is close to it. Wisps that fell
/// back to per-fragment shading would give the same image for both.
#[test]
fn strand_space_shading_reaches_the_wisps() {
    let (_lock, gpu) = open_gpu();
    let scene = load_scene("examples/scenes/small.toml");
    let points = scene
        .strands
        .ranges()
        .map(|r| r.len())
        .min()
        .expect("strands");
    let image = |extra: &[&str]| {
        let mut sets = WISPS.to_vec();
        sets.extend_from_slice(extra);
        let prepared = prepare_small(&gpu, &sets, &scene, SMALL);
        prepared
            .render_unchecked()
            .unwrap_or_else(|e| panic!("{e}"));
        prepared.radiance().unwrap_or_else(|e| panic!("{e}"))
    };
    let every = format!("params.shading_points={points}");
    let fragment = image(&[]);
    let one = image(&["techniques.shading_space=strand", "params.shading_points=1"]);
    let gouraud = image(&["techniques.shading_space=strand", &every]);
    let far = mean_radiance_difference(&one, &fragment);
    let near = mean_radiance_difference(&gouraud, &fragment);
    eprintln!(
        "wisps, strand space vs per fragment: 1 point {far:.3e}, {points} points {near:.3e} (mean |Δ radiance|)"
    );
    assert!(
        far > 1e-3 && far > 3.0 * near,
        "one shading point per strand must change the wisps ({far:.3e}) far more than one per hair vertex ({near:.3e})"
    );
}

/// Mean absolute difference of two linear radiance images' RGB.
fn mean_radiance_difference(a: &image::Rgba32FImage, b: &image::Rgba32FImage) -> f64 {
    let sum: f64 = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..3).map(move |c| f64::from((p[c] - q[c]).abs())))
        .sum();
    sum / (3 * a.width() * a.height()) as f64
}

/// The wisps' own level of detail (Halén & Wester 2007 §2.4: "reducing the
/// number of wisps and at the same time increasing their width"): at the far
/// camera (the groom spans ~0.4 of the screen; every wisp drawn only from a
/// full screen's height) fewer wisps are drawn, each wider, and the hair's
/// total coverage on screen (Σα over the image) stays within 10 % of every
/// wisp's (drawn without widening it would fall to the kept fraction); at
/// the near camera (~0.70, default fraction 0.5) the image is every
/// wisp's, exactly.
#[test]
fn far_away_fewer_wider_wisps_keep_the_coverage_and_near_nothing_changes() {
    let (_lock, gpu) = open_gpu();
    let size = (128, 96);
    for camera in ["near", "far"] {
        let scene = load_scene(&format!("tests/fixtures/golden_{camera}.toml"));
        let render = |extra: &[&str]| {
            let mut sets = WISPS.to_vec();
            sets.extend_from_slice(extra);
            let prepared = prepare_small(&gpu, &sets, &scene, size);
            prepared
                .render_unchecked()
                .unwrap_or_else(|e| panic!("{e}"));
            let count = prepared.wisp_count.expect("wisps were built");
            let (_, total) = hair_centre(&alpha_sums(&prepared), size.0);
            (
                prepared.image().unwrap_or_else(|e| panic!("{e}")),
                total,
                count,
            )
        };
        // Near: the default fraction (0.5), which the groom exceeds there;
        // far: every wisp only from a full screen's height (1), so about a
        // third are drawn, each about three times as wide.
        let fraction = if camera == "near" { 0.5 } else { 1.0 };
        let set = format!("params.wisp_lod_screen_fraction={fraction}");
        let lod_sets = if camera == "near" {
            vec![]
        } else {
            vec![set.as_str()]
        };
        let (lod, lod_sum, count) = render(&lod_sets);
        let (all, all_sum, _) = render(&["params.wisp_lod_screen_fraction=0"]);
        let frame = scene.frame(size, 0);
        let kept = plait::wisps::kept_wisps(&frame, fraction, count);
        eprintln!(
            "{camera}: {kept} of {count} wisps drawn, Σα {lod_sum:.1} vs every wisp's {all_sum:.1}, mean |Δ| {:.3}",
            mean_difference(&lod, &all)
        );
        if camera == "near" {
            assert_eq!(kept, count, "near: every wisp is drawn");
            assert!(lod == all, "near: the image must be every wisp's");
        } else {
            assert!(
                kept < count / 2,
                "far: the level of detail must leave wisps out ({kept} of {count})"
            );
            assert!(lod != all, "far: fewer wisps must change the image");
            let ratio = lod_sum / all_sum;
            assert!(
                (ratio - 1.0).abs() < 0.1,
                "far: {kept} wider wisps cover {ratio:.3} of what {count} do (Σα)"
            );
        }
    }
}
