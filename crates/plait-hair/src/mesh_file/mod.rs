//! Mesh files a scene names under `[[meshes]]` (docs/formats.md, "Meshes").
//!
//! The format is chosen by the file's extension ([`read`]): `.glb` and
//! `.gltf` are glTF 2.0 ([`gltf`]); `.usd`, `.usda`, `.usdc` and `.usdz`
//! are the `Mesh` prims of a USD stage (`crate::usd::mesh`), returning the
//! same [`Mesh`]. Every reader checks the
//! counts a file claims against [`Limits`] before it reads (or allocates for)
//! them, and rejects non-finite positions, so what reaches the GPU and the
//! signed distance field bake is bounded and finite.

pub mod gltf;
pub mod write;

use std::path::{Path, PathBuf};

use crate::mesh::Mesh;

/// The largest mesh a scene may name: the sum over every primitive of every
/// mesh instance in the file. A head scan of a million vertices is far past
/// what a real-time hair renderer draws as an occluder; the limit stops a
/// file whose header claims billions before anything is allocated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Vertices, all primitives together.
    pub vertices: usize,
    /// Triangles, all primitives together.
    pub triangles: usize,
    /// Bytes of one external buffer file (`.bin`).
    pub buffer_bytes: usize,
}

impl Limits {
    /// The limits `plait` applies (docs/formats.md states them).
    pub const DEFAULT: Limits = Limits {
        vertices: 1 << 20,
        triangles: 2 << 20,
        buffer_bytes: 256 << 20,
    };
}

/// A mesh file that cannot be used: the message names the file and, where
/// it applies, the mesh, primitive and field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct MeshFileError {
    /// The mesh file.
    pub path: PathBuf,
    /// What is wrong, and where in the file.
    pub message: String,
}

/// The extensions [`read`] knows, for messages.
pub const EXTENSIONS: &[&str] = &["glb", "gltf", "usd", "usda", "usdc", "usdz"];

/// Reads the mesh file at `path` (format by extension) as one triangle mesh
/// in the file's own space, named after the file.
pub fn read(path: &Path, limits: &Limits) -> Result<Mesh, MeshFileError> {
    read_prim(path, None, limits)
}

/// [`read`], with USD's `Mesh` prims taken under `prim` only (an error for
/// formats without prims).
pub fn read_prim(path: &Path, prim: Option<&str>, limits: &Limits) -> Result<Mesh, MeshFileError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    match extension.as_str() {
        "glb" | "gltf" if prim.is_some() => Err(MeshFileError {
            path: path.to_path_buf(),
            message: "`prim` applies to USD files only: a glTF file has no prims".into(),
        }),
        "usd" | "usda" | "usdc" | "usdz" => crate::usd::mesh::read(path, prim, limits),
        "glb" | "gltf" => {
            let bytes = read_file(path, limits)?;
            gltf::read_bytes(&bytes, path, limits)
        }
        _ => Err(MeshFileError {
            path: path.to_path_buf(),
            message: format!(
                "unknown mesh format `.{extension}`: plait reads {}",
                EXTENSIONS
                    .iter()
                    .map(|e| format!("`.{e}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }),
    }
}

/// A whole file, refused unread when it is larger than a buffer may be.
pub(crate) fn read_file(path: &Path, limits: &Limits) -> Result<Vec<u8>, MeshFileError> {
    let error = |message: String| MeshFileError {
        path: path.to_path_buf(),
        message,
    };
    let size = std::fs::metadata(path)
        .map_err(|e| error(format!("cannot read file: {e}")))?
        .len();
    if size > limits.buffer_bytes as u64 {
        return Err(error(format!(
            "the file is {size} bytes, over the limit of {} bytes",
            limits.buffer_bytes
        )));
    }
    std::fs::read(path).map_err(|e| error(format!("cannot read file: {e}")))
}

#[cfg(test)]
mod tests;
