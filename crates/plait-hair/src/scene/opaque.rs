//! The scene's opaque geometry (head ellipsoid, ground plane, `[[meshes]]`),
//! the head's pose (and the camera's dolly) over time under `[animation]`,
//! and their bounds.

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
            Some(a) => a.head_model(time, self.head_center()),
        }
    }

    /// The camera's distance to its target at `time` seconds, as a factor
    /// of the scene's (the animation's `camera_distance`; 1 without one):
    /// the frame sees through `camera.dollied(factor)`.
    pub fn camera_distance(&self, time: f32) -> f32 {
        self.animation
            .as_ref()
            .map_or(1.0, |a| a.camera_distance(time))
    }

    /// The head's centre: the ellipsoid's, else the head mesh's bounds'.
    fn head_center(&self) -> Vec3 {
        if let Some(h) = &self.head {
            return Vec3::from(h.center);
        }
        self.head_mesh().map_or(Vec3::ZERO, |m| {
            let b = mesh_bounds(&m.mesh);
            0.5 * (b.min + b.max)
        })
    }

    /// Bounds of the meshes read from files (`[[meshes]]`), at rest.
    pub fn file_mesh_bounds(&self) -> Aabb {
        self.meshes
            .iter()
            .fold(Aabb::EMPTY, |b, m| b.union(&mesh_bounds(&m.mesh)))
    }

    /// Opaque geometry: the head ellipsoid and the ground plane, if present,
    /// then the `[[meshes]]`; the head's meshes are marked `head`.
    pub fn opaque_meshes(&self) -> Vec<Mesh> {
        let mut out = Vec::new();
        if let Some(h) = &self.head {
            out.push(
                Mesh::ellipsoid(h.center.into(), h.radii.into(), 32, 64)
                    .with_name("head")
                    .with_albedo(h.albedo)
                    .as_head(),
            );
        }
        if let Some(g) = &self.ground {
            out.push(
                Mesh::ground_plane(Vec3::new(0.0, g.height, 0.0), g.half_size)
                    .with_name("ground")
                    .with_albedo(g.albedo),
            );
        }
        out.extend(self.meshes.iter().map(|m| m.mesh.clone()));
        out
    }

    /// Bounds of the opaque meshes with the head posed by `head_model`.
    pub fn opaque_bounds_posed(&self, head_model: glam::Mat4) -> Aabb {
        self.opaque_meshes()
            .iter()
            .flat_map(|m| {
                let pose = if m.head {
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

fn mesh_bounds(mesh: &Mesh) -> Aabb {
    mesh.vertices
        .iter()
        .map(|v| Vec3::from(v.position))
        .fold(Aabb::EMPTY, |b, p| b.union(&Aabb::new(p, p)))
}
