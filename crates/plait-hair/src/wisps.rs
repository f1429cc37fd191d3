//! Polygon wisps (Halén & Wester, "Real-Time Hair Simulation and
//! Visualization for Games", M.Sc. thesis, Lund University, 2007, §2.2–2.4,
//! §5.4): wisp centres spread over the scalp by relaxation dart throwing
//! (Lagae & Dutré 2005, as §2.2 uses it), each wisp a triangle strip along its
//! guide strand, as wide as the `wisp_width` param (the vertex shader turns
//! it to face the camera and moves it with the hair vertices it stands for,
//! `techniques/geometry/wisps/geometry.wgsl`). The wisps are stored in the
//! order their centres were accepted, a progressive Poisson-disk sample:
//! the wisps' level of detail draws a prefix of them (§2.4).
//!
//! On the CPU, once at load: the thesis makes wisps as a preprocessing step
//! ("there is no need for a fast algorithm", §2.2), dart throwing is
//! sequential (every dart tests the darts accepted before it), and a few
//! hundred to a few thousand wisps take milliseconds.
//!
//! The scalp is where the groom's strands are rooted: a dart is a strand root
//! drawn at random, so darts fall on the scalp with the groom's own root
//! density, whatever the scalp's shape or mesh.

use glam::Vec3;

use crate::guides::Guides;
use crate::rng::SplitMix64;
use crate::strands::{StrandVertex, Strands};

/// Consecutive rejected darts after which the collision radius shrinks
/// (relaxation dart throwing, Lagae & Dutré 2005, as Halén & Wester 2007
/// §2.2 describes it: "if a large number of failed attempts … occur, the
/// collision radius is reduced by a fraction"). The thesis gives no numbers.
pub const RELAXATION_FAILURES: u32 = 64;
/// The fraction the radius keeps at each relaxation step.
pub const RELAXATION_FACTOR: f32 = 0.9;
/// The seed of the darts: wisps are the same at every load.
pub const WISP_SEED: u64 = 0x5749_5350_5345_4544;

/// Centres chosen by relaxation dart throwing.
#[derive(Debug, Clone, PartialEq)]
pub struct Darts {
    /// Indices into the candidate points, in the order accepted.
    pub chosen: Vec<usize>,
    /// The collision radius when the last dart was accepted: every two
    /// chosen points lie at least this far apart (the radius only shrinks).
    pub radius: f32,
}

/// `count` of `candidates` at least [`Darts::radius`] apart: darts drawn at
/// random (seeded), a dart within the radius of an accepted one rejected,
/// and the radius shrunk by [`RELAXATION_FACTOR`] after
/// [`RELAXATION_FAILURES`] rejections in a row, starting from the
/// candidates' bounding-box diagonal. Fewer than `count` only when fewer
/// than `count` candidates lie apart at all (duplicated roots).
pub fn relaxation_dart_throwing(candidates: &[Vec3], count: usize, seed: u64) -> Darts {
    let mut chosen: Vec<usize> = Vec::with_capacity(count);
    let lo = candidates
        .iter()
        .fold(Vec3::splat(f32::MAX), |a, &p| a.min(p));
    let hi = candidates
        .iter()
        .fold(Vec3::splat(f32::MIN), |a, &p| a.max(p));
    let mut radius = if candidates.is_empty() {
        0.0
    } else {
        (hi - lo).length()
    };
    // Below this the radius cannot separate distinct f32 points: stop.
    let floor = radius * 1e-6;
    let mut rng = SplitMix64::new(seed);
    let mut failures = 0;
    let mut accepted_radius = radius;
    // The first dart is always accepted, also when every candidate is one
    // point (radius 0 = floor): a groom of one strand gets its one wisp.
    while chosen.len() < count && !candidates.is_empty() && (radius > floor || chosen.is_empty()) {
        let i = (rng.next_u64() % candidates.len() as u64) as usize;
        let p = candidates[i];
        let r2 = radius * radius;
        if chosen
            .iter()
            .all(|&c| candidates[c].distance_squared(p) >= r2)
        {
            chosen.push(i);
            accepted_radius = radius;
            failures = 0;
        } else {
            failures += 1;
            if failures >= RELAXATION_FAILURES {
                radius *= RELAXATION_FACTOR;
                failures = 0;
            }
        }
    }
    Darts {
        chosen,
        radius: accepted_radius,
    }
}

/// One wisp vertex on the GPU (48 bytes, `#[repr(C)]`): the hair vertex
/// layout's slots ([`StrandVertex`], so every hair draw's vertex stage reads
/// it, locations 0–5) holding what a wisp vertex needs to follow the hair
/// vertex it stands for (`techniques/geometry/wisps/geometry.wgsl`,
/// `wisp_point`). Its colour, alpha and current place come from that hair
/// vertex in the scene's `hair_vertices` every frame.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct WispVertex {
    /// `position`: the wisp's spine point minus the hair vertex's position,
    /// at rest (0 when the wisp follows the strand rooted at its centre).
    pub offset: [f32; 3],
    /// `thickness`: how far along its wisp the vertex lies, 0 at the root, 1
    /// at the tip (the strand texture's v).
    pub along: f32,
    /// `tangent`: the hair vertex's tangent at rest, the frame the offset is
    /// kept in (the shader turns the offset as that tangent has turned).
    pub rest_tangent: [f32; 3],
    /// `alpha`: the hair vertex's index along its strand (0 at the root), so
    /// strand-space shading finds the radiance shaded there.
    pub point: f32,
    /// `color`: x = the wisp's place in the dart throwing's acceptance order,
    /// y = the mesh's wisp count (the wisps' own level of detail draws the
    /// first k: a progressive Poisson-disk sample), z = 0.
    pub order: [f32; 3],
    /// `strand_id`: the hair vertex it stands for — the point at the same
    /// fraction along the strand rooted at the wisp's centre.
    pub hair_vertex: u32,
}

const _: () = assert!(std::mem::size_of::<WispVertex>() == std::mem::size_of::<StrandVertex>());

/// The wisps' triangle list on the GPU, wisp after wisp in the order their
/// centres were accepted. The vertices come in pairs, one per side of the
/// strip (even = left, odd = right): the vertex shader offsets them across
/// the view.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WispMesh {
    pub vertices: Vec<WispVertex>,
    pub indices: Vec<u32>,
    pub wisp_count: usize,
    /// The dart throwing's final collision radius (model units).
    pub radius: f32,
}

/// Whether the wisps followed the groom's guides or, having none, its strands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WispGuides {
    Guides,
    Strands,
}

/// `count` wisps over `strands`' roots, each along its nearest guide of
/// `guides` (moved to the wisp's centre), or along the strand rooted at its
/// centre when the groom has no guides ([`Guides::is_identity`]).
pub fn build_wisps(strands: &Strands, guides: &Guides, count: usize) -> (WispMesh, WispGuides) {
    let roots: Vec<Vec3> = strands
        .ranges()
        .map(|r| strands.points.get(r.start).copied().unwrap_or(Vec3::ZERO))
        .collect();
    let darts = relaxation_dart_throwing(&roots, count, WISP_SEED);
    let own = guides.is_identity() || guides.strands.strand_count() == 0;
    let (followed, kind) = if own {
        (strands, WispGuides::Strands)
    } else {
        (&guides.strands, WispGuides::Guides)
    };
    let guide_roots: Vec<Vec3> = followed
        .ranges()
        .map(|r| followed.points.get(r.start).copied().unwrap_or(Vec3::ZERO))
        .collect();
    let (guide_vertices, _) = followed.line_list();
    // The hair at rest as it is uploaded: the offsets and rest tangents
    // are taken from it.
    let (hair, _) = strands.line_list();
    let mut mesh = WispMesh {
        radius: darts.radius,
        ..WispMesh::default()
    };
    for &s in &darts.chosen {
        let centre = roots[s];
        let g = if own {
            s
        } else {
            nearest(&guide_roots, centre)
        };
        let range = followed.strand_range(g);
        let source = strands.strand_range(s);
        if range.len() < 2 || source.is_empty() {
            continue;
        }
        let shift = centre - guide_roots[g];
        let base = mesh.vertices.len() as u32;
        let last = (range.len() - 1) as f32;
        let order = mesh.wisp_count as f32;
        for (j, k) in range.clone().enumerate() {
            let t = j as f32 / last;
            let point = (t * (source.len() - 1) as f32).round() as usize;
            let src = source.start + point;
            let spine = Vec3::from(guide_vertices[k].position) + shift;
            let vertex = WispVertex {
                offset: (spine - Vec3::from(hair[src].position)).to_array(),
                along: t,
                rest_tangent: hair[src].tangent,
                point: point as f32,
                order: [order, 0.0, 0.0],
                hair_vertex: src as u32,
            };
            mesh.vertices.extend([vertex, vertex]);
        }
        for j in 0..range.len() as u32 - 1 {
            let (a, b, c, d) = (
                base + 2 * j,
                base + 2 * j + 1,
                base + 2 * j + 2,
                base + 2 * j + 3,
            );
            mesh.indices.extend([a, b, c, b, d, c]);
        }
        mesh.wisp_count += 1;
    }
    let total = mesh.wisp_count as f32;
    for v in &mut mesh.vertices {
        v.order[1] = total;
    }
    (mesh, kind)
}

fn nearest(points: &[Vec3], p: Vec3) -> usize {
    points
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.distance_squared(p).total_cmp(&b.1.distance_squared(p)))
        .map_or(0, |(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize) -> Vec<Vec3> {
        let mut rng = SplitMix64::new(7);
        (0..n)
            .map(|_| Vec3::new(rng.signed(), rng.signed(), 0.0))
            .collect()
    }

    #[test]
    fn one_candidate_gets_its_dart() {
        // All candidates one point: the radius starts at 0. No dart was
        // thrown, so a one-strand groom had no wisps at all.
        let darts = relaxation_dart_throwing(&[Vec3::ONE], 3, 1);
        assert_eq!(darts.chosen, vec![0]);
        let darts = relaxation_dart_throwing(&[Vec3::ONE, Vec3::ONE], 3, 1);
        assert_eq!(darts.chosen.len(), 1);
    }

    #[test]
    fn darts_keep_a_minimum_distance_and_are_deterministic() {
        let points = grid(4000);
        let darts = relaxation_dart_throwing(&points, 200, WISP_SEED);
        assert_eq!(darts.chosen.len(), 200);
        // Poisson-disk property: no two centres closer than the final radius.
        let mut closest = f32::MAX;
        for (i, &a) in darts.chosen.iter().enumerate() {
            for &b in &darts.chosen[i + 1..] {
                closest = closest.min(points[a].distance(points[b]));
            }
        }
        assert!(closest >= darts.radius, "{closest} < {}", darts.radius);
        // And the radius is that of an even spread, not a tiny one: 200
        // disks of radius r/2 packed in the 2×2 square cover at most ~0.9 of
        // it, so r ≈ 2·sqrt(0.9 · 4 / (200 π)) ≈ 0.15; pure random picks
        // would come as close as ~0.01.
        assert!(darts.radius > 0.08, "radius {}", darts.radius);
        assert!(closest > 0.08, "closest {closest}");
        assert_eq!(darts, relaxation_dart_throwing(&points, 200, WISP_SEED));
        assert_ne!(darts, relaxation_dart_throwing(&points, 200, WISP_SEED + 1));
    }

    #[test]
    fn darts_stop_when_the_candidates_run_out() {
        let points = vec![Vec3::ZERO, Vec3::ZERO, Vec3::X];
        let darts = relaxation_dart_throwing(&points, 3, 1);
        assert_eq!(darts.chosen.len(), 2);
    }

    #[test]
    fn a_wisp_is_a_strip_along_its_strand() {
        let mut strands = Strands::new();
        for x in 0..10 {
            let root = Vec3::new(x as f32, 0.0, 0.0);
            strands.push_strand(
                &[root, root + Vec3::Y, root + 2.0 * Vec3::Y],
                |_| 0.01,
                |_| 1.0,
                Vec3::ONE,
            );
        }
        let (mesh, kind) = build_wisps(&strands, &Guides::identity(&strands), 4);
        assert_eq!(kind, WispGuides::Strands);
        assert_eq!(mesh.wisp_count, 4);
        // 3 points × 2 sides, 2 segments × 2 triangles per wisp.
        assert_eq!(mesh.vertices.len(), 4 * 6);
        assert_eq!(mesh.indices.len(), 4 * 12);
        let v = &mesh.vertices[..6];
        assert_eq!(v[0].along, 0.0);
        assert_eq!(v[5].along, 1.0);
        // Each vertex names the hair vertex it stands for, lies on it (no
        // guides: no offset) and knows its place along the strand.
        let src = v[2].hair_vertex as usize;
        assert_eq!(v[2].offset, [0.0; 3]);
        assert_eq!(v[2].point, 1.0);
        assert_eq!(strands.points[src], strands.points[src - 1] + Vec3::Y);
        // Wisps in acceptance order, each knowing how many there are.
        assert_eq!(mesh.vertices[6].order, [1.0, 4.0, 0.0]);
    }
}
