//! `self_shadow/density_clustering`: the lookup's relative depth in a
//! texel whose hair spans less than its floor of 1e-9 in light depth, where
//! no rendered scene can place a depth (tests/fixtures/dc_lookup.toml).

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

/// Fixed point of the clusters' depth sums (2¹⁸) and a whole texel's count
/// (MAP_SHARE_SCALE), as `shaders/passes/density_clustering.wgsl` writes them.
const SCALE: f64 = 262_144.0;
const UNIT: u32 = 4096;

/// The five strands' light depths, 2⁻⁹ + k · 2⁻³² (one f32 step apart).
fn depth(k: u32) -> f32 {
    f32::from_bits(0x3B00_0000 + k)
}

/// z of a depth in the texel of range `near..far`, as the pass's
/// `map_texel` (and the lookup) compute it, in f32: relative to the range,
/// or to 1e-9 where the range is narrower.
fn relative(d: f32, near: f32, far: f32) -> f32 {
    (d - near) / (far - near).max(1e-9)
}

/// The pass's words for whole-texel fragments at `z`: stage 0's slices,
/// then one k-means step to the nearest mean (`dc_iterations = 1`).
fn cluster_words(z: &[f32]) -> [[u32; 3]; 4] {
    let add = |assign: &dyn Fn(f32) -> usize| {
        let mut words = [[0u32; 3]; 4];
        for &z in z {
            let w = &mut words[assign(z)];
            w[0] += UNIT;
            // WGSL's round takes a half to the even neighbour.
            w[1] += (z * SCALE as f32).round_ties_even() as u32;
            w[2] += (z * z * SCALE as f32).round_ties_even() as u32;
        }
        words
    };
    let slice = |z: f32| ((z * 4.0) as usize).min(3);
    let stage0 = add(&slice);
    let nearest = |z: f32| {
        let mut best = (slice(z), 2.0f32);
        for (k, w) in stage0.iter().enumerate().filter(|(_, w)| w[0] > 0) {
            let mean = w[1] as f32 / (SCALE as f32 * w[0] as f32 / UNIT as f32);
            if (z - mean).abs() < best.1 {
                best = (k, (z - mean).abs());
            }
        }
        best.0
    };
    add(&nearest)
}

/// The fragments in front of relative depth `z` by the clusters' bins
/// (`cluster_count`'s sum: each cluster a uniform bin of its count over
/// mean ± √3 σ, a step at its mean when narrower than 1e-5).
fn count_in_front(words: &[[u32; 3]; 4], z: f64) -> f64 {
    let mut total = 0.0;
    for w in words.iter().filter(|w| w[0] > 0) {
        let n = f64::from(w[0]) / f64::from(UNIT);
        let mean = f64::from(w[1]) / (SCALE * n);
        let sigma = (f64::from(w[2]) / (SCALE * n) - mean * mean)
            .max(0.0)
            .sqrt();
        let half = 1.732_050_8 * sigma;
        total += if half < 1e-5 {
            if z > mean { n } else { 0.0 }
        } else {
            n * ((z - (mean - half)) / (2.0 * half)).clamp(0.0, 1.0)
        };
    }
    total
}

/// Five whole-texel strands one f32 step apart in light depth at 2⁻⁹ (a
/// range of 9.3e-10, below the 1e-9 floor): the clusters the fixture writes
/// are the pass's for them (checked here from its arithmetic: cluster 0
/// holds z = 0 and 0.2328, a bin over [−0.085, 0.318]), and the lookup at
/// the first strand's depth, the second's and one step past the last reads
/// the hair in front as those bins place it with the pass's z — 0.4227,
/// 1.5773 and 5 (within 1e-3). At the three middle strands' depths each
/// lookup lands on a one-strand cluster's mean, a tie its rounding decides,
/// so they are not read. Kills, in
/// `techniques/self_shadow/density_clustering/self_shadow.wgsl`, the floor
/// max(range, 1e-9) → 0.9e-9 (36:56 ×0.9: z = 0.2587 at the second strand,
/// 1.6625) and → 1.1e-9 (×1.1: z = 0.2117, 1.4724).
#[test]
fn a_texel_thinner_than_the_depth_floor_looks_up_the_passs_relative_depth() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/dc_lookup.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (4, 4)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let read = |name: &str| -> Vec<[u8; 4]> {
        let bytes = prepared.read_buffer(name).expect(name);
        bytes
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect()
    };
    let words: Vec<u32> = read("dc_clusters")
        .into_iter()
        .map(u32::from_le_bytes)
        .collect();
    let got: Vec<f32> = read("counts").into_iter().map(f32::from_le_bytes).collect();
    let (near, far) = (depth(0), depth(4));
    assert!(
        far - near < 1e-9,
        "the range {} must be below the floor",
        far - near
    );
    let z: Vec<f32> = (0..5).map(|k| relative(depth(k), near, far)).collect();
    let pass = cluster_words(&z);
    assert_eq!(
        words,
        pass.concat(),
        "the fixture's clusters against the pass's for z {z:?}"
    );
    let want: Vec<f64> = [0, 1, 5]
        .map(|k| count_in_front(&pass, f64::from(relative(depth(k), near, far))))
        .to_vec();
    eprintln!("hair in front at strands 0, 1 and past 4: GPU {got:?}, the pass's z {want:?}");
    for (g, w) in got.iter().zip(&want) {
        assert!(
            (f64::from(*g) - w).abs() < 1e-3,
            "GPU {got:?}, expected {want:?}"
        );
    }
}
