//! `self_shadow = ray_traced` against `exact` on the small scene, through
//! the visibility probe `plait ab` uses (`plait::probe`, the same 16×16 rays
//! × 48 depths). exact counts the fragments of a light texel in front of a
//! point, so its count is the strands' shares averaged over the texel; the
//! ray counts the strands the point's own ray crosses. Their difference is
//! the texel's averaging, so exact converges to ray_traced as its light map
//! gets finer: measured on lavapipe, mean |ΔV| of ray_traced against exact
//! 0.0494 at light_size 512 and 0.0252 at 1024, where exact at 512 against
//! exact at 1024 is 0.0253 (`plait ab … --sweep
//! techniques.self_shadow=exact,ray_traced --sweep
//! params.light_size=256,512,1024`, reference exact at 1024).

use plait::probe::{ProbeGrid, Probed, probe_visibility, visibility_error};
use plait::session::SceneData;
use plait::source::PipelineSource;
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (160, 120);

fn probed(gpu: &plait_gpu::Gpu, scene: &SceneData, grid: &ProbeGrid, sets: &[&str]) -> Probed {
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let source = PipelineSource::new(&pipeline, &sets);
    probe_visibility(gpu, &source, scene, SIZE, grid)
        .unwrap_or_else(|e| panic!("probing {sets:?}: {e}"))
        .unwrap_or_else(|| panic!("{sets:?} has no self-shadow provider"))
}

#[test]
fn exact_converges_to_ray_traced_as_its_light_map_gets_finer() {
    let (_lock, gpu) = open_gpu();
    assert!(
        gpu.capabilities.ray_query,
        "adapter {} has no ray queries: the test command runs on Mesa 25's lavapipe (bash scripts/ensure-vulkan.sh installs it)",
        gpu.support.describe()
    );
    let path = repo_root().join("examples/scenes/small.toml");
    let scene = SceneData::load(Some(&path)).expect("small scene");
    let grid = ProbeGrid::through_hair(&scene, (16, 16), 48);
    let exact = |size: &str| {
        let light = format!("params.light_size={size}");
        probed(
            &gpu,
            &scene,
            &grid,
            &["techniques.self_shadow=exact", &light],
        )
    };
    let (coarse, fine) = (exact("512"), exact("1024"));
    let traced = probed(&gpu, &scene, &grid, &["techniques.self_shadow=ray_traced"]);
    let error = |reference: &Probed, variant: &Probed| {
        visibility_error(&grid, reference, variant).mean_abs_error
    };
    let (to_coarse, to_fine) = (error(&coarse, &traced), error(&fine, &traced));
    let exact_step = error(&fine, &coarse);
    eprintln!(
        "mean |ΔV|: ray_traced vs exact@512 {to_coarse:.4}, vs exact@1024 {to_fine:.4}; exact@512 vs exact@1024 {exact_step:.4}"
    );
    // Halving the texel halves the difference (0.0494 → 0.0252 measured) …
    assert!(to_fine < 0.7 * to_coarse, "{to_fine} vs {to_coarse}");
    // … and ray_traced is as near exact@1024 as exact@512 is.
    assert!(to_fine <= 1.1 * exact_step, "{to_fine} vs {exact_step}");
}
