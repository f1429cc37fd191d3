//! Ambient occlusion's deep-opacity directions (Xing et al. 2012 §4) weigh a
//! strand by its share of a direction's texel, as the self-shadow maps do
//! (issue 47, item 4): thinner strands occlude proportionally less.
//!
//! One direction (`ao_directions = 1`), so a vertex's visibility is the deep
//! opacity provider's exp(−w · Σ shares in front) itself, not a mean over
//! directions: Σ −ln(visibility) over the vertices is w · Σ shares, and
//! halving every strand's width (all thinner than a texel of a 64² map over
//! the small groom's bounding sphere: whole texels block 12.7× what the
//! shares do here, measured) halves it. With whole
//! texels (`strand_coverage = false`, Xing et al.'s counts) width does not
//! enter, and the same sum stays.

use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (64, 48);

/// Σ −ln(visibility) over the hair vertices, the strands' widths scaled by
/// `scale`.
fn optical_depth(gpu: &Gpu, scale: f32, sets: &[&str]) -> f64 {
    let mut scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    scene.strands.thickness.iter_mut().for_each(|t| *t *= scale);
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let mut all = vec![
        "techniques.ambient_occlusion=deep_opacity_directions".to_owned(),
        "params.ao_directions=1".to_owned(),
        "params.ao_map_size=64".to_owned(),
        "params.ao_shadow_weight=0.5".to_owned(),
    ];
    all.extend(sets.iter().map(|s| s.to_string()));
    let prepared = prepare(gpu, &pipeline, &all, &scene, SIZE).unwrap_or_else(|e| panic!("{e}"));
    prepared.render().expect("renders");
    let bytes = prepared.read_buffer("ao_vertex").expect("ao_vertex");
    let n = scene.strands.points.len();
    let ao: Vec<f32> = bytes
        .chunks_exact(4)
        .take(n)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    assert!(
        ao.iter().all(|a| (0.0..=1.0).contains(a)),
        "visibility in [0, 1]"
    );
    ao.iter().map(|&a| -(a.max(1e-6) as f64).ln()).sum()
}

/// Halving every strand's width halves the optical depth the occlusion
/// directions see (within 2 %: shares are kept to 1/4096 of a texel);
/// without coverage the two widths give the same occlusion.
#[test]
fn occlusion_directions_follow_strand_width() {
    let (_lock, gpu) = open_gpu();
    let full = optical_depth(&gpu, 1.0, &[]);
    let half = optical_depth(&gpu, 0.5, &[]);
    let off_full = optical_depth(&gpu, 1.0, &["params.strand_coverage=false"]);
    let off_half = optical_depth(&gpu, 0.5, &["params.strand_coverage=false"]);
    let (ratio, ratio_off) = (full / half, off_full / off_half);
    eprintln!(
        "Σ −ln AO: width ×1 {full:.3}, ×½ {half:.3}: ratio {ratio:.4}; whole texels {off_full:.3} / {off_half:.3}: ratio {ratio_off:.4}"
    );
    assert!(full > 1.0, "the groom occludes itself: {full}");
    assert!((ratio - 2.0).abs() < 0.04, "ratio {ratio:.4}, not 2");
    assert!(
        (ratio_off - 1.0).abs() < 0.01,
        "whole texels: ratio {ratio_off:.4}"
    );
    assert!(off_full > full, "a whole texel blocks more than a share");
}
