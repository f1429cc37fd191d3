//! Exact self-shadowing against the ray-traced count, one strand at a time
//! (issue 47 item 4, strands wider than a light texel): one straight strand
//! 2 or 4 texels of the 1024-texel map wide (1 or 2 at 512) over a plane of
//! receiver points across the light, one directional light, on square
//! texels and on texels 1.3 times taller than wide (the light's frustum
//! follows the hair's bounds, here two tiny strands at opposite corners).
//! Per receiver point the strands in front (the self_shadow point's
//! `strands_along_light`, tests/fixtures/strands_probe.wgsl) of exact at
//! light_size 512 and 1024 and of ray_traced, and on the CPU the band's
//! coverage of the point's light texel — what exact's list should hold: the
//! strand's share of the texel, the ray's count averaged over it.
//!
//! Found with it (the ray is the reference: its count is 1 exactly where the
//! point's ray passes within the strand's radius, checked here against the
//! closed form): on square texels the quads hold the band's coverage of
//! every texel; on non-square texels the quad's half width was the side's
//! whole image, which leans along the strand there and is longer than the
//! band is wide (+2.1 % of the band at 30°); the line's share was that
//! length too (+17 % on texels twice as tall). Both now take the part
//! across the strand (plait::strand_coverage::view_band_width).

use glam::{Mat4, Vec2, Vec3};
use plait::probe::{ProbeGrid, probe_with};
use plait::session::SceneData;
use plait::source::PipelineSource;
use plait_tests::{one_strand_scene, open_gpu, repo_root};

const HEIGHT: f32 = 0.3;
const LENGTH: f32 = 0.6;
const HALF: f32 = 0.5;
const LIGHT: [f32; 3] = [0.0, -1.0, -0.5];
const COS_I: f32 = 0.894_427_2;
const SIZE: (u32, u32) = (64, 48);
const FINE: u32 = 1024;
/// The receiver window's side in texels of the fine map, and probe points
/// per texel along each side (one more point than that in all, so the
/// points do not repeat every texel).
const WINDOW: f32 = 64.0;
const PER_TEXEL: u32 = 2;

/// One strand of `thickness` at `degrees` from the world's x in the ground's
/// plane, 8 segments; the two corner strands make the hair's bounds seen
/// from the light `aspect` times taller than wide.
fn scene(thickness: f32, degrees: f32, aspect: f32) -> SceneData {
    let text = format!(
        r#"
ambient = 0.0
[hair.procedural]
strands = 1
segments = 1
[ground]
height = 0.0
half_size = 3.0
[camera]
eye = [0.0, 2.0, 0.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
fov_y_degrees = 40.0
[light]
type = "directional"
direction = [{}, {}, {}]
intensity = 1.0
"#,
        LIGHT[0], LIGHT[1], LIGHT[2]
    );
    let (s, c) = degrees.to_radians().sin_cos();
    let along = Vec3::new(c, 0.0, s);
    let points: Vec<Vec3> = (0..=8)
        .map(|k| Vec3::new(0.0, HEIGHT, 0.0) + along * LENGTH * (k as f32 / 8.0 - 0.5))
        .collect();
    let mut data = one_strand_scene("wide_strand_rays.toml", &text, &points, thickness, 0.9);
    for corner in [-1.0f32, 1.0] {
        let end = Vec3::new(corner * HALF, HEIGHT, corner * HALF * aspect / COS_I);
        let inward = Vec3::new(-corner * 0.05, 0.0, 0.0);
        data.strands
            .push_strand(&[end, end + inward], |_| 1e-4, |_| 1.0, Vec3::ONE);
    }
    data
}

/// World size of a texel of a `size`-texel light map, across x and y.
fn texel(m: Mat4, size: u32) -> Vec2 {
    let row = |i: usize| Vec3::new(m.col(0)[i], m.col(1)[i], m.col(2)[i]).length();
    Vec2::new(2.0 / (row(0) * size as f32), 2.0 / (row(1) * size as f32))
}

/// A strand, its receiver points (probe rays at one light depth 0.1 past
/// the strand's middle along the light, a window of WINDOW fine texels
/// around it) and what the CPU needs to place them.
struct Setup {
    data: SceneData,
    grid: ProbeGrid,
    inverse: Mat4,
    to_light: Vec3,
    axis: (Vec3, Vec3),
    radius: f32,
}

/// The strand `texels_wide` texels of the fine map wide (across x).
fn setup(texels_wide: f32, degrees: f32, aspect: f32) -> Setup {
    let probe = scene(1e-3, degrees, aspect);
    let frame = probe.frame(SIZE, 0);
    let m = Mat4::from_cols_array_2d(&frame.light_view_proj);
    let thickness = texels_wide * texel(m, FINE).x;
    let data = scene(thickness, degrees, aspect);
    let frame = data.frame(SIZE, 0);
    let m = Mat4::from_cols_array_2d(&frame.light_view_proj);
    let inverse = Mat4::from_cols_array_2d(&frame.light_inv_view_proj);
    let to_light = -Vec3::from(LIGHT).normalize();
    let mid = Vec3::new(0.0, HEIGHT, 0.0);
    let c = m.project_point3(mid);
    let receiver = m.project_point3(mid - to_light * 0.1).z;
    let uv = Vec2::new(c.x * 0.5 + 0.5, 0.5 - c.y * 0.5);
    let half = 0.5 * WINDOW / FINE as f32;
    let n = (WINDOW as u32) * PER_TEXEL + 1;
    let grid = ProbeGrid {
        uv0: [uv.x - half, uv.y - half],
        uv1: [uv.x + half, uv.y + half],
        rays: (n, n),
        depths: 2,
        depth_range: (receiver, receiver),
    };
    let (s, co) = degrees.to_radians().sin_cos();
    Setup {
        data,
        grid,
        inverse,
        to_light,
        axis: (mid, Vec3::new(co, 0.0, s)),
        radius: 0.5 * thickness,
    }
}

impl Setup {
    fn world(&self, uv: Vec2, z: f32) -> Vec3 {
        self.inverse
            .project_point3(Vec3::new(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, z))
    }

    /// 1 where the ray from `p` toward the light passes within the radius of
    /// the strand's axis (an infinite line here: the window is far from its ends).
    fn analytic(&self, p: Vec3) -> f64 {
        let (a, e) = self.axis;
        let n = self.to_light.cross(e).normalize();
        f64::from(u8::from((p - a).dot(n).abs() < self.radius))
    }

    /// The band's coverage of the light texel of a `size` map holding uv:
    /// its 16 × 16 sub-points' `analytic`.
    fn texel_coverage(&self, uv: Vec2, z: f32, size: u32) -> f64 {
        let t = (uv * size as f32).floor();
        let k = 16;
        let mut sum = 0.0;
        for i in 0..k {
            for j in 0..k {
                let sub = (t + Vec2::new((i as f32 + 0.5) / k as f32, (j as f32 + 0.5) / k as f32))
                    / size as f32;
                sum += self.analytic(self.world(sub, z));
            }
        }
        sum / (k * k) as f64
    }

    /// The band's extent across a column of a `size` map, in texels: its
    /// end points a texel apart along x, projected, give the strand's slope
    /// there; the width across it over cos of the angle is the column's part.
    fn band_extent(&self, size: u32) -> f64 {
        let frame = self.data.frame(SIZE, 0);
        let m = Mat4::from_cols_array_2d(&frame.light_view_proj);
        let on_map = |p: Vec3| {
            let ndc = m.project_point3(p);
            Vec2::new(ndc.x, -ndc.y) * 0.5 * size as f32
        };
        let (a, e) = self.axis;
        let dir = (on_map(a + e * 0.1) - on_map(a)).normalize();
        let side = self.to_light.cross(e).normalize() * 2.0 * self.radius;
        let across = on_map(a + side) - on_map(a);
        f64::from((across.x * dir.y - across.y * dir.x).abs() / dir.x.abs())
    }
}

/// The strands in front of each receiver point (one per probe ray: both of
/// its depths are the receiver's).
fn counts(gpu: &plait_gpu::Gpu, s: &Setup, sets: &[String]) -> Vec<f64> {
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let source = PipelineSource::new(&pipeline, sets);
    probe_with(
        gpu,
        &source,
        &s.data,
        SIZE,
        &s.grid,
        "tests/fixtures/strands_probe.wgsl",
    )
    .unwrap_or_else(|e| panic!("{sets:?}: {e}"))
    .expect("a provider")
    .values
    .chunks_exact(2)
    .map(|d| f64::from(d[0]))
    .collect()
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

fn mean_abs_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f64>() / a.len() as f64
}

/// For each texel shape and width, at 30° to the rows (not along them: an
/// axis-aligned band against the regular points and sub-points aliases by
/// a few per cent): the ray counts the closed form (|Δ| < 1e-3, measured 0);
/// exact at 1024 holds the band's coverage of each point's texel (mean
/// |Δ| < 0.002, measured 0.0006–0.0009, and its mean within 1 % of the
/// coverage's, measured 0.0–0.4 %; with the quad's half width the side's
/// whole image, on the tall texels: +2.1 %, +2.2 %); and its
/// difference from the ray, the texel's averaging, falls with the texel
/// (below 0.75 of the difference at 512, measured 0.50–0.69).
#[test]
fn exact_holds_the_bands_coverage_of_each_texel_and_converges_to_the_ray() {
    let (_lock, gpu) = open_gpu();
    let mut failures = Vec::new();
    for aspect in [1.0f32, 1.3] {
        for texels_wide in [2.0f32, 4.0] {
            let s = setup(texels_wide, 30.0, aspect);
            let z = s.grid.depth_range.0;
            let points: Vec<(Vec2, Vec3)> = (0..s.grid.ray_count() as u32)
                .map(|r| {
                    let uv = Vec2::from(s.grid.ray_uv(r));
                    (uv, s.world(uv, z))
                })
                .collect();
            let closed: Vec<f64> = points.iter().map(|&(_, p)| s.analytic(p)).collect();
            let ray = counts(
                &gpu,
                &s,
                &[
                    "techniques.self_shadow=ray_traced".into(),
                    "params.shadow_meshes=0".into(),
                ],
            );
            let label = format!("aspect {aspect}, {texels_wide} texels");
            let ray_error = mean_abs_difference(&ray, &closed);
            if ray_error > 1e-3 {
                failures.push(format!("{label}: ray vs closed form {ray_error:.4}"));
            }
            let mut to_ray = Vec::new();
            for size in [512u32, 1024] {
                let exact = counts(
                    &gpu,
                    &s,
                    &[
                        "techniques.self_shadow=exact".into(),
                        format!("params.light_size={size}"),
                    ],
                );
                let coverage: Vec<f64> = points
                    .iter()
                    .map(|&(uv, _)| s.texel_coverage(uv, z, size))
                    .collect();
                let (to_coverage, ratio) = (
                    mean_abs_difference(&exact, &coverage),
                    mean(&exact) / mean(&coverage),
                );
                to_ray.push(mean_abs_difference(&exact, &ray));
                eprintln!(
                    "{label}, exact@{size}: mean n {:.4} (texel coverage {:.4}, ray {:.4}); mean |Δ| to the coverage {to_coverage:.4}, to the ray {:.4}",
                    mean(&exact),
                    mean(&coverage),
                    mean(&ray),
                    to_ray[to_ray.len() - 1]
                );
                if size == FINE && (to_coverage > 0.002 || (ratio - 1.0).abs() > 0.01) {
                    failures.push(format!(
                        "{label}: exact@{size} vs the band's texel coverage: mean |Δ| {to_coverage:.4}, ratio {ratio:.4}"
                    ));
                }
            }
            if to_ray[1] > 0.75 * to_ray[0] {
                failures.push(format!(
                    "{label}: exact to the ray {:.4} at 512, {:.4} at 1024",
                    to_ray[0], to_ray[1]
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A strand narrower than a light texel is a line, each fragment holding
/// the band's width across the strand: lavapipe draws a line as a rectangle
/// one texel wide (1.13 fragments per column at 27° to the rows, 1 / cos 27°
/// = 1.12), so over 120 columns of the 512 map the shares sum to the band's
/// extent per column, its width ÷ cos of its angle, within 2 % (measured
/// −1.2 % to +1.5 %), on square texels and on texels twice as tall as wide.
/// With the share the side's whole image (as before the fix) the tall
/// texels read +17 % at 30° (0.684 against 0.584) and +2.2 % at 10°.
#[test]
fn a_lines_shares_sum_to_its_band() {
    let (_lock, gpu) = open_gpu();
    let size = 512usize;
    let mut failures = Vec::new();
    // (aspect, degrees, texels of the fine map wide): lines at 512.
    for (aspect, degrees, wide) in [
        (1.0f32, 30.0f32, 1.6f32),
        (1.0, 10.0, 1.6),
        (2.0, 30.0, 2.0),
        (2.0, 10.0, 2.0),
    ] {
        let s = setup(wide, degrees, aspect);
        let sets = [
            format!("params.light_size={size}"),
            "techniques.self_shadow=exact".to_string(),
        ];
        let pipeline = repo_root().join("pipelines/occupancy.toml");
        let prepared = plait::session::prepare(&gpu, &pipeline, &sets, &s.data, SIZE)
            .unwrap_or_else(|e| panic!("{sets:?}: {e}"));
        prepared.render().expect("renders");
        let words = |name: &str| -> Vec<u32> {
            prepared
                .read_buffer(name)
                .expect(name)
                .chunks_exact(4)
                .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                .collect()
        };
        let (lists, counts) = (words("light_lists"), words("light_counts"));
        let capacity = lists.len() / (size * size);
        let centre =
            ((Vec2::from(s.grid.uv0) + Vec2::from(s.grid.uv1)) * 0.5 * size as f32).as_ivec2();
        let mut sum = 0.0;
        for x in (centre.x - 60)..(centre.x + 60) {
            for y in (centre.y - 40)..(centre.y + 40) {
                let t = y as usize * size + x as usize;
                let n = (counts[t] as usize).min(capacity);
                // Each entry's share in its low 8 bits (plait::map_share).
                sum += lists[t * capacity..t * capacity + n]
                    .iter()
                    .map(|&e| f64::from(e & 0xFF) / 255.0)
                    .sum::<f64>();
            }
        }
        let per_column = sum / 120.0;
        let expected = s.band_extent(size as u32);
        eprintln!(
            "aspect {aspect}, {degrees}°: Σ share per column {per_column:.4}, band {expected:.4}"
        );
        if (per_column / expected - 1.0).abs() > 0.02 || expected >= 1.0 {
            failures.push(format!(
                "aspect {aspect}, {degrees}°: {per_column:.4} vs {expected:.4}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
