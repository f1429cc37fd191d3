//! Every combination of techniques composes: for each choice point's every
//! technique (found in `techniques/`, so a new one is tested without editing
//! this file), the default pipeline with those `--set techniques.…` keys
//! checks and renders on a tiny scene, and the hair shows.

use plait::session::{SceneData, prepare};
use plait_graph::techniques::{choices, points};
use plait_tests::{open_gpu, repo_root, strands_subset};

/// Every combination of one technique per point, as `--set` flags.
fn combinations() -> Vec<Vec<String>> {
    let root = repo_root().join("techniques");
    let mut combos: Vec<Vec<String>> = vec![Vec::new()];
    for point in points(&root) {
        let names = choices(&root, &point);
        assert!(!names.is_empty(), "choice point {point} has no technique");
        let mut next = Vec::new();
        for c in &combos {
            for n in &names {
                let mut c = c.clone();
                c.push(format!("techniques.{point}={n}"));
                next.push(c);
            }
        }
        combos = next;
    }
    combos
}

/// The small scene cut to 60 strands at 64×48: each frame takes well under a
/// second even when depth peeling.
fn tiny_scene() -> SceneData {
    let path = repo_root().join("examples/scenes/small.toml");
    let mut data = SceneData::load(Some(&path)).expect("small scene");
    let step = data.strands.strand_count() / 60;
    data.strands = strands_subset(&data.strands, |s| s % step == 0);
    data
}

#[test]
fn every_combination_of_techniques_checks_and_renders() {
    let combos = combinations();
    assert!(
        combos.len() >= 48,
        "expected 8 × 6 combinations, found {}",
        combos.len()
    );
    let (_lock, gpu) = open_gpu();
    let scene = tiny_scene();
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let mut failures = Vec::new();
    for sets in &combos {
        let result = prepare(&gpu, &pipeline, sets, &scene, (64, 48)).and_then(|p| {
            p.renderer.render()?;
            Ok(p.image()?)
        });
        match result {
            Ok(image) => {
                // Hair and head cover part of the frame: not one flat colour.
                let first = image.get_pixel(0, 0);
                if image.pixels().all(|p| p == first) {
                    failures.push(format!("{sets:?}: a flat image"));
                }
            }
            Err(e) => failures.push(format!("{sets:?}: {e}")),
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} combinations failed:\n{}",
        failures.len(),
        combos.len(),
        failures.join("\n")
    );
}
