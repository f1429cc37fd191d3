//! Guide strands and barycentric interpolation (Halén & Wester 2007 §2.5):
//! guides grow at the vertices of a grid over the scalp's parameter square,
//! and each rendered strand blends the three guides of the triangle its root
//! falls in.

use glam::Vec3;

use super::grow::{
    StrandLook, add_waves, comb, grow, head_point, look, push, sample_root, scalp_dir,
};
use super::spec::GroomSpec;
use crate::guides::{GuideBinding, Guides};
use crate::rng::SplitMix64;
use crate::strands::Strands;

/// Guide grid layout for about `g` guides: `rows` polar rings (u = 0..=1)
/// times `cols` azimuth columns (v wraps around).
pub(super) fn guide_grid(g: u32) -> (usize, usize) {
    let rows = ((g as f32 / 2.0).sqrt().round() as usize).max(2);
    let cols = (g as usize / rows).max(3);
    (rows, cols)
}

/// The triangle of the guide grid that scalp parameter (u, v) falls in:
/// grid corners `(row, col)` (col may equal `cols`, meaning column 0) and
/// barycentric weights (≥ 0, summing to 1). Each grid cell is split along
/// its anti-diagonal into two triangles.
pub(super) fn locate(u: f32, v: f32, rows: usize, cols: usize) -> ([(usize, usize); 3], [f32; 3]) {
    let fu = u.clamp(0.0, 1.0) * (rows - 1) as f32;
    let fv = v.clamp(0.0, 1.0) * cols as f32;
    let i = (fu.floor() as usize).min(rows - 2);
    let j = (fv.floor() as usize).min(cols - 1);
    let (a, b) = (
        (fu - i as f32).clamp(0.0, 1.0),
        (fv - j as f32).clamp(0.0, 1.0),
    );
    if a + b <= 1.0 {
        ([(i, j), (i + 1, j), (i, j + 1)], [1.0 - a - b, a, b])
    } else {
        (
            [(i + 1, j + 1), (i, j + 1), (i + 1, j)],
            [a + b - 1.0, 1.0 - a, 1.0 - b],
        )
    }
}

/// Barycentric blend of three guide strands (Halén & Wester 2007 §2.5), translated so it
/// starts at `root`, its offsets from the root scaled by `scale`.
pub(super) fn blend(tri: [&Vec<Vec3>; 3], w: [f32; 3], root: Vec3, scale: f32) -> Vec<Vec3> {
    let n = tri.iter().map(|g| g.len()).min().unwrap_or(0);
    if n == 0 {
        return Vec::new();
    }
    let at = |k: usize| tri[0][k] * w[0] + tri[1][k] * w[1] + tri[2][k] * w[2];
    let start = at(0);
    (0..n).map(|k| root + (at(k) - start) * scale).collect()
}

pub(super) fn interpolate_from_guides(
    spec: &GroomSpec,
    g: u32,
    strands: &mut Strands,
    lift_of: impl Fn(f32) -> f32,
) -> Guides {
    let (rows, cols) = guide_grid(g);
    // Guides: grown with the mean length, with their own wave phase.
    let mut guides: Vec<Vec<Vec3>> = Vec::with_capacity(rows * cols);
    for i in 0..rows {
        for j in 0..cols {
            let u = i as f32 / (rows - 1) as f32;
            let v = j as f32 / cols as f32;
            let mut rng = SplitMix64::stream(spec.seed ^ 0x006D_1DE5, (i * cols + j) as u64);
            let phase = rng.range(0.0, std::f32::consts::TAU);
            let (root, normal) = head_point(spec, scalp_dir(spec, u, v));
            let mut pts = grow(
                spec,
                root,
                comb(normal, v),
                spec.length,
                spec.gravity,
                lift_of(u),
            );
            add_waves(spec, &mut pts, phase);
            guides.push(pts);
        }
    }
    let index = |i: usize, j: usize| i.min(rows - 1) * cols + j % cols;
    let mut bindings = Vec::with_capacity(spec.strands as usize);
    for s in 0..spec.strands {
        let mut rng = SplitMix64::stream(spec.seed, u64::from(s));
        let (u, v) = sample_root(spec, &mut rng);
        let lk = look(spec, &mut rng);
        let (corners, w) = locate(u, v, rows, cols);
        let ids = corners.map(|(i, j)| index(i, j));
        let tri = ids.map(|k| &guides[k]);
        let (root, _) = head_point(spec, scalp_dir(spec, u, v));
        let scale = lk.length / spec.length.max(1e-6);
        let pts = blend(tri, w, root, scale);
        push(strands, spec, &pts, &lk);
        bindings.push(GuideBinding {
            guides: ids.map(|k| k as u32),
            weights: w,
            root,
            scale,
        });
    }
    let mut guide_strands = Strands::new();
    for pts in &guides {
        let lk = StrandLook {
            length: spec.length,
            thickness: spec.thickness,
            alpha: spec.alpha,
            color: Vec3::from(spec.color),
            phase: 0.0,
        };
        push(&mut guide_strands, spec, pts, &lk);
    }
    Guides {
        strands: guide_strands,
        bindings,
    }
}
