//! Opaque geometry: the head (an ellipsoid) and the ground plane.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// One mesh vertex as uploaded to the GPU (24 bytes, `#[repr(C)]`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct MeshVertex {
    /// Position.
    pub position: [f32; 3],
    /// Unit outward normal.
    pub normal: [f32; 3],
}

/// An indexed triangle list; front faces are counter-clockwise seen from
/// outside (the side the normals point to).
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// A name for labels and debugging ("head", "ground").
    pub name: String,
    /// Vertices.
    pub vertices: Vec<MeshVertex>,
    /// Triangle list indices.
    pub indices: Vec<u32>,
    /// Diffuse albedo (linear RGB).
    pub albedo: [f32; 3],
    /// The head: it moves with the head's pose (`Scene::head_model`); the
    /// rest of the opaque geometry stays put. Not the name, so a static mesh
    /// read from `head.glb` stays put too.
    pub head: bool,
}

impl Mesh {
    /// A UV ellipsoid. `stacks` (≥ 2) rings from pole to pole, `slices` (≥ 3)
    /// around; smaller values are raised to these minimums. Normals are the
    /// true ellipsoid normals (gradient of the implicit surface).
    pub fn ellipsoid(center: Vec3, radii: Vec3, stacks: u32, slices: u32) -> Mesh {
        let stacks = stacks.max(2);
        let slices = slices.max(3);
        let mut vertices = Vec::with_capacity(((stacks + 1) * (slices + 1)) as usize);
        let safe = radii.abs().max(Vec3::splat(1e-12));
        for i in 0..=stacks {
            let theta = std::f32::consts::PI * i as f32 / stacks as f32; // from +Y
            for j in 0..=slices {
                let phi = std::f32::consts::TAU * j as f32 / slices as f32;
                let unit = Vec3::new(
                    theta.sin() * phi.sin(),
                    theta.cos(),
                    theta.sin() * phi.cos(),
                );
                let p = center + unit * radii;
                let n = (unit / safe).normalize_or(unit);
                vertices.push(MeshVertex {
                    position: p.to_array(),
                    normal: n.to_array(),
                });
            }
        }
        let indices = grid_indices(stacks, slices);
        Mesh {
            name: "ellipsoid".into(),
            vertices,
            indices,
            albedo: [0.8, 0.8, 0.8],
            head: false,
        }
    }

    /// A square in the XZ plane at `center`, side `2 * half_size`, facing +Y.
    pub fn ground_plane(center: Vec3, half_size: f32) -> Mesh {
        let h = half_size;
        let corners = [
            Vec3::new(-h, 0.0, -h),
            Vec3::new(-h, 0.0, h),
            Vec3::new(h, 0.0, h),
            Vec3::new(h, 0.0, -h),
        ];
        let vertices = corners
            .iter()
            .map(|&c| MeshVertex {
                position: (center + c).to_array(),
                normal: [0.0, 1.0, 0.0],
            })
            .collect();
        Mesh {
            name: "ground".into(),
            vertices,
            indices: vec![0, 1, 2, 0, 2, 3],
            albedo: [0.6, 0.6, 0.6],
            head: false,
        }
    }

    /// Sets the name.
    pub fn with_name(mut self, name: impl Into<String>) -> Mesh {
        self.name = name.into();
        self
    }

    /// Marks the mesh as the head (it moves with the head's pose).
    pub fn as_head(mut self) -> Mesh {
        self.head = true;
        self
    }

    /// Sets the albedo.
    pub fn with_albedo(mut self, albedo: [f32; 3]) -> Mesh {
        self.albedo = albedo;
        self
    }
}

/// The triangles of a pole-to-pole grid of (`stacks` + 1) × (`slices` + 1)
/// vertices, row by row from the top pole (each pole a row of coincident
/// vertices, the seam a column twice): counter-clockwise seen from outside,
/// one triangle per quad at the poles, where the other would be degenerate.
pub(crate) fn grid_indices(stacks: u32, slices: u32) -> Vec<u32> {
    let row = slices + 1;
    let mut indices = Vec::with_capacity((stacks * slices * 6) as usize);
    for i in 0..stacks {
        for j in 0..slices {
            let a = i * row + j; // upper-left
            let b = a + row; // lower-left
            let c = b + 1; // lower-right
            let d = a + 1; // upper-right
            if i != 0 {
                indices.extend_from_slice(&[a, b, d]);
            }
            if i != stacks - 1 {
                indices.extend_from_slice(&[d, b, c]);
            }
        }
    }
    indices
}

#[cfg(test)]
/// Every triangle's geometric normal (CCW winding) agrees with the
/// vertex normals, i.e. faces are front-facing from outside.
pub(crate) fn assert_outward(m: &Mesh) {
    assert_eq!(m.indices.len() % 3, 0);
    for t in m.indices.chunks_exact(3) {
        let p = |i: u32| Vec3::from(m.vertices[i as usize].position);
        let n = |i: u32| Vec3::from(m.vertices[i as usize].normal);
        let face = (p(t[1]) - p(t[0])).cross(p(t[2]) - p(t[0]));
        assert!(face.length() > 0.0, "degenerate triangle {t:?}");
        assert!(
            face.dot(n(t[0]) + n(t[1]) + n(t[2])) > 0.0,
            "triangle {t:?} faces inward"
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ellipsoid_is_closed_and_outward() {
        let m = Mesh::ellipsoid(Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 1.2, 0.9), 8, 12);
        assert_outward(&m);
        assert_eq!(m.indices.len(), (2 * 12 + 6 * 12 * 2) * 3);
        for v in &m.vertices {
            let q = (Vec3::from(v.position) - Vec3::new(1.0, 2.0, 3.0)) / Vec3::new(1.0, 1.2, 0.9);
            assert!((q.length() - 1.0).abs() < 1e-5);
            assert!((Vec3::from(v.normal).length() - 1.0).abs() < 1e-5);
        }
        assert_eq!(std::mem::size_of::<MeshVertex>(), 24);
    }

    #[test]
    fn ground_faces_up() {
        let m = Mesh::ground_plane(Vec3::new(0.0, -2.0, 0.0), 3.0);
        assert_outward(&m);
        assert!(
            m.vertices
                .iter()
                .all(|v| v.position[1] == -2.0 && v.normal == [0.0, 1.0, 0.0])
        );
    }
}
