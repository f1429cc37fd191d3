//! A signed distance field of a closed triangle mesh on a regular grid, the
//! head mesh's collider in the simulation (`shaders/passes/sim_verlet.wgsl`
//! samples it trilinearly and moves a node inside out along its gradient).
//!
//! Baked once per mesh on the CPU, in three steps that keep it fast for a
//! head (milliseconds at 32³): exact distances to the nearest triangle in a
//! band of two cells around each triangle; the nearest triangle passed on to
//! the rest of the grid by sweeps in the eight diagonal orders, each grid
//! point taking the nearer of its neighbours' triangles (the exact distance
//! to it, so errors do not accumulate); and the sign by parity — a grid point
//! is inside when a ray along +x from it crosses the surface an odd number of
//! times. Parity needs a closed mesh (a head open at the neck is inside-out
//! along rays through the opening); docs/formats.md says so.

use glam::Vec3;

use crate::mesh::Mesh;

/// Distances (model units) at grid points `origin + cell · (i, j, k)`,
/// negative inside, `x` fastest.
#[derive(Debug, Clone, PartialEq)]
pub struct SignedDistanceField {
    /// The grid's first corner.
    pub origin: Vec3,
    /// Spacing of the grid points (cubic cells).
    pub cell: f32,
    /// Grid points along x, y, z.
    pub dims: [u32; 3],
    /// One distance per grid point.
    pub values: Vec<f32>,
}

/// Edges of `mesh` that do not border exactly two triangles, with vertices
/// at the same place (within a millionth of the mesh's size) taken as one: 0
/// for a closed surface, which the field's sign by parity needs. Counted
/// once per edge; returns the count and one such edge's end points.
pub fn open_edges(mesh: &Mesh) -> (usize, Option<[Vec3; 2]>) {
    use std::collections::HashMap;
    let points: Vec<Vec3> = mesh
        .vertices
        .iter()
        .map(|v| Vec3::from(v.position))
        .collect();
    let (lo, hi) = points.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    // Welding by rounding alone splits two nearly equal points that straddle
    // a cell boundary; each point looks in the 27 cells around its own for
    // an earlier one within `tolerance`.
    let tolerance = ((hi - lo).max_element() * 1e-6).max(f32::MIN_POSITIVE);
    let cell = |p: Vec3| ((p - lo) / tolerance).floor().as_ivec3();
    let mut grid: HashMap<[i32; 3], Vec<(Vec3, u32)>> = HashMap::new();
    let mut count = 0u32;
    let ids: Vec<u32> = points
        .iter()
        .map(|&p| {
            let c = cell(p);
            for dz in -1..=1 {
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let near = grid.get(&(c + glam::IVec3::new(dx, dy, dz)).to_array());
                        if let Some(&(_, id)) = near
                            .into_iter()
                            .flatten()
                            .find(|(q, _)| (*q - p).abs().max_element() <= tolerance)
                        {
                            return id;
                        }
                    }
                }
            }
            count += 1;
            grid.entry(c.to_array()).or_default().push((p, count - 1));
            count - 1
        })
        .collect();
    let mut edges: HashMap<(u32, u32), (u32, [Vec3; 2])> = HashMap::new();
    for t in mesh.indices.chunks_exact(3) {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            let (i, j) = (ids[a as usize], ids[b as usize]);
            if i == j {
                continue; // a collapsed edge (a pole) borders nothing
            }
            let e = edges
                .entry((i.min(j), i.max(j)))
                .or_insert((0, [points[a as usize], points[b as usize]]));
            e.0 += 1;
        }
    }
    let open: Vec<&[Vec3; 2]> = edges
        .values()
        .filter(|(n, _)| *n != 2)
        .map(|(_, e)| e)
        .collect();
    (open.len(), open.first().map(|e| **e))
}

/// Floats before the distances in [`SignedDistanceField::gpu_words`].
pub const GPU_HEADER_WORDS: usize = 8;

impl SignedDistanceField {
    /// Bakes the field of `mesh` with `resolution` grid points along the
    /// longest side of its bounds (grown by a tenth of that side on every
    /// side, so the surface is never at the grid's edge). `resolution` is
    /// raised to 4 at least.
    pub fn bake(mesh: &Mesh, resolution: u32) -> SignedDistanceField {
        let resolution = resolution.max(4);
        let points: Vec<Vec3> = mesh
            .vertices
            .iter()
            .map(|v| Vec3::from(v.position))
            .collect();
        let (lo, hi) = points.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let longest = (hi - lo).max_element().max(1e-6);
        let margin = 0.1 * longest;
        let cell = (longest + 2.0 * margin) / (resolution - 1) as f32;
        let origin = lo - Vec3::splat(margin);
        let dims = ((hi + Vec3::splat(margin) - origin) / cell)
            .ceil()
            .as_uvec3()
            .to_array()
            .map(|n| n + 1);
        let triangles: Vec<[Vec3; 3]> = mesh
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]].map(|i| points[i as usize]))
            .collect();
        let mut grid = Grid::new(origin, cell, dims);
        grid.near_band(&triangles);
        grid.sweep(&triangles);
        let inside = grid.parity(&triangles);
        let values = grid
            .distance
            .iter()
            .zip(&inside)
            .map(|(d, &i)| if i { -d } else { *d })
            .collect();
        SignedDistanceField {
            origin,
            cell,
            dims,
            values,
        }
    }

    /// The trilinear interpolation at `p`, `None` outside the grid.
    pub fn sample(&self, p: Vec3) -> Option<f32> {
        let g = (p - self.origin) / self.cell;
        let top = glam::UVec3::from(self.dims).as_vec3() - Vec3::ONE;
        if g.min_element() < 0.0 || (g - top).max_element() > 0.0 {
            return None;
        }
        let base = g.floor().min(top - Vec3::ONE).max(Vec3::ZERO);
        let f = g - base;
        let b = base.as_uvec3();
        let at = |dx: u32, dy: u32, dz: u32| {
            let [nx, ny, _] = self.dims;
            self.values[((b.z + dz) * ny * nx + (b.y + dy) * nx + b.x + dx) as usize]
        };
        let x00 = at(0, 0, 0) + f.x * (at(1, 0, 0) - at(0, 0, 0));
        let x10 = at(0, 1, 0) + f.x * (at(1, 1, 0) - at(0, 1, 0));
        let x01 = at(0, 0, 1) + f.x * (at(1, 0, 1) - at(0, 0, 1));
        let x11 = at(0, 1, 1) + f.x * (at(1, 1, 1) - at(0, 1, 1));
        let y0 = x00 + f.y * (x10 - x00);
        let y1 = x01 + f.y * (x11 - x01);
        Some(y0 + f.z * (y1 - y0))
    }

    /// The layout of the `head_sdf` scene resource: origin xyz, cell, the
    /// dims as u32 bits, 1.0 (a field is present), then the distances.
    pub fn gpu_words(&self) -> Vec<f32> {
        let mut words = Vec::with_capacity(GPU_HEADER_WORDS + self.values.len());
        words.extend(self.origin.to_array());
        words.push(self.cell);
        words.extend(self.dims.map(f32::from_bits));
        words.push(1.0);
        words.extend(&self.values);
        words
    }
}

/// The bake's working state: unsigned distances and each point's nearest
/// triangle (`u32::MAX`: none yet).
struct Grid {
    origin: Vec3,
    cell: f32,
    dims: [u32; 3],
    distance: Vec<f32>,
    nearest: Vec<u32>,
}

impl Grid {
    fn new(origin: Vec3, cell: f32, dims: [u32; 3]) -> Grid {
        let n = dims.iter().map(|&d| d as usize).product();
        Grid {
            origin,
            cell,
            dims,
            distance: vec![f32::INFINITY; n],
            nearest: vec![u32::MAX; n],
        }
    }

    fn index(&self, i: u32, j: u32, k: u32) -> usize {
        ((k * self.dims[1] + j) * self.dims[0] + i) as usize
    }

    fn point(&self, i: u32, j: u32, k: u32) -> Vec3 {
        self.origin + self.cell * Vec3::new(i as f32, j as f32, k as f32)
    }

    /// Grid index range of coordinates `lo..=hi` (clamped to the grid).
    fn span(&self, lo: Vec3, hi: Vec3) -> ([u32; 3], [u32; 3]) {
        let top = glam::UVec3::from(self.dims) - glam::UVec3::ONE;
        let a = ((lo - self.origin) / self.cell)
            .floor()
            .max(Vec3::ZERO)
            .as_uvec3()
            .min(top);
        let b = ((hi - self.origin) / self.cell)
            .ceil()
            .max(Vec3::ZERO)
            .as_uvec3()
            .min(top);
        (a.to_array(), b.to_array())
    }

    fn near_band(&mut self, triangles: &[[Vec3; 3]]) {
        for (t, tri) in triangles.iter().enumerate() {
            let lo = tri[0].min(tri[1]).min(tri[2]) - Vec3::splat(2.0 * self.cell);
            let hi = tri[0].max(tri[1]).max(tri[2]) + Vec3::splat(2.0 * self.cell);
            let (a, b) = self.span(lo, hi);
            for k in a[2]..=b[2] {
                for j in a[1]..=b[1] {
                    for i in a[0]..=b[0] {
                        let d = point_triangle_distance(self.point(i, j, k), tri);
                        let n = self.index(i, j, k);
                        if d < self.distance[n] {
                            self.distance[n] = d;
                            self.nearest[n] = t as u32;
                        }
                    }
                }
            }
        }
    }

    /// Two rounds of sweeps in the 8 diagonal orders; a point takes a
    /// neighbour's (the one before it along each axis) nearest triangle when
    /// that triangle is nearer than its own.
    fn sweep(&mut self, triangles: &[[Vec3; 3]]) {
        let [nx, ny, nz] = self.dims.map(|d| d as i64);
        for _round in 0..2 {
            for order in 0..8 {
                let step = [
                    1 - 2 * (order & 1),
                    1 - 2 * ((order >> 1) & 1),
                    1 - 2 * ((order >> 2) & 1),
                ];
                let range = |n: i64, s: i64| -> Vec<i64> {
                    if s > 0 {
                        (0..n).collect()
                    } else {
                        (0..n).rev().collect()
                    }
                };
                for k in range(nz, step[2]) {
                    for j in range(ny, step[1]) {
                        for i in range(nx, step[0]) {
                            let here = self.index(i as u32, j as u32, k as u32);
                            let p = self.point(i as u32, j as u32, k as u32);
                            for (di, dj, dk) in [(step[0], 0, 0), (0, step[1], 0), (0, 0, step[2])]
                            {
                                let (a, b, c) = (i - di, j - dj, k - dk);
                                if a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz {
                                    continue;
                                }
                                let t = self.nearest[self.index(a as u32, b as u32, c as u32)];
                                if t == u32::MAX || t == self.nearest[here] {
                                    continue;
                                }
                                let d = point_triangle_distance(p, &triangles[t as usize]);
                                if d < self.distance[here] {
                                    self.distance[here] = d;
                                    self.nearest[here] = t;
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    /// Whether each grid point is inside: the crossings of a ray along +x
    /// from it, odd. The rays are moved off the grid's rows by a small
    /// irrational fraction of a cell so none runs exactly along an edge
    /// shared by two triangles (which would count one crossing twice).
    fn parity(&self, triangles: &[[Vec3; 3]]) -> Vec<bool> {
        let [nx, ny, nz] = self.dims;
        let offset = self.cell * glam::Vec2::new(1.234_567e-3, 2.718_281e-3);
        let mut crossings: Vec<Vec<f32>> = vec![Vec::new(); (ny * nz) as usize];
        for tri in triangles {
            let lo = tri[0].min(tri[1]).min(tri[2]);
            let hi = tri[0].max(tri[1]).max(tri[2]);
            let (a, b) = self.span(lo, hi);
            for k in a[2]..=b[2] {
                for j in a[1]..=b[1] {
                    let p = self.point(0, j, k);
                    let yz = glam::Vec2::new(p.y, p.z) + offset;
                    if let Some(x) = ray_x_crossing(yz, tri) {
                        crossings[(k * ny + j) as usize].push(x);
                    }
                }
            }
        }
        let mut inside = vec![false; self.distance.len()];
        for k in 0..nz {
            for j in 0..ny {
                let row = &crossings[(k * ny + j) as usize];
                for i in 0..nx {
                    let x = self.point(i, j, k).x;
                    let after = row.iter().filter(|&&c| c > x).count();
                    inside[self.index(i, j, k)] = after % 2 == 1;
                }
            }
        }
        inside
    }
}

/// Where the line {(x, yz)} crosses the triangle, if it does.
fn ray_x_crossing(yz: glam::Vec2, tri: &[Vec3; 3]) -> Option<f32> {
    let p = tri.map(|v| glam::Vec2::new(v.y, v.z));
    let area = (p[1] - p[0]).perp_dot(p[2] - p[0]);
    if area == 0.0 {
        return None;
    }
    let w0 = (p[1] - yz).perp_dot(p[2] - yz) / area;
    let w1 = (p[2] - yz).perp_dot(p[0] - yz) / area;
    let w2 = 1.0 - w0 - w1;
    (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0).then(|| w0 * tri[0].x + w1 * tri[1].x + w2 * tri[2].x)
}

/// Distance from `p` to the nearest point of the triangle: by the region of
/// the triangle's plane `p` projects into (a vertex, an edge or the face;
/// Ericson, Real-Time Collision Detection, 2005, §5.1.5).
fn point_triangle_distance(p: Vec3, [a, b, c]: &[Vec3; 3]) -> f32 {
    let (ab, ac, ap) = (*b - *a, *c - *a, p - *a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - *b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (p - (*a + v * ab)).length();
    }
    let cp = p - *c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (p - (*a + w * ac)).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (*b + w * (*c - *b))).length();
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    (p - (*a + ab * v + ac * w)).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The field of an ellipsoid mesh agrees with the distance to the
    /// ellipsoid: exactly on the axes (where the distance is the radius
    /// difference), in sign everywhere a cell or more from the surface.
    #[test]
    fn ellipsoid_field_matches_the_ellipsoid() {
        let radii = Vec3::new(0.9, 1.05, 1.0);
        let mesh = Mesh::ellipsoid(Vec3::ZERO, radii, 32, 64);
        let started = std::time::Instant::now();
        let sdf = SignedDistanceField::bake(&mesh, 32);
        eprintln!(
            "bake 32³ ({} triangles): {:?}",
            mesh.indices.len() / 3,
            started.elapsed()
        );
        let at = |p: Vec3| sdf.sample(p).expect("inside the grid");
        // Along the axes the distance to an ellipsoid is |p| − radius.
        for (p, want) in [
            (Vec3::new(0.0, 0.0, 0.5), -0.5),
            (Vec3::new(0.0, 0.0, 1.1), 0.1),
            (Vec3::new(0.0, 0.8, 0.0), -0.25),
            (Vec3::new(-1.0, 0.0, 0.0), 0.1),
        ] {
            let d = at(p);
            assert!((d - want).abs() < 0.03, "at {p}: {d}, want {want}");
        }
        // Sign: outside/inside by the implicit function, a cell away.
        let mut checked = 0;
        for k in 0..sdf.dims[2] {
            for j in 0..sdf.dims[1] {
                for i in 0..sdf.dims[0] {
                    let p = sdf.origin + sdf.cell * Vec3::new(i as f32, j as f32, k as f32);
                    let q = (p / radii).length();
                    let d = sdf.values[((k * sdf.dims[1] + j) * sdf.dims[0] + i) as usize];
                    if (q - 1.0).abs() * radii.min_element() > sdf.cell {
                        assert_eq!(d < 0.0, q < 1.0, "sign at {p} (|q| = {q}): {d}");
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 20_000, "{checked}");
        assert_eq!(sdf.sample(Vec3::splat(10.0)), None);
    }

    #[test]
    fn closed_and_open_meshes_are_told_apart() {
        let head = Mesh::ellipsoid(Vec3::ZERO, Vec3::new(0.9, 1.05, 1.0), 32, 64);
        assert_eq!(
            open_edges(&head).0,
            0,
            "the UV ellipsoid is closed once its seam is welded"
        );
        let mut open = head.clone();
        open.indices.truncate(open.indices.len() - 3 * 64); // the bottom cap's ring
        assert_eq!(open_edges(&open).0, 64);
        assert_eq!(open_edges(&Mesh::ground_plane(Vec3::ZERO, 1.0)).0, 4);
    }

    #[test]
    fn triangle_distance_by_region() {
        let t = [Vec3::ZERO, Vec3::X, Vec3::Y];
        assert!((point_triangle_distance(Vec3::new(0.2, 0.2, 0.5), &t) - 0.5).abs() < 1e-6);
        assert!(
            (point_triangle_distance(Vec3::new(-1.0, -1.0, 0.0), &t) - 2f32.sqrt()).abs() < 1e-6
        );
        assert!((point_triangle_distance(Vec3::new(0.5, -2.0, 0.0), &t) - 2.0).abs() < 1e-6);
        assert!(
            (point_triangle_distance(Vec3::new(1.0, 1.0, 0.0), &t) - 0.5f32.sqrt()).abs() < 1e-6
        );
    }
}
