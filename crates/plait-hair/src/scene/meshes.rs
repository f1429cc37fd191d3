//! The scene's `[[meshes]]`: mesh files drawn as opaque geometry, each with
//! a transform and a role (`head`: moves with `[animation]`, collides with
//! the simulation through its signed distance field; `static`: stays put).
//! Files are read when the scene is loaded (so `plait check` reads them
//! too), by `crate::mesh_file::read`, which picks the format by extension.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::Scene;
use crate::mesh::Mesh;
use crate::mesh_file::{Limits, MeshFileError};
use crate::sdf::SignedDistanceField;
use crate::transform::Transform;

/// What a mesh is in the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MeshRole {
    /// Moves with `[animation]`, collides with simulated hair, casts and
    /// receives shadows.
    Head,
    /// Stays where it is placed; casts and receives shadows.
    Static,
}

/// Grid points of the head's signed distance field along its longest side,
/// when the scene does not say.
pub const DEFAULT_SDF_RESOLUTION: u32 = 32;
/// The largest `sdf_resolution`: 128³ floats are 8 MiB.
pub const MAX_SDF_RESOLUTION: u32 = 128;

/// One `[[meshes]]` entry as written.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MeshToml {
    file: toml::Spanned<PathBuf>,
    role: MeshRole,
    albedo: Option<[f32; 3]>,
    #[serde(default)]
    transform: Transform,
    sdf_resolution: Option<u32>,
    /// USD files only: read the `Mesh` prims under this prim.
    prim: Option<String>,
}

/// A mesh of the scene, read and placed.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneMesh {
    /// The file (resolved against the scene's directory).
    pub file: PathBuf,
    /// Where the scene names it (`path:line:column`), for messages.
    pub declared_at: String,
    /// Head or static.
    pub role: MeshRole,
    /// Placement in the scene (applied to `mesh`).
    pub transform: Transform,
    /// Grid points of the head's distance field along its longest side.
    pub sdf_resolution: u32,
    /// The triangles in scene space, with the albedo; marked `head` for the
    /// head (the GPU upload and bounds pose it by `Scene::head_model`).
    pub mesh: Mesh,
}

/// A mesh file that cannot be used, with where the scene names it.
#[derive(Debug, thiserror::Error)]
#[error("{error} (the mesh of meshes[{index}] at {declared_at})")]
pub struct SceneMeshError {
    /// The reader's error (names the mesh file).
    pub error: MeshFileError,
    /// Which entry.
    pub index: usize,
    /// `scene:line:column` of its `file`.
    pub declared_at: String,
}

impl MeshToml {
    /// Range checks; messages name the field.
    pub(super) fn validate(&self, index: usize) -> Result<(), String> {
        let field = format!("meshes[{index}]");
        if let Some(a) = self.albedo
            && !a.iter().all(|c| c.is_finite())
        {
            return Err(format!("{field}.albedo must be finite"));
        }
        if let Some(a) = self.albedo
            && a.iter().any(|c| !(0.0..=1.0).contains(c))
        {
            return Err(format!(
                "{field}.albedo must be in [0, 1] (an albedo: the fraction of the light reflected), got {a:?}"
            ));
        }
        self.transform
            .validate_named(&format!("{field}.transform"))?;
        if let Some(p) = &self.prim
            && !p.starts_with('/')
        {
            return Err(format!(
                "{field}.prim must be an absolute prim path such as \"/Head\", got {p:?}"
            ));
        }
        match (self.role, self.sdf_resolution) {
            (MeshRole::Static, Some(_)) => Err(format!(
                "{field}.sdf_resolution applies to role = \"head\" only (a static mesh does not collide)"
            )),
            (_, Some(r)) if !(4..=MAX_SDF_RESOLUTION).contains(&r) => Err(format!(
                "{field}.sdf_resolution must be in 4..={MAX_SDF_RESOLUTION}, got {r}"
            )),
            _ => Ok(()),
        }
    }

    /// Reads the file (relative to `dir`) and places it.
    pub(super) fn load(
        &self,
        index: usize,
        dir: &Path,
        declared_at: String,
    ) -> Result<SceneMesh, SceneMeshError> {
        let file = dir.join(self.file.get_ref());
        let fail = |error: MeshFileError| SceneMeshError {
            error,
            index,
            declared_at: declared_at.clone(),
        };
        let mut mesh = crate::mesh_file::read_prim(&file, self.prim.as_deref(), &Limits::DEFAULT)
            .map_err(fail)?;
        place(&mut mesh, &self.transform).map_err(|message| {
            fail(MeshFileError {
                path: file.clone(),
                message,
            })
        })?;
        if self.role == MeshRole::Head
            && let (count @ 1.., Some([a, b])) = crate::sdf::open_edges(&mesh)
        {
            return Err(fail(MeshFileError {
                path: file.clone(),
                message: format!(
                    "the head mesh is not closed: {count} edges border one triangle or more than two (one from {a} to {b}); \
                     its collision field tells inside from outside by counting crossings, which needs a closed surface — \
                     close it (e.g. cap the neck) or give it role = \"static\""
                ),
            }));
        }
        let albedo = match self.role {
            MeshRole::Head => {
                mesh.name = "head".into();
                mesh.head = true;
                super::default_head_albedo()
            }
            MeshRole::Static => mesh.albedo,
        };
        mesh.albedo = self.albedo.unwrap_or(albedo);
        Ok(SceneMesh {
            file,
            declared_at,
            role: self.role,
            transform: self.transform.clone(),
            sdf_resolution: self.sdf_resolution.unwrap_or(DEFAULT_SDF_RESOLUTION),
            mesh,
        })
    }

    /// Role head.
    pub(super) fn is_head(&self) -> bool {
        self.role == MeshRole::Head
    }

    /// The file as written.
    pub(super) fn file(&self) -> &Path {
        self.file.get_ref()
    }

    /// Where `file` is written in the scene text.
    pub(super) fn file_span(&self) -> std::ops::Range<usize> {
        self.file.span()
    }
}

/// Moves the mesh by the transform: positions by its matrix, normals by the
/// inverse transpose, the winding turned when it mirrors.
fn place(mesh: &mut Mesh, transform: &Transform) -> Result<(), String> {
    let m = transform.matrix();
    let normals = glam::Mat3::from_mat4(m).inverse().transpose();
    for v in &mut mesh.vertices {
        let p = m.transform_point3(v.position.into());
        if !p.is_finite() {
            return Err(format!(
                "the scene's transform moves a vertex out of the f32 range ({p})"
            ));
        }
        v.position = p.to_array();
        v.normal = (normals * glam::Vec3::from(v.normal))
            .normalize_or(glam::Vec3::Y)
            .to_array();
    }
    if m.determinant() < 0.0 {
        for t in mesh.indices.chunks_exact_mut(3) {
            t.swap(1, 2);
        }
    }
    Ok(())
}

impl Scene {
    /// The mesh with role `head`, if the scene has one.
    pub fn head_mesh(&self) -> Option<&SceneMesh> {
        self.meshes.iter().find(|m| m.role == MeshRole::Head)
    }

    /// The head mesh's signed distance field at rest, baked at its
    /// `sdf_resolution` (`None` without a head mesh).
    pub fn head_sdf(&self) -> Option<SignedDistanceField> {
        self.head_mesh()
            .map(|h| SignedDistanceField::bake(&h.mesh, h.sdf_resolution))
    }
}
