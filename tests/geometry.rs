//! GPU tier: the `geometry` choice point. `lod` (coverage-preserving strand
//! reduction, `techniques/geometry/lod/technique.toml`) has a golden image at
//! a near and a far camera, each of which fails against `strands` at the
//! same camera; its widening brings the image closer to every strand than
//! the same strands dropped without it; a screen fraction out of range is an
//! error naming the param.

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
    prepared.renderer.render().unwrap_or_else(|e| panic!("{e}"));
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
                p.renderer.render().map_err(|e| e.to_string())?;
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
/// the near and the far camera, each of which fails against `strands` and
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
