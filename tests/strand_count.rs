//! The self_shadow point's optional strand counts (`hair_strands_along_light`,
//! techniques/self_shadow/point.toml `[wgsl.optional]`): x, the strands
//! toward the light — what Zinke et al. 2008 §4's global multiple
//! scattering attenuates and spreads by — and y, the strands behind the
//! point along the light's ray — what plait's local back-scattering counts —
//! checked for every provider against a closed form.
//!
//! A slab of `LAYERS` horizontal layers of parallel strands along x, each
//! layer `PER_LAYER` strands of width `WIDTH` spaced `SPACING` apart in z;
//! the light slanted along the strands' axis only, so every layer seen from
//! the light is the same set of parallel bands of width `WIDTH` every
//! `SPACING`. A ray from the light then crosses a layer's strands with
//! expected count `WIDTH / SPACING` (a strand's share of the texels it
//! crosses, summed — the convention of every provider: "one strand across
//! the ray: n = 1"), so a point below k layers has n = k · WIDTH / SPACING,
//! whatever the light map's resolution. Probed on a grid of points from the
//! light over the slab's interior (`plait::probe::probe_with`,
//! tests/fixtures/strands_probe.wgsl), away from the layers by more than the
//! self-shadow bias, and averaged per k (one point's texel can hold one
//! strand or two; the mean over the grid is the expectation).

use plait::probe::{ProbeGrid, probe_with};
use plait::session::SceneData;
use plait::source::PipelineSource;
use plait_tests::{open_gpu, repo_root};

const LAYERS: usize = 4;
/// The top layer's height; layer k is at `TOP − k · GAP`.
const TOP: f32 = 0.4;
const GAP: f32 = 0.1;
const PER_LAYER: usize = 50;
const SPACING: f32 = 0.02;
const WIDTH: f32 = 0.005;
/// Half the strands' length along x.
const HALF_LENGTH: f32 = 0.5;
/// The light travels down, slanted along x (the strands' axis) only.
const LIGHT: [f32; 3] = [-0.3, -1.0, 0.0];
const SIZE: (u32, u32) = (64, 48);

fn slab() -> SceneData {
    let mut strands = Vec::new();
    for k in 0..LAYERS {
        let y = TOP - GAP * k as f32;
        for i in 0..PER_LAYER {
            // Each layer shifted by a quarter spacing: the layers do not
            // line up behind each other (the count is the same either way).
            let z = SPACING * (i as f32 + 0.25 * k as f32) - 0.5 * SPACING * PER_LAYER as f32;
            strands.push(
                (0..=8)
                    .map(|s| glam::Vec3::new(HALF_LENGTH * (s as f32 / 4.0 - 1.0), y, z))
                    .collect(),
            );
        }
    }
    let light = glam::Vec3::from(LIGHT);
    plait_tests::strands_under_light("strand_count.toml", &strands, WIDTH, light)
}

/// Per k = 0..=LAYERS (layers above the point): the provider's mean count
/// over the interior probe points below k layers, and how many there were.
fn mean_counts(technique: &str, extra: &[String], shader: &str) -> Vec<(f64, usize)> {
    let (_lock, gpu) = open_gpu();
    let scene = slab();
    // Several rays per light texel (64² over the slab): the mean over the
    // rays is the mean over the texels, which is the expectation; coarser
    // rays beat against the strands' spacing (measured 4 % off at 24²).
    let mut grid = ProbeGrid::through_hair(&scene, (96, 96), 40);
    // The middle half of the slab seen from the light: every ray through it
    // stays inside the slab (|x|, |z| ≤ 0.25 + the slant's 0.12) at all depths.
    let (u0, u1) = (grid.uv0, grid.uv1);
    let inner = |a: f32, b: f32, t: f32| a + (b - a) * t;
    grid.uv0 = [inner(u0[0], u1[0], 0.25), inner(u0[1], u1[1], 0.25)];
    grid.uv1 = [inner(u0[0], u1[0], 0.75), inner(u0[1], u1[1], 0.75)];
    let mut sets = vec![format!("techniques.self_shadow={technique}")];
    sets.extend(extra.iter().cloned());
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let source = PipelineSource::new(&pipeline, &sets);
    let probed = probe_with(&gpu, &source, &scene, SIZE, &grid, shader)
        .unwrap_or_else(|e| panic!("probing {technique}: {e}"))
        .unwrap_or_else(|| panic!("{technique} has no self-shadow provider"));
    let frame = scene.frame(SIZE, 0);
    let inverse = glam::Mat4::from_cols_array_2d(&frame.light_inv_view_proj);
    let mut sums = [(0.0, 0usize); LAYERS + 1];
    for r in 0..grid.ray_count() as u32 {
        let uv = grid.ray_uv(r);
        for d in 0..grid.depths {
            let ndc = glam::Vec3::new(uv[0] * 2.0 - 1.0, 1.0 - uv[1] * 2.0, grid.depth(d));
            let world = inverse.project_point3(ndc);
            let Some(k) = layers_above(world) else {
                continue;
            };
            let value = probed.values[(r * grid.depths + d) as usize] as f64;
            sums[k].0 += value;
            sums[k].1 += 1;
        }
    }
    sums.iter()
        .map(|&(sum, n)| (sum / n.max(1) as f64, n))
        .collect()
}

/// The layers above `world` when it is inside the slab's interior and at
/// least a quarter gap from every layer (well past the self-shadow bias and
/// a density voxel's reach); `None` otherwise.
fn layers_above(world: glam::Vec3) -> Option<usize> {
    let inside = world.x.abs() <= 0.4 * HALF_LENGTH && world.z.abs() <= 0.2;
    let bottom = TOP - GAP * (LAYERS - 1) as f32;
    let in_range = world.y < TOP + 0.5 * GAP && world.y > bottom - 0.5 * GAP;
    let layer_heights = (0..LAYERS).map(|k| TOP - GAP * k as f32);
    let clear = layer_heights
        .clone()
        .all(|y| (world.y - y).abs() >= 0.25 * GAP);
    (inside && in_range && clear).then(|| layer_heights.filter(|&y| y > world.y).count())
}

/// Expected strands crossed per layer.
const PER_LAYER_COUNT: f64 = (WIDTH / SPACING) as f64;

/// A provider under test: its sets, the allowed |mean / closed form − 1|
/// where the closed form is not 0, the allowed |mean| where it is (n above
/// the slab, m below it), and whether the layers between are asserted (else
/// only k = 0 and k = LAYERS).
struct Provider {
    technique: &'static str,
    sets: Vec<String>,
    tolerance: f64,
    above: f64,
    below: f64,
    between: bool,
}

fn providers() -> Vec<Provider> {
    let light_64 = || vec!["params.light_size=64".to_owned()];
    let provider = |technique, sets, between| Provider {
        technique,
        sets,
        tolerance: 0.05,
        above: 0.01,
        below: 0.01,
        between,
    };
    // Deep opacity maps interpolate the count linearly inside a layer
    // (Yuksel & Keyser 2008 §3): between the strand layers their count is
    // that interpolation, not the closed form, so only the count behind all
    // the hair is asserted — with layers ending at 0.05, 0.15, 0.30 (the
    // slab is 0.31 deep along the light), every point behind it is past the
    // last layer's end and reads the prefix sum of all of them — and, for m,
    // the whole slab behind a point above it (0 in front of it, that sum
    // beyond it) and, below it, m = the slab's total less n there: what n
    // misses of the total (its ratio 0.971 below the slab), so m is held to
    // that same 5 % of the slab's count (measured 0.018 strands).
    let mut dom = light_64();
    dom.push("params.dom_layer_size=0.05".to_owned());
    vec![
        provider("exact", light_64(), true),
        provider("occupancy", light_64(), true),
        provider("occupancy_no_slab", light_64(), true),
        Provider {
            below: 0.05 * LAYERS as f64 * PER_LAYER_COUNT,
            ..provider("deep_opacity", dom, false)
        },
        provider("opacity_shadow_maps", light_64(), true),
        provider("density_volume", vec![], true),
        // One ray per point through the strands' acceleration structure
        // (tests/ray_traced_strands.rs holds one strand and the mutations).
        provider("ray_traced", vec![], true),
        // Four rays per point, jittered over the pixel's footprint: their
        // mean count, the same in the mean over the probe points (issue 40:
        // the sum not divided by the ray count, ray_traced's
        // self_shadow.wgsl 116:14, read 4 × 4 = 16 times the closed form).
        provider("ray_traced", vec!["params.shadow_rays=4".to_owned()], true),
        // The volume converges with its resolution (the trilinear lookup
        // smears the count over a voxel either side: at 8³, voxels wider
        // than the layers' gap, 0.78 below the first layer): at 64³ it
        // holds to 1% (measured 0.998–1.000).
        Provider {
            tolerance: 0.01,
            ..provider(
                "density_volume",
                vec!["params.density_resolution=64".to_owned()],
                true,
            )
        },
    ]
}

/// The two counts of `hair_strands_along_light`: its probe fixture, and
/// the closed form below k layers in layers' worth of strands.
struct Count {
    name: &'static str,
    shader: &'static str,
    layers: fn(usize) -> usize,
}

const COUNTS: [Count; 2] = [
    Count {
        name: "n (toward the light)",
        shader: "tests/fixtures/strands_probe.wgsl",
        layers: |k| k,
    },
    Count {
        name: "m (behind the point)",
        shader: "tests/fixtures/strands_behind_probe.wgsl",
        layers: |k| LAYERS - k,
    },
];

/// Every provider of the strand counts: its mean over the points below k
/// layers within the stated fraction of the closed form — n = k · WIDTH /
/// SPACING toward the light, m = (LAYERS − k) · WIDTH / SPACING behind the
/// point — and ≈ 0 where the closed form is 0 (n above the slab, m below
/// it). Measured on lavapipe: n ratios 0.973 (opacity_shadow_maps, k = 1)
/// to 1.009 (exact, k = 3); density_volume 0.987–1.006 at its default 32³
/// and 0.998–1.000 at 64³ (16³: 0.969–0.996; 8³: 0.785–1.027, not
/// asserted); deep_opacity behind the slab 0.971 (between the
/// layers, not asserted: 0.794, 0.970, 1.078); 0 above the slab for all.
/// m (issue 43): ratios 0.978 (occupancy, opacity_shadow_maps: k = 3) to
/// 1.039 (ray_traced, k = 3), 0 below the slab for all but deep_opacity
/// (0.018, what its n misses of the total there; between its layers not
/// asserted: 0.98, 0.90, 0.52).
/// Checked to fail: occupancy returning 0 (ratio 0), or its opacity
/// n · shadow_weight instead of n (ratio 0.15 with the pipeline's 0.15),
/// and density_volume's count scaled by 0.97 (64³: ratio 0.968–0.970);
/// occupancy's m as the texel's total (m ratio 1.33–3.99, 1.0 below the
/// slab) and exact's m as its count in front of `light_behind`'s x (0 above
/// the slab, 1.0 below it). Not caught here: m counted from the point
/// rather than past its own strand — the probe points lie a quarter gap
/// from every strand, where the two agree.
#[test]
fn every_provider_counts_the_strands_toward_the_light() {
    let only = std::env::var("PLAIT_COUNT_ONLY").ok();
    let mut report = Vec::new();
    let mut failures = Vec::new();
    for p in providers() {
        let technique = p.technique;
        if only.as_deref().is_some_and(|o| o != technique) {
            continue;
        }
        for count in &COUNTS {
            let means = mean_counts(technique, &p.sets, count.shader);
            for (k, &(mean, n)) in means.iter().enumerate() {
                let layers = (count.layers)(k);
                let expected = layers as f64 * PER_LAYER_COUNT;
                // The ends (no layer on one side, all of them on the other)
                // always; between them where the provider resolves layers.
                let asserted = k == 0 || k == LAYERS || p.between;
                let ok = !asserted
                    || if layers == 0 {
                        mean.abs() <= if k == 0 { p.above } else { p.below }
                    } else {
                        (mean / expected - 1.0).abs() <= p.tolerance
                    };
                let line = format!(
                    "{technique}: {} below {k} layers: mean {mean:.4} over {n} points, closed form {expected:.4}{}{}",
                    count.name,
                    if layers == 0 {
                        String::new()
                    } else {
                        format!(", ratio {:.4}", mean / expected)
                    },
                    if asserted { "" } else { " (not asserted)" }
                );
                assert!(n >= 20, "{line}: too few probe points to average");
                if !ok {
                    failures.push(line.clone());
                }
                report.push(line);
            }
        }
    }
    println!("{}", report.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
