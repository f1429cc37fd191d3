//! The scene file every pipeline renders (TOML; see `examples/scenes/`).
//!
//! A scene names its hair (a `.hair` or `.tfx` file or a procedural groom,
//! with optional follow strands and placement: [`crate::hair_source`]), the
//! opaque geometry (head, ground), a camera (look-at, or `"fit"` to the
//! hair), one light (or `"fit"`), the background and the hair material.
//! Unknown fields are errors, reported as `path:line:column: message`.
//! Relative paths are resolved against the directory of the scene file.
//!
//! Here the scene's types; `parse` reads the TOML (positions in messages),
//! `validate` range-checks it, `builtin` is the default scene, `hair` loads
//! the hair and fits `"fit"` camera and light to it, `opaque` is the head and
//! ground geometry and the head's animated pose, `meshes` the `[[meshes]]`
//! read from files.

mod builtin;
mod hair;
mod meshes;
mod opaque;
mod parse;
#[cfg(test)]
mod tests;
mod validate;

use std::path::PathBuf;

use serde::Deserialize;

pub use crate::animation::Animation;
use crate::asset::AssetError;
pub use crate::camera::{Camera, CameraFit};
use crate::environment::{Environment, EnvironmentError};
use crate::hair_file::HairError;
pub use crate::hair_source::{Hair, HairSource};
pub use crate::light::{Light, LightKind};
use crate::tfx::TfxError;
pub use meshes::{DEFAULT_SDF_RESOLUTION, MAX_SDF_RESOLUTION, MeshRole, SceneMesh, SceneMeshError};

/// Errors loading a scene or its hair.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("{}: cannot read file: {error}", path.display())]
    Io {
        /// The scene file.
        path: PathBuf,
        /// The I/O error (in the message, not a `source()`).
        error: std::io::Error,
    },
    /// TOML syntax or schema error, with its position.
    #[error("{}:{line}:{column}: {message}", path.display())]
    Parse {
        /// The scene file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// 1-based column (in characters).
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A value is out of range (the message names the field).
    #[error("{}: {message}", path.display())]
    Invalid {
        /// The scene file (or `<builtin>`).
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The hair file a scene names could not be read: where the scene
    /// names it (`scene.toml:LINE:COL`), then the file's own error.
    #[error("{at}: hair.file: {error}")]
    HairFile {
        /// The scene file, line and column of the `file = "…"` value.
        at: String,
        /// The error reading the hair file (it names the file).
        error: Box<SceneError>,
    },
    /// The hair file could not be read (the error names it).
    #[error(transparent)]
    Hair(#[from] HairError),
    /// The `.tfx` file could not be read (the error names it).
    #[error(transparent)]
    Tfx(#[from] TfxError),
    /// The USD groom could not be read (the error names the file and prim).
    #[error(transparent)]
    Usd(#[from] crate::usd::UsdError),
    /// The hair file is of no format plait reads (the error names it).
    #[error("{0}")]
    UnknownAsset(String),
    /// The environment image could not be used (the error names it).
    #[error(transparent)]
    Environment(#[from] EnvironmentError),
    /// A `[[meshes]]` file could not be used (the error names it, the mesh
    /// and primitive or field, and where the scene names the file).
    #[error(transparent)]
    Mesh(#[from] SceneMeshError),
}

impl From<AssetError> for SceneError {
    fn from(e: AssetError) -> Self {
        match e {
            AssetError::Hair(e) => SceneError::Hair(e),
            AssetError::Tfx(e) => SceneError::Tfx(e),
            AssetError::Usd(e) => SceneError::Usd(e),
            unknown @ AssetError::Unknown { .. } => SceneError::UnknownAsset(unknown.to_string()),
        }
    }
}

/// The head: an opaque ellipsoid.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Head {
    /// Center.
    pub center: [f32; 3],
    /// Semi-axes.
    pub radii: [f32; 3],
    /// Diffuse albedo.
    #[serde(default = "default_head_albedo")]
    pub albedo: [f32; 3],
}

fn default_head_albedo() -> [f32; 3] {
    [0.75, 0.55, 0.45]
}

/// The ground: a horizontal square facing +Y.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ground {
    /// Height (y) of the plane.
    pub height: f32,
    /// Half the side length; centered under the origin.
    pub half_size: f32,
    /// Diffuse albedo.
    #[serde(default = "default_ground_albedo")]
    pub albedo: [f32; 3],
}

fn default_ground_albedo() -> [f32; 3] {
    [0.6, 0.6, 0.6]
}

/// What is behind everything.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(try_from = "BackgroundToml")]
pub enum Background {
    /// A constant linear RGB color.
    Color([f32; 3]),
    /// An environment image (path resolved against the scene file).
    Image(PathBuf),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BackgroundToml {
    color: Option<[f32; 3]>,
    image: Option<PathBuf>,
}

impl TryFrom<BackgroundToml> for Background {
    type Error = String;
    fn try_from(t: BackgroundToml) -> Result<Background, String> {
        match (t.color, t.image) {
            (Some(c), None) => Ok(Background::Color(c)),
            (None, Some(p)) => Ok(Background::Image(p)),
            _ => Err("background needs exactly one of `color` or `image`".into()),
        }
    }
}

/// Hair shading parameters (Kajiya-Kay, Halén & Wester 2007 §3.2.1).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HairMaterial {
    /// Tint multiplied with the per-strand color.
    pub color: [f32; 3],
    /// Multiplied with the per-strand alpha.
    pub alpha: f32,
    /// Kajiya-Kay diffuse coefficient kd.
    pub diffuse: f32,
    /// Kajiya-Kay specular coefficient ks.
    pub specular: f32,
    /// Specular exponent.
    pub specular_exponent: f32,
    /// Shift of the highlight along the tangent (toward the root for < 0).
    pub specular_shift: f32,
}

impl Default for HairMaterial {
    fn default() -> Self {
        HairMaterial {
            color: [1.0, 1.0, 1.0],
            alpha: 1.0,
            // kd + ks ≤ 1: the fibre reflects no more than it receives
            // (docs/formats.md, "Light and units"); 0.3 before the
            // shading was energy-normalized.
            diffuse: 0.8,
            specular: 0.2,
            specular_exponent: 60.0,
            specular_shift: -0.05,
        }
    }
}

/// A complete scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The hair.
    pub hair: Hair,
    /// The opaque head, if any.
    pub head: Option<Head>,
    /// The ground, if any.
    pub ground: Option<Ground>,
    /// Meshes read from files (`[[meshes]]`), placed in the scene.
    pub meshes: Vec<SceneMesh>,
    /// The camera (until [`Scene::load_hair`], a stand-in when it is fitted).
    pub camera: Camera,
    /// The one light (likewise).
    pub light: Light,
    /// What is fitted to the hair when it is loaded.
    pub framing: Framing,
    /// The background.
    pub background: Background,
    /// Hair material.
    pub material: HairMaterial,
    /// Constant ambient light intensity.
    pub ambient: f32,
    /// The light around the scene (the procedural sky unless the file
    /// names an image), for the `lighting` techniques.
    pub environment: Environment,
    /// Keyframes of the head, if it moves.
    pub animation: Option<Animation>,
}

/// What [`Scene::load_hair`] fits to the hair's bounds.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Framing {
    /// `camera = "fit"`: the camera is placed to see the hair (and head).
    pub camera: Option<CameraFit>,
    /// `light = "fit"`: the light's direction follows the camera.
    pub light: bool,
}
