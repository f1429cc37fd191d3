//! The strands' acceleration structure (`plait_gpu::strand_structure`) and
//! the ray-traced strand count through it (issue 48): a ray from a point
//! toward the light counts the strands it crosses beyond the self-shadow
//! bias, each candidate box intersected as a tapered swept sphere
//! (`shaders/lib/strand_capsule.wgsl`), or each segment's DOTS triangles
//! counted once (`shaders/lib/strand_dots.wgsl`). Checked on one strand
//! (its own strand never counts, one strand across the ray counts once), on
//! one segment from many directions (DOTS: one crossing however many of its
//! four triangles the ray meets, and the crossed quads' width), and on the
//! slab of tests/strand_count.rs against its closed form k · WIDTH / SPACING.

use glam::Vec3;
use plait_gpu::strand_structure::{
    StrandPrimitive, StructureError, check_primitives, check_segments,
};
use plait_hair::StrandVertex;
use plait_tests::strand_trace::{counts, strand};

/// The self-shadow bias every provider shares (docs/design.md).
const BIAS: f32 = 0.01;

/// One straight strand along x of width 0.005, four segments; the light
/// slanted in the x-y plane. Points on its axis (its own strand, behind no
/// other) count 0; points 0.05 below it along the light count 1 when the
/// ray passes within half the width of the axis, 0 when just outside; a
/// point through a joint between two segments counts 1, not 2. As swept
/// spheres and as DOTS (the strand along x: quad 0 spans z, which the light
/// in the x-y plane crosses square on, quad 1 lies in the light's plane).
#[test]
fn one_strand_counts_once_and_never_itself() {
    for primitive in [StrandPrimitive::SweptSphere, StrandPrimitive::Dots] {
        one_strand(primitive);
    }
}

fn one_strand(primitive: StrandPrimitive) {
    let width = 0.005;
    let axis: Vec<Vec3> = (0..=4)
        .map(|i| Vec3::new(0.25 * i as f32 - 0.5, 0.0, 0.0))
        .collect();
    let vertices = strand(&axis, width, 0);
    let to_light = Vec3::new(0.3, 1.0, 0.0).normalize();
    let below = |x: f32, dz: f32| Vec3::new(x, 0.0, dz) - 0.05 * to_light;
    let cases = [
        ("on the axis", Vec3::new(0.1, 0.0, 0.0), 0.0),
        ("on the axis at a joint", Vec3::new(0.0, 0.0, 0.0), 0.0),
        ("on the surface", Vec3::new(0.1, 0.0, 0.4 * width), 0.0),
        ("below the middle of a segment", below(0.1, 0.0), 1.0),
        ("below a joint", below(0.0, 0.0), 1.0),
        ("below, 0.4 widths aside", below(0.1, 0.4 * width), 1.0),
        ("below, 0.6 widths aside", below(0.1, 0.6 * width), 0.0),
        ("above it", Vec3::new(0.1, 0.0, 0.0) + 0.05 * to_light, 0.0),
    ];
    let points: Vec<Vec3> = cases.iter().map(|c| c.1).collect();
    let found = counts(primitive, &vertices, &points, to_light, BIAS);
    let wrong: Vec<String> = cases
        .iter()
        .zip(&found)
        .filter(|((_, _, want), got)| *got != want)
        .map(|((what, _, want), got)| format!("{what}: {got}, expected {want}"))
        .collect();
    assert!(wrong.is_empty(), "{primitive:?}: {wrong:#?}");
}

/// One segment along x (width 0.01, so half-width r = 0.005; DOTS quad 0
/// spans z, quad 1 y) and rays toward it from 24 directions around its axis
/// (every 15°, so some square to a quad, some along one, some between the
/// two) and tilted 0° and 40° out of the plane across it, each from a point
/// 0.1 before the axis point 0.3 along it (off the middle, where a ray
/// through the axis would also run through both quads' diagonals: a
/// triangle's edge, where which triangle the driver reports and which
/// plait::strand_dots picks may differ): passing at ρ from the axis, 0 and 0.3 r
/// aside, the ray crosses both of DOTS' quads (or one, along the other)
/// and counts 1; 0.9 r aside it meets DOTS only where a quad reaches it —
/// where ρ ≤ r · max(|cos φ|, |sin φ|), φ the offset's angle to quad 0 —
/// and the swept sphere always. Kills counting each reported triangle
/// (2 through the axis) and counting one quad only (0 along quad 0).
#[test]
fn one_segment_counts_once_from_every_direction() {
    let width = 0.01;
    let r = 0.5 * width;
    let vertices = strand(
        &[Vec3::new(-0.1, 0.0, 0.0), Vec3::new(0.1, 0.0, 0.0)],
        width,
        0,
    );
    let mut wrong = Vec::new();
    for primitive in [StrandPrimitive::SweptSphere, StrandPrimitive::Dots] {
        for tilt in [0.0f32, 40.0] {
            for step in 0..24 {
                let theta = (15.0 * step as f32).to_radians();
                // The ray's direction: across the axis at theta from +z
                // (toward +y), tilted along x.
                let across = Vec3::new(0.0, theta.sin(), theta.cos());
                let dir = (across * tilt.to_radians().cos() + Vec3::X * tilt.to_radians().sin())
                    .normalize();
                // The offset: perpendicular to the axis and to the ray.
                let side = Vec3::X.cross(across).normalize();
                let cases = [(0.0, true), (0.3, true), (0.9, false)];
                let points: Vec<Vec3> = cases
                    .iter()
                    .map(|(k, _)| Vec3::new(-0.04, 0.0, 0.0) + side * (k * r) - 0.1 * dir)
                    .collect();
                let found = counts(primitive, &vertices, &points, dir, 0.0);
                // The offset's angle to quad 0 (z): side is across rotated by 90°.
                let phi = theta + std::f32::consts::FRAC_PI_2;
                let reach = phi.cos().abs().max(phi.sin().abs());
                for ((k, always), got) in cases.iter().zip(&found) {
                    let want = match primitive {
                        StrandPrimitive::SweptSphere => 1.0,
                        StrandPrimitive::Dots if *always => 1.0,
                        // Clear of the edge by 2 %: no ray within rounding of it.
                        StrandPrimitive::Dots if k * 1.02 < reach => 1.0,
                        StrandPrimitive::Dots if *k > reach * 1.02 => 0.0,
                        StrandPrimitive::Dots => continue,
                    };
                    if *got != want {
                        wrong.push(format!(
                            "{primitive:?}, {:.0}° around, {tilt}° tilted, {k} r aside: {got}, expected {want}",
                            theta.to_degrees()
                        ));
                    }
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}

const LAYERS: usize = 4;
const TOP: f32 = 0.4;
const GAP: f32 = 0.1;
const PER_LAYER: usize = 50;
const SPACING: f32 = 0.02;
const WIDTH: f32 = 0.005;
const HALF_LENGTH: f32 = 0.5;

/// The slab of tests/strand_count.rs: LAYERS layers of PER_LAYER parallel
/// strands along x, 8 segments each, layer k a quarter spacing aside.
fn slab() -> Vec<StrandVertex> {
    let mut out = Vec::new();
    for k in 0..LAYERS {
        let y = TOP - GAP * k as f32;
        for i in 0..PER_LAYER {
            let z = SPACING * (i as f32 + 0.25 * k as f32) - 0.5 * SPACING * PER_LAYER as f32;
            let points: Vec<Vec3> = (0..=8)
                .map(|s| Vec3::new(HALF_LENGTH * (s as f32 / 4.0 - 1.0), y, z))
                .collect();
            out.extend(strand(&points, WIDTH, (k * PER_LAYER + i) as u32));
        }
    }
    out
}

/// Below k of the slab's layers (between layers k-1 and k, half a gap from
/// each; k = 0 above the slab), the mean count over 4,096 points spread
/// over the interior (z by the golden ratio, so no beat with the spacing)
/// is k · WIDTH / SPACING within 5 %, the tolerance of
/// tests/strand_count.rs; above the slab it is 0.
#[test]
fn the_slab_counts_k_layers_as_the_closed_form() {
    for primitive in [StrandPrimitive::SweptSphere, StrandPrimitive::Dots] {
        slab_counts(primitive);
    }
}

/// The slab as `primitive`: the light crosses quad 0 square on (it spans z,
/// across every strand along x), so DOTS' crossed width is the strand's.
fn slab_counts(primitive: StrandPrimitive) {
    let to_light = Vec3::new(0.3, 1.0, 0.0).normalize();
    let n = 4096;
    let mut points = Vec::new();
    for k in 0..=LAYERS {
        let y = TOP + GAP * 0.5 - GAP * k as f32;
        for j in 0..n {
            let x = -0.2 + 0.4 * (j as f32 + 0.5) / n as f32;
            let z = -0.2 + 0.4 * (j as f32 * 0.618_034).fract();
            points.push(Vec3::new(x, y, z));
        }
    }
    let found = counts(primitive, &slab(), &points, to_light, BIAS);
    let per_layer = f64::from(WIDTH / SPACING);
    let means: Vec<f64> = found
        .chunks(n)
        .map(|c| c.iter().map(|&v| f64::from(v)).sum::<f64>() / n as f64)
        .collect();
    eprintln!(
        "{primitive:?}: mean counts below k = 0..={LAYERS} layers: {means:?} (closed form k · {per_layer})"
    );
    assert_eq!(means[0], 0.0, "above the slab: {means:?}");
    for (k, mean) in means.iter().enumerate().skip(1) {
        let ratio = mean / (k as f64 * per_layer);
        assert!(
            (ratio - 1.0).abs() <= 0.05,
            "{primitive:?}, k = {k}: ratio {ratio} ({means:?})"
        );
    }
}

/// More segments than the adapter's BLAS primitive limit, or no ray
/// queries at all: refused with the numbers, before anything is created.
#[test]
fn too_many_segments_are_refused_with_the_numbers() {
    let mut caps = plait_gpu::Capabilities::of_compile(&Default::default());
    caps.ray_query = true;
    caps.max_blas_primitives = 16_777_215;
    assert_eq!(check_segments(16_777_215, &caps, "`lavapipe`"), Ok(()));
    let e = check_segments(16_777_216, &caps, "`lavapipe`").expect_err("refused");
    assert_eq!(
        e,
        StructureError::TooManySegments {
            segments: 16_777_216,
            primitives: 16_777_216,
            primitive: StrandPrimitive::SweptSphere,
            limit: 16_777_215,
            adapter: "`lavapipe`".into()
        }
    );
    // DOTS: four triangles per segment, so a quarter of the segments fit.
    let dots = StrandPrimitive::Dots;
    assert_eq!(
        check_primitives(4_194_303, dots, &caps, "`lavapipe`"),
        Ok(())
    );
    let text = check_primitives(4_194_304, dots, &caps, "`lavapipe`")
        .expect_err("refused")
        .to_string();
    assert!(
        text.contains("4194304 segments, 16777216 primitives as dots (4 per segment), more than the 16777215 primitives"),
        "{text}"
    );
    assert!(text.contains("primitive = \"swept_sphere\""), "{text}");
    let text = e.to_string();
    assert!(
        text.contains("16777216 segments, 16777216 primitives as swept_sphere (1 per segment), more than the 16777215 primitives"),
        "{text}"
    );
    caps.ray_query = false;
    let text = check_segments(1, &caps, "`old`")
        .expect_err("refused")
        .to_string();
    assert!(text.contains("`bash scripts/ensure-vulkan.sh`"), "{text}");
}
