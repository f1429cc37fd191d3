//! GPU tier: the compute rasterizer (`techniques/transparency/compute_raster`)
//! draws what the hardware-rasterized hair draws, by the one strand-coverage
//! convention: isolated strands, where no order matters, cover the same
//! total alpha at the same place as linked_list's rasterized lines (its
//! analytic coverage spreads each line's one fragment per column over the
//! two pixels the line straddles, keeping the sum).

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{open_gpu, repo_root, strands_subset};

const SIZE: (u32, u32) = (96, 72);

/// The small scene keeping the strands `keep` selects.
fn scene(keep: impl Fn(usize) -> bool) -> SceneData {
    let path = repo_root().join("examples/scenes/small.toml");
    let mut data = SceneData::load(Some(&path)).expect("examples/scenes/small.toml loads");
    data.strands = strands_subset(&data.strands, keep);
    data
}

/// Σα of the premultiplied hair image (`hair`) and its α-weighted centroid.
fn hair_alpha(gpu: &Gpu, pipeline: &str, sets: &[&str], scene: &SceneData) -> (f64, [f64; 2]) {
    let mut all: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    all.push("pipeline.outputs=[\"final\", \"hair\"]".into());
    let prepared = prepare(gpu, &repo_root().join(pipeline), &all, scene, SIZE)
        .unwrap_or_else(|e| panic!("preparing {pipeline}: {e}"));
    prepared.renderer.render().expect("renders");
    let hair = prepared.renderer.read_resource("hair").expect("hair");
    let (mut sum, mut x, mut y) = (0.0, 0.0, 0.0);
    for i in 0..(hair.width * hair.height) as usize {
        let a = f64::from(hair.texel(i)[3]);
        sum += a;
        x += a * (i % hair.width as usize) as f64;
        y += a * (i / hair.width as usize) as f64;
    }
    assert!(sum > 0.0, "{pipeline}: no hair drawn");
    (sum, [x / sum, y / sum])
}

#[test]
fn isolated_strands_cover_what_rasterized_lines_cover() {
    let (_lock, gpu) = open_gpu();
    // A handful of strands far apart in the groom: they rarely overlap.
    let sparse = scene(|s| s % 97 == 5);
    let (raster, raster_at) = hair_alpha(&gpu, "pipelines/linked_list.toml", &[], &sparse);
    let (compute, compute_at) = hair_alpha(&gpu, "pipelines/compute_raster.toml", &[], &sparse);
    let ratio = compute / raster;
    let shift = ((compute_at[0] - raster_at[0]).powi(2) + (compute_at[1] - raster_at[1]).powi(2)).sqrt();
    println!("Σα raster {raster:.3}, compute {compute:.3} (× {ratio:.4}); centroid shift {shift:.3} px");
    assert!((ratio - 1.0).abs() < 0.03, "Σα {compute} against {raster}");
    assert!(shift < 0.1, "the hair moved by {shift} px");
}
