//! The scene's opaque geometry (head ellipsoid, ground plane), the head's
//! pose over time under `[animation]`, and their bounds.

use glam::Vec3;

use super::Scene;
use crate::mesh::Mesh;
use crate::strands::Aabb;

impl Scene {
    /// The head's world-from-rest matrix at `time` seconds: the identity
    /// without `[animation]`; the animation turns about the head's centre
    /// unless it names a pivot.
    pub fn head_model(&self, time: f32) -> glam::Mat4 {
        match &self.animation {
            None => glam::Mat4::IDENTITY,
            Some(a) => {
                let center = self
                    .head
                    .as_ref()
                    .map_or(Vec3::ZERO, |h| Vec3::from(h.center));
                a.head_model(time, center)
            }
        }
    }

    /// Opaque geometry: the head ellipsoid and the ground plane, if present.
    pub fn opaque_meshes(&self) -> Vec<Mesh> {
        let mut out = Vec::new();
        if let Some(h) = &self.head {
            out.push(
                Mesh::ellipsoid(h.center.into(), h.radii.into(), 32, 64)
                    .with_name("head")
                    .with_albedo(h.albedo),
            );
        }
        if let Some(g) = &self.ground {
            out.push(
                Mesh::ground_plane(Vec3::new(0.0, g.height, 0.0), g.half_size)
                    .with_name("ground")
                    .with_albedo(g.albedo),
            );
        }
        out
    }

    /// Bounds of the opaque meshes with the head posed by `head_model`.
    pub fn opaque_bounds_posed(&self, head_model: glam::Mat4) -> Aabb {
        self.opaque_meshes()
            .iter()
            .flat_map(|m| {
                let pose = if m.name == "head" {
                    head_model
                } else {
                    glam::Mat4::IDENTITY
                };
                m.vertices
                    .iter()
                    .map(move |v| pose.transform_point3(Vec3::from(v.position)))
            })
            .fold(Aabb::EMPTY, |b, p| b.union(&Aabb::new(p, p)))
    }

    /// Bounds of the opaque meshes (empty if none).
    pub fn opaque_bounds(&self) -> Aabb {
        self.opaque_meshes()
            .iter()
            .flat_map(|m| m.vertices.iter().map(|v| Vec3::from(v.position)))
            .fold(Aabb::EMPTY, |b, p| b.union(&Aabb::new(p, p)))
    }
}
