//! `self_shadow/ray_traced` through DOTS (`primitive = "dots"`): the corner
//! table the structure is built from and the tracers' quads
//! (`shaders/lib/strand_dots.wgsl`), and which segment of a strand counts a
//! ray that crosses quads of two (`dots_owns`, `shaders/lib/strand_rays.wgsl`).
//!
//! The strands below lie along x, so `dots_across` gives u = ẑ and v = −ŷ
//! exactly: quad 0 lies in the plane y = 0 (its half-width along z), quad 1
//! in z = 0 (along y), both taken through the strand's joint `JOINT`, away
//! from the origin (a strand through it would meet the origin's planes).
//! The rays are hand-made through points chosen on those planes, written
//! about the joint; every margin to a quad's or band's edge is 3–5 % of a
//! radius.

use glam::Vec3;
use plait::session::{SceneData, prepare};
use plait_gpu::strand_structure::StrandPrimitive;
use plait_hair::StrandVertex;
use plait_tests::strand_trace::{counts, strand};
use plait_tests::{open_gpu, repo_root};

/// The joint of the strands below (their middle vertex), exact in f32.
const JOINT: Vec3 = Vec3::new(0.25, 0.5, -0.75);

/// A strand along x through JOINT + x for x = −0.1, 0, 0.1, of widths
/// `widths` at those vertices (twice the DOTS quads' half-widths ra, rb,
/// rc).
fn three_vertices(widths: [f32; 3]) -> Vec<StrandVertex> {
    along_x([-0.1, 0.0, 0.1], widths)
}

/// A strand along x through JOINT + x for each of `xs`, of widths `widths`
/// there.
fn along_x(xs: [f32; 3], widths: [f32; 3]) -> Vec<StrandVertex> {
    let points = xs.map(|x| JOINT + Vec3::new(x, 0.0, 0.0));
    let mut vertices = strand(&points, widths[0], 0);
    for (v, w) in vertices.iter_mut().zip(widths) {
        v.thickness = w;
    }
    vertices
}

/// DOTS crossings counted along the ray through JOINT + `first` then
/// JOINT + `second`, and along the reverse ray: from 0.1 before the first
/// point, as the tracers walk them (no bias).
fn both_ways(vertices: &[StrandVertex], first: Vec3, second: Vec3) -> [f32; 2] {
    let d = (second - first).normalize();
    let (first, second) = (JOINT + first, JOINT + second);
    let dots = StrandPrimitive::Dots;
    let forward = counts(dots, vertices, &[first - 0.1 * d], d, 0.0)[0];
    let back = counts(dots, vertices, &[second + 0.1 * d], -d, 0.0)[0];
    [forward, back]
}

/// A strand whose first segment tapers from ra = 0.015 to rb = 0.005 and
/// whose second keeps rb, and a ray through the joint's two planes: first
/// z = 0 at P1 = (0.005, 0.95 rb, 0), inside the second segment's quad 1
/// and past the first's end (s = 1.05), then y = 0 at P2 = (−0.005, 0,
/// 0.002), inside the first segment's quad 0 (s = 0.95). Each segment
/// reports one quad; the pass belongs to the segment whose quad's plane the
/// ray crosses first — the second — so the count is 1, and so it is along
/// the reverse ray (the first's). Kills, in `shaders/lib/strand_rays.wgsl`,
/// `strand_segment`'s `s + k` → `s − k` (101:20: the first segment's
/// neighbour looked for at −1, the second's at 2, neither there: both
/// segments count, 2 each way) and, before the neighbour's own half-width
/// held a crossing past an end (`on_segment`), `dots_plane`'s band
/// `clamp(s, 0, 1)` → `clamp(s, 0, 1.1)` in `shaders/lib/strand_dots.wgsl`
/// (101:60: the band past the tapering segment's end narrowed to 0.9 rb,
/// P1 fell outside it, and the first segment counted the pass too: 2
/// forward).
#[test]
fn a_ray_through_a_tapered_joint_counts_once_either_way() {
    let (rb, gap) = (0.005, 0.005);
    let vertices = three_vertices([0.03, 2.0 * rb, 2.0 * rb]);
    let p1 = Vec3::new(gap, 0.95 * rb, 0.0);
    let p2 = Vec3::new(-gap, 0.0, 0.002);
    let found = both_ways(&vertices, p1, p2);
    assert_eq!(found, [1.0, 1.0], "crossings (through P1 first, P2 first)");
}

/// A strand of constant half-width 0.005 whose second segment then tapers
/// (to 0.0025) or widens (to 0.01), and a ray through the plane z = 0 at
/// P1 = (−0.005, 0.002, 0), inside the first segment's quad 1 (s = 0.95),
/// and through y = 0 at P2 = (0.02, 0, z), past the joint (0.2 along the
/// second segment): z = 0.00475, outside the narrower second segment's quad
/// there (0.0045) but within the first's end (0.005); or z = 0.0055, inside
/// the wider one's (0.006) and past the first's end. Either way along the
/// ray the strand is crossed once: 1. `dots_owns` holds a crossing past a
/// segment's end to the neighbour's half-width there (`on_segment`). When it
/// held it to the segment's own end's, the narrower neighbour's ray from
/// P2 counted 0 (the first segment gave the pass to the neighbour, which
/// reports nothing there) and the wider one's 2 (neither segment saw the
/// other's crossing).
#[test]
fn a_ray_past_a_joint_counts_once_beside_a_narrower_or_wider_neighbour() {
    let p1 = Vec3::new(-0.005, 0.002, 0.0);
    let mut wrong = Vec::new();
    for (end, z) in [(0.005, 0.00475), (0.02, 0.0055)] {
        let vertices = three_vertices([0.01, 0.01, end]);
        let found = both_ways(&vertices, p1, Vec3::new(0.02, 0.0, z));
        if found != [1.0, 1.0] {
            wrong.push(format!(
                "second segment's end width {end}, P2 at z = {z}: {found:?} (P1 first, P2 first)"
            ));
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}

/// A strand of half-width 0.015 whose second segment, 0.02 long, tapers
/// to 0.005, and a ray through y = 0 at P_A = (0.019, 0, 0.0058), near
/// the second segment's far end (0.95 along it), just outside its quad
/// there (0.0055 wide), then z = 0 at P_B = (−0.005, 0.002, 0), inside the
/// first segment's quad 1. Only the first segment reports, and the pass is
/// its own: 1, either way along the ray. Kills, in
/// `shaders/lib/strand_rays.wgsl`, `on_segment`'s place along the
/// neighbour clamped to 0.9 instead of 1 (120:85: the neighbour taken 0.006
/// wide at P_A, whose plane the ray from P_A crosses first: the first
/// segment gives it the pass, 0).
#[test]
fn a_ray_just_outside_a_tapering_neighbours_far_end_counts_the_segment_it_crosses() {
    let vertices = along_x([-0.1, 0.0, 0.02], [0.03, 0.03, 0.01]);
    let p_a = Vec3::new(0.019, 0.0, 0.0058);
    let p_b = Vec3::new(-0.005, 0.002, 0.0);
    let found = both_ways(&vertices, p_a, p_b);
    assert_eq!(found, [1.0, 1.0], "crossings (P_A first, P_B first)");
}

/// A strand of one segment (x from −0.1 to 0 about JOINT, half-width
/// 0.005) and a ray through z = 0 at P1 = (0.005, 0.002, 0), past the
/// strand's tip, then y = 0 at P2 = (−0.005, 0, 0.002), inside quad 0: no
/// segment lies where the ray crosses the first plane, so the pass is the
/// one segment's, 1, either way along the ray. Kills, in
/// `shaders/lib/strand_rays.wgsl`, `dots_owns`' second plane taken when it
/// lies on a segment `&&` nearer → `||` (146:57: the plane past the tip,
/// nearer, gives the pass to a segment that is not there, 0).
#[test]
fn a_ray_past_a_strands_tip_counts_its_last_segment() {
    let vertices = strand(&[JOINT - Vec3::new(0.1, 0.0, 0.0), JOINT], 0.01, 0);
    let p1 = Vec3::new(0.005, 0.002, 0.0);
    let p2 = Vec3::new(-0.005, 0.0, 0.002);
    let found = both_ways(&vertices, p1, p2);
    assert_eq!(found, [1.0, 1.0], "crossings (P1 first, P2 first)");
}

/// A straight strand of half-width 0.005 and a ray through the joint's two
/// planes: z = 0 at P1 = (0.005, 0.002, 0), inside the second segment's
/// quad 1, then y = 0 at P2 = (−0.005, 0, 0.002), inside the first's quad
/// 0, 0.0104 further. The pass is the second segment's, at P1's ray
/// distance. With a bias of 0.01 and P1 0.005 from the ray's origin, the
/// pass lies within the bias and counts 0; from 0.015 before P1, 1. Kills,
/// in `shaders/lib/strand_rays.wgsl`, `dots_owns`' second plane taken when
/// `planes[1].x < first` → `>=` (132:42 before `on_segment`: the first
/// segment, whose crossing lies beyond the bias, keeps the pass, 1). Where
/// both crossings lie beyond the bias, that mutant hands the pass from one
/// segment to the other and the count stays 1.
#[test]
fn a_pass_whose_first_crossing_lies_within_the_bias_is_not_counted() {
    let vertices = three_vertices([0.01; 3]);
    let p1 = Vec3::new(0.005, 0.002, 0.0);
    let p2 = Vec3::new(-0.005, 0.0, 0.002);
    let d = (p2 - p1).normalize();
    let origins = [JOINT + p1 - 0.005 * d, JOINT + p1 - 0.015 * d];
    let found = counts(StrandPrimitive::Dots, &vertices, &origins, d, 0.01);
    assert_eq!(
        found,
        [0.0, 1.0],
        "crossings beyond a bias of 0.01, P1 0.005 then 0.015 on"
    );
}

/// One segment along x (half-width 0.005) and rays along +x descending
/// through quad 0's plane y = 0 at a grazing slope: from (−0.15, 0.1 f, 0.002)
/// along (1, −f, 0), which crosses the plane at x = −0.05 (a quarter along
/// the segment, 0.002 off its axis) and runs parallel to quad 1. |facing|,
/// the direction's component along the quad's normal, is f. At f = 2e-7
/// the quad is crossed and counts 1 (so the driver reports a triangle
/// crossed this obliquely); at f = 9.5e-8, within `dots_quad`'s 1e-7 of
/// its plane, the ray runs along the quad and counts 0. Kills, in
/// `shaders/lib/strand_dots.wgsl`, `dots_quad`'s `abs(facing) <= 1e-7` →
/// `<= 9e-8` (69:24: the quad is then crossed at f = 9.5e-8 too, 1).
#[test]
fn a_ray_within_1e7_of_a_quads_plane_runs_along_it() {
    let vertices = strand(
        &[Vec3::new(-0.1, 0.0, 0.0), Vec3::new(0.1, 0.0, 0.0)],
        0.01,
        0,
    );
    for (f, want) in [(2e-7f32, 1.0), (9.5e-8, 0.0)] {
        // |(1, −f, 0)| rounds to 1 in f32: the direction is exact.
        let d = Vec3::new(1.0, -f, 0.0);
        let origin = Vec3::new(-0.15, 0.1 * f, 0.002);
        let found = counts(StrandPrimitive::Dots, &vertices, &[origin], d, 0.0);
        assert_eq!(found, [want], "|facing| {f}: crossings");
    }
}

/// The twelve corners `dots_corner` gives one segment (`tests/fixtures/dots_corners.wgsl`:
/// a = (0.1, −0.2, 0.3), ra = 0.02 → b = (0.4, 0.1, 0.2), rb = 0.01),
/// which the structure's builder writes as its triangles, are those the
/// module documents and the tracers' `dots_quad` assumes: quad q (w = u,
/// then v) is triangle (a − ra w, a + ra w, b − rb w) and triangle
/// (b − rb w, a + ra w, b + rb w), within 1e-6; u and v (`dots_across`)
/// are unit vectors square to each other and to b − a. The builder holds
/// the module from its build, so the tracing tests never see this table
/// as the file is now; this fixture reads it at run time. Kills, in
/// `shaders/lib/strand_dots.wgsl`, the table's fifth end 0 → 1 (50:46:
/// each quad's second triangle loses its corner a + ra w and has no area).
#[test]
fn dots_corners_are_the_documented_quads() {
    let (a, ra, b, rb) = (
        Vec3::new(0.1, -0.2, 0.3),
        0.02,
        Vec3::new(0.4, 0.1, 0.2),
        0.01,
    );
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/dots_corners.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (4, 4)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let bytes = prepared.read_buffer("corners").expect("corners");
    let words: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    let found: Vec<Vec3> = words.iter().map(|w| Vec3::new(w[0], w[1], w[2])).collect();
    let (u, v) = (found[12], found[13]);
    let e = (b - a).normalize();
    for (what, got, want) in [
        ("|u|", u.length(), 1.0),
        ("|v|", v.length(), 1.0),
        ("u·v", u.dot(v), 0.0),
        ("u·e", u.dot(e), 0.0),
        ("v·e", v.dot(e), 0.0),
    ] {
        assert!((got - want).abs() < 1e-6, "{what} = {got} (dots_across)");
    }
    let mut wrong = Vec::new();
    for (q, w) in [u, v].into_iter().enumerate() {
        let quad = [
            a - ra * w,
            a + ra * w,
            b - rb * w,
            b - rb * w,
            a + ra * w,
            b + rb * w,
        ];
        for (k, want) in quad.into_iter().enumerate() {
            let j = 6 * q + k;
            if found[j].distance(want) > 1e-6 {
                wrong.push(format!("corner {j}: {}, documented {want}", found[j]));
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}
