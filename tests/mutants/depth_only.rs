//! plait::light_share, the library of the depth-only self-shadow maps
//! (modified shadow map, TressFX), against its formulas on the CPU at known
//! texture coordinates, depths and map sizes
//! (`tests/fixtures/light_share_cases.wgsl`): the light texel's sides from
//! the frame's inverse light matrix, a strand's share of its texel
//! ½ (min(w / tx, 1) + min(w / ty, 1)) (1 with strand coverage off), and
//! the strands a light ray crosses per unit of depth, ρ · w (ρ · the sides'
//! harmonic mean with coverage off). The ground-shadow tests
//! (`tests/shadow_coverage.rs`) hold the maps' integrals where TressFX's
//! one-fibre floor does not bind and the texel's two sides are alike, so a
//! side 10 % off, the floor's share or the harmonic mean with one side
//! dropped passed them.

use glam::{Mat4, Vec2, Vec3};
use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (32, 2);
const DENSITY: f32 = 1000.0;

/// The fixture's rows, with `sets`, and the frame's inverse light matrix.
fn cases(sets: &[&str]) -> (Vec<[f32; 4]>, Vec<[f32; 4]>, Mat4) {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/light_share_cases.toml");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let prepared = prepare(&gpu, &pipeline, &sets, &scene, SIZE)
        .unwrap_or_else(|e| panic!("light_share_cases prepares: {e}"));
    prepared.render().expect("renders");
    let read = prepared.read_resource("cases").expect("cases");
    let texels: Vec<[f32; 4]> = read
        .bytes
        .chunks_exact(16)
        .map(|t| {
            std::array::from_fn(|c| f32::from_le_bytes(t[4 * c..4 * c + 4].try_into().unwrap()))
        })
        .collect();
    let inverse = Mat4::from_cols_array_2d(&scene.frame(SIZE, 0).light_inv_view_proj);
    let (row0, row1) = texels.split_at(SIZE.0 as usize);
    (row0.to_vec(), row1.to_vec(), inverse)
}

/// The fixture's case `x`: (uv, stored depth).
fn case(x: usize) -> (Vec2, f32) {
    let x = x as f32;
    (Vec2::new(0.1 + 0.025 * x, 0.85 - 0.02 * x), 0.2 + 0.02 * x)
}

/// The light texel's sides in world units (plait::light_share::light_texel).
fn texel(inverse: Mat4, uv: Vec2, stored: f32, size: Vec2) -> Vec2 {
    let at =
        |uv: Vec2| inverse.project_point3(Vec3::new(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, stored));
    let p = at(uv);
    Vec2::new(
        (at(uv + Vec2::new(1.0 / size.x, 0.0)) - p).length(),
        (at(uv + Vec2::new(0.0, 1.0 / size.y)) - p).length(),
    )
}

/// The largest relative difference of the GPU's values from the CPU's.
fn worst(coverage: bool) -> f64 {
    let sets: &[&str] = if coverage {
        &[]
    } else {
        &["params.strand_coverage=false"]
    };
    let (gpu, inputs, inverse) = cases(sets);
    let (width, convention) = (inputs[0][2], inputs[0][3]);
    assert_eq!(
        convention,
        if coverage { 1.0 } else { 0.0 },
        "the coverage convention"
    );
    let (mut worst, mut floors, mut uneven) = (0.0f64, 0, 0);
    for (x, (got, input)) in gpu.iter().zip(&inputs).enumerate() {
        let (uv, stored) = case(x);
        let size = Vec2::new(input[0], input[1]);
        let t = texel(inverse, uv, stored, size);
        let (share, per_depth) = if coverage {
            let share = 0.5 * ((width / t.x).min(1.0) + (width / t.y).min(1.0));
            (share, DENSITY * width)
        } else {
            (1.0, DENSITY * 2.0 / (1.0 / t.x + 1.0 / t.y))
        };
        floors += usize::from(width > t.x.max(t.y));
        uneven += usize::from((t.x / t.y - 1.0).abs() > 0.3);
        let want = [t.x, t.y, share, per_depth];
        for c in 0..4 {
            let e = f64::from((got[c] - want[c]).abs() / want[c].abs().max(1e-12));
            worst = worst.max(e);
        }
    }
    eprintln!(
        "strand coverage {coverage}: width {width}, {floors} of {} cases with the width past both sides, \
         {uneven} with sides more than 1.3× apart; largest relative difference {worst:e}",
        gpu.len()
    );
    assert!(
        uneven > 0,
        "every case's texel is square: a side could be swapped unseen"
    );
    assert!(
        floors > 0 && floors < gpu.len(),
        "the width should be past both sides of some texels and not of others"
    );
    worst
}

/// Kills, in `shaders/lib/light_share.wgsl`: the texel's y side scaled
/// (20:56 ×0.9, ×1.1), the share's terms (47:12, 47:25, 47:52), the share
/// with coverage off (43:16) and the harmonic mean with a side dropped
/// (59:38).
#[test]
fn light_share_matches_its_formulas_with_and_without_strand_coverage() {
    let on = worst(true);
    let off = worst(false);
    // f32 unprojection at these depths: measured (printed) well below.
    assert!(on < 1e-3, "strand coverage on: {on:e} from the formulas");
    assert!(off < 1e-3, "strand coverage off: {off:e} from the formulas");
}
