//! lavapipe's loop budget (65,535 laps per group of 8 invocations, shared
//! by all their loops, then every loop ends silently; docs/design.md, "Loop
//! budgets") against the linked-list resolve, the exact reference of A/B
//! runs: a pixel whose list it could not resolve is counted in
//! `list_counter`'s `incomplete` word and fails the frame.

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_gpu::{FrameReport, Gpu};
use plait_tests::{open_gpu, repo_root};

/// `strands` identical straight strands in front of the small scene's head,
/// across the screen: every pixel of their row holds one fragment of each.
fn stacked(strands: usize) -> SceneData {
    let path = repo_root().join("examples/scenes/small.toml");
    let mut scene = SceneData::load(Some(&path)).expect("examples/scenes/small.toml loads");
    let mut hair = plait_hair::Strands::new();
    let points = [Vec3::new(-1.2, 0.3, 2.5), Vec3::new(1.2, 0.3, 2.5)];
    for _ in 0..strands {
        hair.push_strand(&points, |_| 0.01, |_| 0.5, Vec3::new(0.9, 0.2, 0.1));
    }
    scene.strands = hair;
    scene
}

/// The linked-list pipeline's frame report at 8x6, every strand drawn. The
/// pool is sized by hand (a user's cap: no sizing frame, which would fail
/// the cut frame in `prepare` already).
fn resolve(gpu: &Gpu, scene: &SceneData) -> FrameReport {
    let sets = [
        "techniques.geometry=strands".to_string(),
        "params.nodes_per_pixel=20000".to_string(),
    ];
    let pipeline = repo_root().join("pipelines/linked_list.toml");
    let prepared = prepare(gpu, &pipeline, &sets, scene, (8, 6)).expect("prepares");
    prepared.render_unchecked().expect("renders")
}

fn incomplete(report: &FrameReport) -> u64 {
    let [c] = report.overflow.as_slice() else {
        panic!("one counter: {:?}", report.overflow)
    };
    assert_eq!(c.counter, "list_counter");
    assert_eq!(c.last_pass, "list_resolve", "the resolve writes it last");
    assert_eq!(c.dropped, 0, "the pool holds every fragment");
    c.incomplete
}

/// 3,000 fragments a pixel resolve (the heap keeps the nearest 256 in
/// ~2 laps a fragment); 40,000 are past the budget in the walk alone, and
/// the frame fails naming the pass. A driver without the limit (the probe,
/// `Gpu::loop_budget`, finds none on Mesa 25's lavapipe) resolves both.
#[test]
fn a_list_past_the_loop_budget_fails_the_frame() {
    let (_lock, gpu) = open_gpu();
    let fits = resolve(&gpu, &stacked(3_000));
    assert_eq!(incomplete(&fits), 0);
    plait::overflow::check_frame(&fits).expect("a resolved frame passes");

    let cut = resolve(&gpu, &stacked(40_000));
    let count = incomplete(&cut);
    eprintln!("40,000 fragments a pixel: {count} pixels unresolved");
    let budget = gpu.loop_budget().expect("the loop-budget probe runs");
    eprintln!("driver's loop budget: {budget:?}");
    if budget.is_some() {
        assert!(
            count > 0,
            "a driver with a loop budget cannot walk 40,000 fragments"
        );
        let e = plait::overflow::check_frame(&cut)
            .expect_err("a frame with unresolved pixels fails")
            .to_string();
        assert!(
            e.contains("shader invocations of pass `list_resolve` could not finish"),
            "{e}"
        );
    } else {
        assert_eq!(count, 0);
    }
}

/// The probe the loop-budget tests branch on: a driver that cuts loops cuts
/// the probe's near lavapipe's 65,535 laps (one loop, so the group's whole
/// budget); one that does not runs all of them. A probe that reported a cut
/// where there is none, or none where there is one, would send the tests
/// above down the wrong branch — where their frame's own count disagrees.
#[test]
fn the_loop_budget_probe_measures_the_drivers_budget() {
    let (_lock, gpu) = open_gpu();
    let budget = gpu.loop_budget().expect("the probe runs");
    eprintln!("{}: loop budget {budget:?}", plait_tests::driver());
    if let Some(laps) = budget {
        assert!(
            (60_000..plait_gpu::loop_budget::PROBE_LAPS).contains(&laps),
            "a cut near lavapipe's 65,535 laps, got {laps}"
        );
    }
}
