//! compute_raster shaded per fragment (`shading_space = fragment`): its
//! blend pass shades each covered pixel about the smooth curve's tangent
//! (`plait::strand_curve::strand_curve_tangent`, the cubic Hermite piece
//! through the strand's points), as the rasterized hair draw does
//! (`strand_curve_tangent_lerp`, measured against the spline by
//! `tests/curve_tangent.rs`). The gallery's compute_raster shades in strand
//! space, whose shading points also read the curve's tangent, so nothing
//! else renders this path: with the tangent's two ends interpolated
//! linearly (`curve_unit(mix(t0, t1, u))`) every other test passes.
//!
//! One strand, `tests/curve_tangent.rs`'s coarse wave facing the camera
//! (each segment turns by tens of degrees; the linear interpolation is up
//! to ~10° from the spline's tangent there), lit from nearly along the
//! image plane so that the diffuse term sin(T, L) follows the tangent
//! steeply. Where both draw it at least a fifth opaque, compute_raster's
//! hair radiance (premultiplied colour ÷ alpha) is linked_list's, pixel by
//! pixel.

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{coarse_wave, one_strand_scene, open_gpu, repo_root};

use crate::SIDE_LIT;

const SIZE: (u32, u32) = (160, 120);

/// The wave of `tests/curve_tangent.rs` (`plait_tests::coarse_wave`), wider
/// (about a pixel: the camera sees 4.3 world units over 160 pixels) so that
/// most of its pixels are well covered, lit from nearly along the image plane.
fn scene() -> SceneData {
    one_strand_scene(
        "compute_raster_tangent.toml",
        SIDE_LIT,
        &coarse_wave(),
        0.02,
        0.8,
    )
}

/// The premultiplied `hair` image of `pipeline` shaded per fragment, with
/// no self-shadow (one strand: nothing to shadow but itself).
fn hair(gpu: &Gpu, pipeline: &str, scene: &SceneData) -> Vec<[f32; 4]> {
    let sets = [
        "techniques.shading_space=fragment".to_owned(),
        "techniques.self_shadow=none".to_owned(),
        "pipeline.outputs=[\"final\", \"hair\"]".to_owned(),
    ];
    let prepared = prepare(gpu, &repo_root().join(pipeline), &sets, scene, SIZE)
        .unwrap_or_else(|e| panic!("preparing {pipeline}: {e}"));
    prepared.render().expect("renders");
    let hair = prepared.read_resource("hair").expect("hair");
    (0..(hair.width * hair.height) as usize)
        .map(|i| hair.texel(i))
        .collect()
}

/// Kills, in `shaders/lib/strand_curve.wgsl`, `strand_curve_tangent`
/// returning the ends' tangents interpolated linearly (the survivor issue
/// 40 names) and the Hermite piece's terms dropped or their signs changed.
#[test]
fn compute_raster_shades_fragments_about_the_curves_tangent() {
    let (_lock, gpu) = open_gpu();
    let scene = scene();
    let raster = hair(&gpu, "pipelines/linked_list.toml", &scene);
    let compute = hair(&gpu, "pipelines/compute_raster.toml", &scene);
    let (mut pixels, mut sum, mut worst, mut difference) = (0usize, 0.0f64, 0.0f64, 0.0f64);
    for (r, c) in raster.iter().zip(&compute) {
        if r[3] < 0.2 || c[3] < 0.2 {
            continue;
        }
        pixels += 1;
        for ch in 0..3 {
            let (want, got) = (f64::from(r[ch] / r[3]), f64::from(c[ch] / c[3]));
            sum += want;
            difference += (got - want).abs();
            worst = worst.max((got - want).abs());
        }
    }
    let mean = sum / (3 * pixels.max(1)) as f64;
    let relative = difference / sum.max(f64::MIN_POSITIVE);
    println!(
        "{pixels} pixels both at least 0.2 opaque: mean radiance {mean:.4}, \
         mean |Δ| / mean {relative:.5}, largest |Δ| {worst:.4}"
    );
    assert!(pixels >= 100, "the wave is drawn: {pixels} pixels");
    assert!(mean > 0.05, "the wave is lit: mean radiance {mean}");
    assert!(
        relative < TOLERANCE,
        "compute_raster's radiance is {relative:.5} of linked_list's away (mean |Δ| / mean)"
    );
}

/// Mean |Δ radiance| / mean radiance allowed between the two draws:
/// measured 0.0031 (145 pixels, the wave out of the plane, at c51ef42);
/// with `strand_curve_tangent`'s zero-chord test inverted (strand_curve.wgsl
/// 27:15, which then interpolates the ends' tangents linearly on every
/// chord) 0.0865, and the test fails. (In the plane: 0.0047, and 0.0996
/// with the linear interpolation edited in by hand.)
const TOLERANCE: f64 = 0.01;

/// Σα of the premultiplied `hair` image of `pipeline` with `extra` on
/// `scene`.
fn hair_alpha(gpu: &Gpu, pipeline: &str, extra: &[&str], scene: &SceneData) -> f64 {
    let mut sets = vec!["pipeline.outputs=[\"final\", \"hair\"]".to_owned()];
    sets.extend(extra.iter().map(|s| s.to_string()));
    let prepared = prepare(gpu, &repo_root().join(pipeline), &sets, scene, SIZE)
        .unwrap_or_else(|e| panic!("preparing {pipeline}: {e}"));
    prepared.render().expect("renders");
    let hair = prepared.read_resource("hair").expect("hair");
    (0..(hair.width * hair.height) as usize)
        .map(|i| f64::from(hair.texel(i)[3]))
        .sum()
}

/// A groom of one segment (two points: the line list's index buffer holds
/// two indices) is binned and drawn: Σα within 10 % of linked_list's
/// rasterized line (strand space, the gallery's setting; one shading point
/// per strand point). Measured 67.09 against 64.21 (+4.5 %, more than the
/// 2 % `tests/compute_raster.rs` holds for 7-segment strands: not looked
/// into here; the mutant below draws nothing). Kills, in
/// `techniques/transparency/compute_raster/tiles.wgsl`, the walk's guard
/// `2u * s + 1u >= arrayLength(&hair_indices)` with `*` → `/` (74:12),
/// which stops segment 0 where the buffer holds fewer than four indices.
#[test]
fn a_groom_of_one_segment_is_drawn() {
    let (_lock, gpu) = open_gpu();
    let mut scene = scene();
    scene.strands = plait_hair::Strands::new();
    let ends = [Vec3::new(-1.2, -0.3, 0.0), Vec3::new(1.1, 0.4, 0.0)];
    scene
        .strands
        .push_strand(&ends, |_| 0.02, |_| 1.0, Vec3::splat(0.8));
    let raster = hair_alpha(&gpu, "pipelines/linked_list.toml", &[], &scene);
    // At most as many shading points as the strand has points.
    let two = ["params.shading_points=2"];
    let compute = hair_alpha(&gpu, "pipelines/compute_raster.toml", &two, &scene);
    println!("one segment: Σα linked_list {raster:.3}, compute_raster {compute:.3}");
    assert!(
        raster > 10.0,
        "the segment is drawn by the raster draw: Σα {raster}"
    );
    assert!(
        (compute / raster - 1.0).abs() < 0.1,
        "compute_raster's Σα {compute:.3} against linked_list's {raster:.3}"
    );
}

fn word(bytes: &[u8], i: usize) -> u32 {
    u32::from_le_bytes(bytes[4 * i..4 * i + 4].try_into().expect("4 bytes"))
}

/// More tiles than 65,538 — 2-pixel tiles over 666 × 392, the buffer's
/// (666 / 2 + 1) × (392 / 2 + 1) = 65,798 — with a strand along the
/// image's bottom rows: the tile scan's
/// `needed` (raster_counter[1]) is the sum of the tiles' counts. Kills, in
/// `techniques/transparency/compute_raster/scan.wgsl`, the tiles per thread
/// `(tiles + THREADS - 1u) / THREADS` → `* THREADS` (26:38): one thread
/// then scans all tiles, the same sums, unless `lid · per` wraps past 2³²
/// to below the tile count — at this count thread 254's, which scans the
/// last 2,822 tiles (the bottom rows) a second time (a count found on the
/// CPU; most counts above 65,538 wrap past it).
#[test]
fn the_tile_scan_counts_every_tile_once_past_65538_tiles() {
    let (_lock, gpu) = open_gpu();
    let mut scene = scene();
    scene.strands = plait_hair::Strands::new();
    // The camera sees y from −1.61 to 1.61 at z = 0: the bottom 4 % of
    // the image, the last tiles, from y = −1.47 down.
    let ends = [Vec3::new(-1.8, -1.55, 0.0), Vec3::new(1.8, -1.52, 0.0)];
    scene
        .strands
        .push_strand(&ends, |_| 0.005, |_| 1.0, Vec3::splat(0.8));
    let size = (666u32, 392u32);
    let tiles = ((size.0 / 2 + 1) * (size.1 / 2 + 1)) as usize;
    let sets = [
        "params.tile_size=2".to_owned(),
        "params.shading_points=2".to_owned(),
        "pipeline.outputs=[\"final\", \"tile_ranges\", \"raster_counter\"]".to_owned(),
    ];
    let pipeline = repo_root().join("pipelines/compute_raster.toml");
    let prepared =
        prepare(&gpu, &pipeline, &sets, &scene, size).unwrap_or_else(|e| panic!("prepares: {e}"));
    prepared.render().expect("renders");
    let ranges = prepared.read_buffer("tile_ranges").expect("tile_ranges");
    let counter = prepared
        .read_buffer("raster_counter")
        .expect("raster_counter");
    let counts: Vec<u32> = (0..tiles).map(|i| word(&ranges, 2 * i)).collect();
    let sum: u64 = counts.iter().map(|&c| u64::from(c)).sum();
    let last: u64 = counts[62_976..].iter().map(|&c| u64::from(c)).sum();
    let needed = word(&counter, 1);
    println!("{tiles} tiles: Σ counts {sum} ({last} in the last 2,822 tiles), needed {needed}");
    assert!(last > 0, "the strand reaches the last tiles");
    assert_eq!(
        u64::from(needed),
        sum,
        "the scan's total against the tiles' counts"
    );
}

/// Four wide segments (one each, 0.4 thick: ≈ 15 px at 160×120; 1.0 long:
/// ≈ 37 px) running along the four diagonals of the screen, one from each
/// quadrant. A quad's corners are (start −, start +, end −, end +): along
/// one of the four directions the first corner alone is the lowest in y,
/// along another the lowest in x, by min(L sin 45°, 2r cos 45°) ≈ 11 px
/// beyond the next corner, more than an 8-pixel tile. The tiles below or
/// left of the others' box reach only that corner's part of the quad.
/// compute_raster draws them as linked_list's quads: Σ|Δα| / Σα within
/// 0.005, as `tests/compute_raster.rs` holds its wide strands. Kills, in
/// `techniques/transparency/compute_raster/tiles.wgsl`, the box's low
/// corner taken from corners 1–3 (`c[0]` → `c[1]`, 157:34; 137:34 when
/// issue 40 named it): the first corner's tiles lose its triangle's tip.
#[test]
fn a_wide_quads_first_corner_alone_reaches_its_tiles() {
    let (_lock, gpu) = open_gpu();
    let mut scene = scene();
    scene.strands = plait_hair::Strands::new();
    for (centre, direction) in [
        (Vec3::new(-1.0, 0.75, 0.0), Vec3::new(1.0, 1.0, 0.0)),
        (Vec3::new(1.0, 0.75, 0.0), Vec3::new(-1.0, 1.0, 0.0)),
        (Vec3::new(-1.0, -0.75, 0.0), Vec3::new(1.0, -1.0, 0.0)),
        (Vec3::new(1.0, -0.75, 0.0), Vec3::new(-1.0, -1.0, 0.0)),
    ] {
        let half = direction.normalize() * 0.5;
        scene.strands.push_strand(
            &[centre - half, centre + half],
            |_| 0.4,
            |_| 1.0,
            Vec3::splat(0.8),
        );
    }
    let raster = hair(&gpu, "pipelines/linked_list.toml", &scene);
    let compute = hair(&gpu, "pipelines/compute_raster.toml", &scene);
    let raster_sum: f64 = raster.iter().map(|p| f64::from(p[3])).sum();
    let compute_sum: f64 = compute.iter().map(|p| f64::from(p[3])).sum();
    let difference: f64 = raster
        .iter()
        .zip(&compute)
        .map(|(r, c)| f64::from((r[3] - c[3]).abs()))
        .sum::<f64>()
        / raster_sum;
    println!(
        "four wide diagonal quads: Σα linked_list {raster_sum:.2}, compute_raster \
         {compute_sum:.2}, Σ|Δα| / Σα {difference:.5}"
    );
    assert!(raster_sum > 1000.0, "the quads are drawn: Σα {raster_sum}");
    assert!(
        difference < 0.005,
        "compute_raster's quads are {difference:.5} of linked_list's away (Σ|Δα| / Σα)"
    );
}
