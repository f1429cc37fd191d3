//! `self_shadow/ray_traced`: the swept sphere behind a candidate box
//! (`shaders/lib/strand_rays.wgsl`), the pattern of a point's jittered rays
//! and the count behind a point (`techniques/self_shadow/ray_traced/self_shadow.wgsl`).
//! Its own tests cross every strand square to its width and hold the
//! rays' means over many points, which the pattern's details leave alone.

use glam::Vec3;
use plait::probe::{ProbeGrid, probe_with};
use plait::session::SceneData;
use plait::source::PipelineSource;
use plait_gpu::frame::FrameUniforms;
use plait_gpu::strand_structure::StrandPrimitive;
use plait_tests::strand_trace::{counts, strand};
use plait_tests::{open_gpu, repo_root};

/// One segment along x, half-width r = 0.005, and rays across it at 45°
/// around its axis, which cross its box (the swept sphere grown by r on
/// every axis, `shaders/passes/strand_boxes.wgsl`) through a corner of its
/// square cross-section. A ray passing 0.5 r from the axis crosses the
/// strand (1); one passing 1.2 r or 1.35 r from it runs through the box's
/// corner — its point nearest the axis is k r / √2 < r from it on y and z —
/// but outside the capsule, and crosses nothing (0). Three places along
/// the segment (s = 0.25, 0.65, 0.9), both corners' diagonals. Kills, in
/// `shaders/lib/strand_rays.wgsl`, the box path's end radius
/// `0.5 * b.thickness` → `0.5 / b.thickness` (87:93: a radius of 50 at the
/// segment's end, so every box candidate counts: 1 at 1.2 r).
#[test]
fn a_ray_through_a_segments_box_corner_outside_its_capsule_crosses_nothing() {
    let width = 0.01;
    let r = 0.5 * width;
    let vertices = strand(
        &[Vec3::new(-0.1, 0.0, 0.0), Vec3::new(0.1, 0.0, 0.0)],
        width,
        0,
    );
    let mut wrong = Vec::new();
    for dir in [Vec3::new(0.0, 1.0, 1.0), Vec3::new(0.0, 1.0, -1.0)] {
        let dir = dir.normalize();
        // Toward a corner of the square cross-section, square to the ray.
        let corner = Vec3::X.cross(dir);
        let cases: Vec<(f32, f32, f32)> = [-0.05f32, 0.03, 0.08]
            .into_iter()
            .flat_map(|x| [(x, 0.5, 1.0), (x, 1.2, 0.0), (x, 1.35, 0.0)])
            .collect();
        let points: Vec<Vec3> = cases
            .iter()
            .map(|&(x, k, _)| Vec3::new(x, 0.0, 0.0) + corner * (k * r) - 0.1 * dir)
            .collect();
        let found = counts(StrandPrimitive::SweptSphere, &vertices, &points, dir, 0.0);
        for (&(x, k, want), got) in cases.iter().zip(&found) {
            if *got != want {
                wrong.push(format!(
                    "toward {dir}, at x = {x}, {k} r from the axis: {got}, expected {want}"
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}

const SIZE: (u32, u32) = (64, 48);

/// A scene of the strands `strands` (each a polyline of width `width`), the
/// camera of tests/ray_traced_self_shadow.rs and a directional light
/// travelling along `light` (`plait_tests::strands_under_light`).
fn scene(strands: &[Vec<Vec3>], width: f32, light: Vec3) -> SceneData {
    plait_tests::strands_under_light("ray_pattern.toml", strands, width, light)
}

/// Points on the plane y = `y`: `columns` along x from `x0` by `dx`, `rows`
/// along z from `z0` by `dz`, as `tests/fixtures/plane_strands_probe.wgsl`
/// reads the grid.
struct Plane {
    x0: f32,
    dx: f32,
    columns: u32,
    z0: f32,
    dz: f32,
    rows: u32,
    y: f32,
}

impl Plane {
    fn point(&self, p: u32) -> Vec3 {
        let (c, r) = (p % self.columns, p / self.columns);
        Vec3::new(
            self.x0 + c as f32 * self.dx,
            self.y,
            self.z0 + r as f32 * self.dz,
        )
    }
}

/// `hair_strands_along_light` of `self_shadow = ray_traced` with `sets` at
/// every point of `plane`: its x (toward the light) or, with `behind`, y.
fn along_light(scene: &SceneData, plane: &Plane, sets: &[&str], behind: bool) -> Vec<f32> {
    let (_lock, gpu) = open_gpu();
    assert!(
        gpu.capabilities.ray_query,
        "no ray queries on {}",
        gpu.support.describe()
    );
    let grid = ProbeGrid {
        uv0: [plane.x0, plane.z0],
        uv1: [plane.dx, plane.dz],
        rays: (plane.columns, plane.rows),
        depths: 1,
        depth_range: (plane.y, if behind { 1.0 } else { 0.0 }),
    };
    let mut sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    sets.push("techniques.self_shadow=ray_traced".to_owned());
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let source = PipelineSource::new(&pipeline, &sets);
    let shader = "tests/fixtures/plane_strands_probe.wgsl";
    probe_with(&gpu, &source, scene, SIZE, &grid, shader)
        .unwrap_or_else(|e| panic!("probing {sets:?}: {e}"))
        .expect("a self-shadow provider")
        .values
}

/// The self-shadow shader's `hash` (PCG's output permutation), on the CPU.
fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// The side of one pixel at `world`'s depth from the camera: the shader's
/// `pixel_footprint`, on the CPU.
fn pixel_footprint(frame: &FrameUniforms, world: Vec3) -> f32 {
    let view_proj = glam::Mat4::from_cols_array_2d(&frame.camera_view_proj);
    let inverse = glam::Mat4::from_cols_array_2d(&frame.camera_inv_view_proj);
    let ndc = view_proj.project_point3(world);
    let up = ndc + Vec3::new(0.0, 2.0 * frame.screen_size[3], 0.0);
    inverse
        .project_point3(ndc)
        .distance(inverse.project_point3(up))
}

/// The origins of `world`'s `count` rays toward a directional light, as the
/// shader's `rays_from` and `ray_origin` document them: the point itself for
/// one ray; else a Vogel spiral, ray i at √((i + ½) / count) of the radius
/// of a disc of one pixel's area and i golden angles, turned by the point's
/// hash of its coordinates' bits, across the light.
fn ray_origins(frame: &FrameUniforms, world: Vec3, count: u32) -> Vec<Vec3> {
    if count <= 1 {
        return vec![world];
    }
    let to_light = Vec3::new(
        frame.light_direction[0],
        frame.light_direction[1],
        frame.light_direction[2],
    );
    let helper = if to_light.x.abs() > 0.9 {
        Vec3::Y
    } else {
        Vec3::X
    };
    let u = to_light.cross(helper).normalize();
    let v = to_light.cross(u);
    let radius = pixel_footprint(frame, world) * 0.564_189_6;
    let [bx, by, bz] = [world.x, world.y, world.z].map(f32::to_bits);
    let bits = pcg_hash(bx ^ pcg_hash(by ^ pcg_hash(bz)));
    let turn = std::f32::consts::TAU * (bits >> 8) as f32 / 16_777_216.0;
    (0..count)
        .map(|i| {
            let rho = radius * ((i as f32 + 0.5) / count as f32).sqrt();
            let phi = turn + 2.399_963_2 * i as f32;
            world + rho * (phi.cos() * u + phi.sin() * v)
        })
        .collect()
}

/// The light of the edge and of the two strands: travelling down, slanted
/// along z only (to_light has no x).
const LIGHT: Vec3 = Vec3::new(0.0, -1.0, -0.3);

/// One opaque straight strand along z at height 0.4 (half-width
/// `EDGE_RADIUS`) and the points 0.2 below it on a grid across its shadow's
/// two edges: x from −0.08 to 0.08 by 2⁻¹², z from −0.25 by 2⁻⁵ (16 rows),
/// every value exact in f32. The light has no x, so a ray from origin o
/// toward it stays at x = o.x and crosses the strand exactly when
/// |o.x| < EDGE_RADIUS: each point's count is the share of its rays'
/// origins inside the band, which the CPU reads from the documented
/// pattern (`ray_origins`). With one ray that is the point's own, 0 or 1;
/// with 16 each ray's origin is pinned by the point's hash, the spiral's
/// radii and angles and the pixel's footprint. A ray whose origin lies
/// within 1e-5 (5e-4 of the disc's radius) of an edge may go either way
/// (f32 sin and cos on the GPU). Kills, in
/// `techniques/self_shadow/ray_traced/self_shadow.wgsl`: the strand count's
/// floor of rays 1 → 2 (111:52: one ray becomes two jittered ones, 0.5
/// near an edge), the spiral's (i + 0.5) → 0.55 (102:41: each ray 0.2–1 %
/// of the radius farther out; tens of points near the edges then differ by
/// 1/16), and a shift dropped from the per-point hash (58:42: another
/// rotation at every point).
#[test]
fn the_strand_count_behind_an_edge_follows_the_documented_ray_pattern() {
    const EDGE_RADIUS: f32 = 0.05;
    let axis: Vec<Vec3> = (0..=12)
        .map(|s| Vec3::new(0.0, 0.4, 0.1 * s as f32 - 0.6))
        .collect();
    let scene = scene(&[axis], 2.0 * EDGE_RADIUS, LIGHT);
    let frame = scene.frame(SIZE, 0);
    let step = 1.0 / 4096.0;
    let plane = Plane {
        x0: -328.0 * step,
        dx: step,
        columns: 657,
        z0: -0.25,
        dz: 1.0 / 32.0,
        rows: 16,
        y: 0.2,
    };
    for rays in [1u32, 16] {
        let set = format!("params.shadow_rays={rays}");
        let found = along_light(&scene, &plane, &[&set], false);
        assert_eq!(found.len(), (plane.columns * plane.rows) as usize);
        let (mut wrong, mut unsure, mut partial) = (Vec::new(), 0, 0);
        for (p, got) in found.iter().enumerate() {
            let world = plane.point(p as u32);
            let origins = ray_origins(&frame, world, rays);
            let inside = origins.iter().filter(|o| o.x.abs() < EDGE_RADIUS).count();
            let near = origins
                .iter()
                .filter(|o| (o.x.abs() - EDGE_RADIUS).abs() < 1e-5)
                .count();
            let want = inside as f32 / rays as f32;
            unsure += near;
            partial += usize::from(want > 0.0 && want < 1.0);
            if (got - want).abs() > near as f32 / rays as f32 + 1e-6 {
                wrong.push(format!("{world}: {got}, expected {want}"));
            }
        }
        eprintln!(
            "{rays} rays: {} of {} points differ from the pattern; {unsure} rays within 1e-5 of an edge, {partial} points partly shadowed",
            wrong.len(),
            found.len()
        );
        assert!(
            wrong.is_empty(),
            "{rays} rays: {} points:\n{}",
            wrong.len(),
            wrong.join("\n")
        );
    }
}

/// Two short strands (along x, 0.06 long) centred on the light's ray
/// through the origin, `half` either side of it, so the hair's bounding
/// sphere (the box's half-diagonal, R = √(half² + 0.03²)) barely holds
/// them: a point on the near strand, on the hair sphere's near side, has the
/// far strand 2·half ≈ 2R − 0.03²/half behind it. The count behind the
/// point — the rays' count from two biases past the sphere's diameter
/// farther on, less that from two biases past the point's own strand — is
/// that one strand; the count toward the light is 0. At half = 0.3
/// (R ≈ 0.30) and at half = 1.5 (R ≈ 1.5, where 2/R ≈ 1.33 falls short of
/// 2R). Kills, in `techniques/self_shadow/ray_traced/self_shadow.wgsl`, the
/// far end 2R + 2·bias → 2R − 2·bias (142:75: it then starts 0.017 in front
/// of the far strand and counts 0 behind) and 2R → 2/R (142:53: at
/// half = 1.5 it starts 1.7 in front of the far strand, 0 behind).
#[test]
fn a_point_on_the_near_side_of_the_hair_counts_the_strand_on_the_far_side_behind_it() {
    let to_light = -LIGHT.normalize();
    for half in [0.3, 1.5] {
        let (near, far) = (to_light * half, -to_light * half);
        let scene = scene(&[short(near), short(far)], 0.005, LIGHT);
        let frame = scene.frame(SIZE, 0);
        let radius = frame.hair_sphere[3];
        let bias = frame.conventions[0] * (frame.near_far[3] - frame.near_far[2]);
        // The far strand's axis 2·half behind the point: inside the unmutated
        // span by more than the bias, past the mutant's by more than one.
        let gap = 2.0 * half;
        assert!(
            gap < 2.0 * radius + bias && gap > 2.0 * radius - 3.0 * bias,
            "the far strand {gap} behind, hair sphere radius {radius}, bias {bias}"
        );
        let plane = along_x(near);
        let behind = along_light(&scene, &plane, &[], true);
        let toward = along_light(&scene, &plane, &[], false);
        eprintln!(
            "{half} either side, on the near strand: behind {behind:?}, toward the light {toward:?}"
        );
        assert_eq!(
            behind,
            vec![1.0; 3],
            "{half} either side: strands behind the point"
        );
        assert_eq!(
            toward,
            vec![0.0; 3],
            "{half} either side: strands toward the light"
        );
    }
}

/// A short strand (along x, 0.06 long) centred on `centre`.
fn short(centre: Vec3) -> Vec<Vec3> {
    vec![centre - Vec3::X * 0.03, centre + Vec3::X * 0.03]
}

/// Three points along x about `centre` (x = −2⁻⁶, 0, 2⁻⁶).
fn along_x(centre: Vec3) -> Plane {
    Plane {
        x0: centre.x - 1.0 / 64.0,
        dx: 1.0 / 64.0,
        columns: 3,
        z0: centre.z,
        dz: 0.0,
        rows: 1,
        y: centre.y,
    }
}

/// Points at the origin's row (three along x) with two short strands behind
/// them along the light's ray, 0.9 and 1.1 biases behind. The count behind
/// a point starts two biases behind it and takes the crossings more than one
/// bias on toward the light (`strands_toward` from there): from one bias
/// behind the point on, which holds the first strand and not the second.
/// So the count behind reads 2 (all the strands behind, from beyond the
/// hair) less 1: 1. Kills, in
/// `techniques/self_shadow/ray_traced/self_shadow.wgsl`, the start 2·bias →
/// 1.8·bias (141:50 ×0.9: from 0.8 biases behind on, neither strand is
/// taken off, 2) and → 2.2·bias (141:50 ×1.1: from 1.2 biases behind on,
/// both are, 0).
#[test]
fn a_strand_within_a_bias_behind_the_point_is_not_behind_it_and_one_past_it_is() {
    let to_light = -LIGHT.normalize();
    // The bias in world units: the frame's share of the light's depth
    // range times that range (plait_gpu::frame::SELF_SHADOW_BIAS, 0.01,
    // up to rounding).
    let bias = plait_gpu::frame::SELF_SHADOW_BIAS;
    let strands = [0.9, 1.1].map(|k| short(-to_light * (k * bias)));
    let scene = scene(&strands, 0.005, LIGHT);
    let frame = scene.frame(SIZE, 0);
    let read = frame.conventions[0] * (frame.near_far[3] - frame.near_far[2]);
    assert!(
        (read / bias - 1.0).abs() < 1e-3,
        "the frame's bias {read}, not {bias}"
    );
    let behind = along_light(&scene, &along_x(Vec3::ZERO), &[], true);
    eprintln!("bias {bias}: strands behind {behind:?}");
    assert_eq!(behind, vec![1.0; 3], "strands behind the point");
}
