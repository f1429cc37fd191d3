//! Reading a scene file: the TOML shape (`camera`/`light` may be `"fit"`),
//! syntax, schema and keyframe errors as `path:line:column: message`, and
//! relative paths resolved against the scene file's directory.

use std::path::Path;

use serde::Deserialize;

use super::{
    Animation, Background, Camera, Framing, Ground, Hair, HairMaterial, HairSource, Head, Scene,
    SceneError,
};
use crate::camera::CameraSetting;
use crate::environment::EnvironmentSetting;
use crate::light::LightSetting;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneToml {
    hair: Hair,
    #[serde(default)]
    head: Option<Head>,
    #[serde(default)]
    ground: Option<Ground>,
    camera: CameraSetting,
    light: LightSetting,
    #[serde(default = "default_background")]
    background: Background,
    #[serde(default)]
    material: HairMaterial,
    #[serde(default = "default_ambient")]
    ambient: f32,
    #[serde(default)]
    environment: Option<toml::Spanned<EnvironmentSetting>>,
    animation: Option<Animation>,
}

impl From<SceneToml> for Scene {
    fn from(t: SceneToml) -> Scene {
        let (camera, camera_fit) = match t.camera {
            CameraSetting::Fixed(c) => (c, None),
            CameraSetting::Fit(fit) => (Camera::looking_down_z(), Some(fit)),
        };
        Scene {
            hair: t.hair,
            head: t.head,
            ground: t.ground,
            camera,
            light: t.light.light,
            framing: Framing {
                camera: camera_fit,
                light: t.light.fit,
            },
            background: t.background,
            material: t.material,
            ambient: t.ambient,
            // Its place in the file is filled in by `from_toml_str`.
            environment: t.environment.map(|e| e.into_inner().0).unwrap_or_default(),
            animation: t.animation,
        }
    }
}

fn default_background() -> Background {
    Background::Color([0.05, 0.06, 0.08])
}
fn default_ambient() -> f32 {
    0.15
}

/// 1-based (line, column) of a byte offset.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let mut start = offset;
    while start > 0 && !text.is_char_boundary(start) {
        start -= 1;
    }
    let before = &text[..start];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

impl Scene {
    /// Parses scene text; `path` is used in messages and to resolve relative
    /// paths (against its directory).
    pub fn from_toml_str(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let parsed: SceneToml = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((1, 1), |s| line_col(text, s.start));
            SceneError::Parse {
                path: path.to_path_buf(),
                line,
                column,
                message: e.message().trim().to_string(),
            }
        })?;
        let environment_at = parsed.environment.as_ref().map(|e| {
            let (line, column) = line_col(text, e.span().start);
            format!("{}:{line}:{column}", path.display())
        });
        if let Some(e) = parsed.animation.as_ref().and_then(|a| a.validate().err()) {
            let (line, column) = line_col(text, e.span.start);
            return Err(SceneError::Parse {
                path: path.to_path_buf(),
                line,
                column,
                message: e.message,
            });
        }
        let mut scene = Scene::from(parsed);
        scene.environment.declared_at = environment_at;
        scene.validate().map_err(|message| SceneError::Invalid {
            path: path.to_path_buf(),
            message,
        })?;
        let dir = path.parent().unwrap_or(Path::new(""));
        if let HairSource::File(p) = &mut scene.hair.source
            && p.is_relative()
        {
            *p = dir.join(&*p);
        }
        if let Background::Image(p) = &mut scene.background
            && p.is_relative()
        {
            *p = dir.join(&*p);
        }
        scene.environment.resolve_paths(dir);
        Ok(scene)
    }

    /// Loads a scene file.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|error| SceneError::Io {
            path: path.to_path_buf(),
            error,
        })?;
        Scene::from_toml_str(&text, path)
    }
}
