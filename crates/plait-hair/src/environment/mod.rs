//! The light around the scene: an environment image (or the built-in
//! procedural sky) that the `lighting` techniques turn into irradiance
//! (Xing et al. 2012 §3, §5).
//!
//! In a scene file:
//!
//! ```toml
//! environment = "sky.hdr"                 # an equirectangular image
//! [environment]                           # or a table
//! image = "cross.exr"
//! layout = "cube_cross"                   # equirect | cube_cross | cube_faces
//! rotate = 90.0                           # degrees about +y
//! intensity = 1.5                         # scales the radiance
//! # layout = "cube_faces" takes faces = [+x, -x, +y, -y, +z, -z] instead of image
//! ```
//!
//! Without the key the scene is lit by [`sky`], so nothing needs
//! downloading. Every layout is read into one [`EnvironmentImage`]: a linear
//! RGB equirectangular image of at most [`MAX_WIDTH`] × [`MAX_WIDTH`]/2
//! texels (box-filtered down: the lighting techniques sum a 16×16×6 cube of
//! it, so more detail would only alias), rotated and scaled as the scene
//! says. That image reaches the GPU as the scene binding
//! `environment_source`.
//!
//! [`cube`], [`irradiance`] and [`sh`] are the CPU references of the GPU
//! kernels (`shaders/passes/environment_cube.wgsl`, `irradiance_maps.wgsl`,
//! `sh_*.wgsl`), used by the tests to check them and measure the maps' error.

pub mod cube;
mod files;
pub mod image;
pub mod irradiance;
pub mod sh;
pub mod sky;

use std::fmt;
use std::path::{Path, PathBuf};

use serde::Deserialize;

pub use self::image::{EnvironmentImage, MAX_WIDTH};

/// How the six directions of a cube or the sphere are laid out in the file(s).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Layout {
    /// Longitude × latitude, twice as wide as high; the image's centre looks
    /// along -z, its top row is +y.
    Equirect,
    /// One image of six square faces: a horizontal cross (4 × 3 faces: +y
    /// above +z; -x, +z, +x, -z in the middle row; -y below +z) or a vertical
    /// one (3 × 4: +y; -x, +z, +x; -y; -z upside down).
    CubeCross,
    /// Six images, `faces = [+x, -x, +y, -y, +z, -z]`, each seen from the
    /// cube's centre with the Vulkan / Direct3D orientation.
    CubeFaces,
}

/// Where the radiance comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum EnvironmentSource {
    /// The built-in procedural sky ([`sky`]).
    Sky,
    /// An image file in one layout.
    Image { path: PathBuf, layout: Layout },
    /// Six face images, in the order +x, -x, +y, -y, +z, -z.
    Faces(Box<[PathBuf; 6]>),
}

/// The scene's environment: its source, rotation and intensity, and where
/// the scene file declared it (for messages about the image it names).
#[derive(Debug, Clone, PartialEq)]
pub struct Environment {
    pub source: EnvironmentSource,
    /// Degrees about +y: the radiance from direction d is the file's from
    /// d rotated by -rotate.
    pub rotate_degrees: f32,
    /// Scale on the radiance.
    pub intensity: f32,
    /// `scene.toml:line:column` of the `environment` key, when a file set it.
    pub declared_at: Option<String>,
}

impl Default for Environment {
    fn default() -> Self {
        Environment {
            source: EnvironmentSource::Sky,
            rotate_degrees: 0.0,
            intensity: 1.0,
            declared_at: None,
        }
    }
}

/// Why an environment could not be read. Every message names the file (and
/// the scene key that named it).
#[derive(Debug, thiserror::Error)]
#[error("{}: {message}{}", path.display(), declared_suffix(declared_at))]
pub struct EnvironmentError {
    pub path: PathBuf,
    pub message: String,
    pub declared_at: Option<String>,
}

fn declared_suffix(at: &Option<String>) -> String {
    at.as_ref()
        .map(|at| format!(" (the scene's environment, {at})"))
        .unwrap_or_default()
}

/// The `environment` value of a scene file: a path or a table.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct EnvironmentSetting(pub Environment);

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EnvironmentTable {
    image: Option<PathBuf>,
    faces: Option<Vec<PathBuf>>,
    layout: Option<Layout>,
    #[serde(default)]
    rotate: f32,
    #[serde(default = "one")]
    intensity: f32,
}

fn one() -> f32 {
    1.0
}

impl TryFrom<EnvironmentTable> for EnvironmentSetting {
    type Error = String;
    fn try_from(t: EnvironmentTable) -> Result<Self, String> {
        if !t.rotate.is_finite() {
            return Err("environment.rotate must be finite (degrees)".into());
        }
        if !(t.intensity.is_finite() && t.intensity >= 0.0) {
            return Err(format!(
                "environment.intensity must be a finite number >= 0, got {}",
                t.intensity
            ));
        }
        let layout = t.layout.unwrap_or(if t.faces.is_some() {
            Layout::CubeFaces
        } else {
            Layout::Equirect
        });
        let source = match (layout, t.image, t.faces) {
            (Layout::CubeFaces, None, Some(faces)) => {
                let faces: [PathBuf; 6] = faces.try_into().map_err(|f: Vec<PathBuf>| {
                    format!(
                        "environment.faces needs 6 images (+x, -x, +y, -y, +z, -z), got {}",
                        f.len()
                    )
                })?;
                EnvironmentSource::Faces(Box::new(faces))
            }
            (Layout::CubeFaces, _, None) => {
                return Err(
                    "layout = \"cube_faces\" needs faces = [+x, -x, +y, -y, +z, -z] (six images)"
                        .into(),
                );
            }
            (Layout::CubeFaces, Some(_), Some(_)) => {
                return Err("layout = \"cube_faces\" takes faces, not image".into());
            }
            (layout, Some(path), None) => EnvironmentSource::Image { path, layout },
            (_, _, Some(_)) => {
                return Err(
                    "environment.faces is for layout = \"cube_faces\"; use image for one file"
                        .into(),
                );
            }
            (_, None, None) => EnvironmentSource::Sky,
        };
        Ok(EnvironmentSetting(Environment {
            source,
            rotate_degrees: t.rotate,
            intensity: t.intensity,
            declared_at: None,
        }))
    }
}

impl<'de> Deserialize<'de> for EnvironmentSetting {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = EnvironmentSetting;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an image path or a table with image, layout, rotate, intensity")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Self::Value, E> {
                Ok(EnvironmentSetting(Environment {
                    source: EnvironmentSource::Image {
                        path: PathBuf::from(v),
                        layout: Layout::Equirect,
                    },
                    ..Environment::default()
                }))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<Self::Value, A::Error> {
                let table = EnvironmentTable::deserialize(
                    serde::de::value::MapAccessDeserializer::new(map),
                )?;
                EnvironmentSetting::try_from(table).map_err(serde::de::Error::custom)
            }
        }
        d.deserialize_any(V)
    }
}

impl Environment {
    /// Resolve relative image paths against `dir` (the scene file's folder).
    pub fn resolve_paths(&mut self, dir: &Path) {
        let fix = |p: &mut PathBuf| {
            if p.is_relative() {
                *p = dir.join(&*p);
            }
        };
        match &mut self.source {
            EnvironmentSource::Sky => {}
            EnvironmentSource::Image { path, .. } => fix(path),
            EnvironmentSource::Faces(faces) => faces.iter_mut().for_each(fix),
        }
    }

    /// The files the environment reads (for watching them).
    pub fn files(&self) -> Vec<PathBuf> {
        match &self.source {
            EnvironmentSource::Sky => Vec::new(),
            EnvironmentSource::Image { path, .. } => vec![path.clone()],
            EnvironmentSource::Faces(faces) => faces.to_vec(),
        }
    }

    /// Read the environment into a rotated, scaled equirectangular image.
    pub fn load(&self) -> Result<EnvironmentImage, EnvironmentError> {
        let err = |path: &Path, message: String| EnvironmentError {
            path: path.to_path_buf(),
            message,
            declared_at: self.declared_at.clone(),
        };
        let image = match &self.source {
            EnvironmentSource::Sky => sky::image(MAX_WIDTH),
            EnvironmentSource::Image { path, layout } => {
                let read = files::read_linear(path).map_err(|m| err(path, m))?;
                match layout {
                    Layout::Equirect => EnvironmentImage::from_equirect(read),
                    Layout::CubeCross => {
                        let faces = files::split_cross(&read).map_err(|m| err(path, m))?;
                        EnvironmentImage::from_faces(&faces)
                    }
                    Layout::CubeFaces => unreachable_layout(),
                }
                .map_err(|m| err(path, m))?
            }
            EnvironmentSource::Faces(paths) => {
                let mut faces = Vec::with_capacity(6);
                for path in paths.iter() {
                    faces.push(files::read_linear(path).map_err(|m| err(path, m))?);
                }
                files::check_faces(&faces).map_err(|(i, m)| err(&paths[i], m))?;
                EnvironmentImage::from_faces(&faces).map_err(|m| err(&paths[0], m))?
            }
        };
        Ok(image.rotated(self.rotate_degrees).scaled(self.intensity))
    }
}

// `layout = "cube_faces"` always parses to `EnvironmentSource::Faces`.
fn unreachable_layout() -> Result<EnvironmentImage, String> {
    Err("layout = \"cube_faces\" takes faces = [...], not image".into())
}
