//! Reading a scene file: the TOML shape (`camera`/`light` may be `"fit"`),
//! syntax, schema and keyframe errors as `path:line:column: message`, and
//! relative paths resolved against the scene file's directory.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::meshes::MeshToml;
use super::{
    Animation, Background, Camera, Framing, Ground, Hair, HairMaterial, HairSource, Head, Scene,
    SceneError,
};
use crate::camera::CameraSetting;
use crate::environment::EnvironmentSetting;
use crate::groom::GroomSpec;
use crate::light::LightSetting;

/// Every field may be left out (`docs/formats.md`, "Defaults"): the hair is
/// the procedural groom with its defaults, camera and light are fitted to
/// it, no head, no ground.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneToml {
    #[serde(default = "default_hair")]
    hair: Hair,
    #[serde(default)]
    head: Option<Head>,
    #[serde(default)]
    ground: Option<Ground>,
    #[serde(default)]
    meshes: Vec<MeshToml>,
    #[serde(default)]
    camera: CameraSetting,
    #[serde(default = "LightSetting::fitted")]
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
            // Read from their files by `from_toml_str`.
            meshes: Vec::new(),
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

fn default_hair() -> Hair {
    Hair::from(HairSource::Procedural(GroomSpec::default()))
}
fn default_background() -> Background {
    Background::Color([0.05, 0.06, 0.08])
}
fn default_ambient() -> f32 {
    0.15
}

/// A range error of `Scene::validate`, whose message starts with the field's
/// dotted name (`light.intensity must be ≥ 0`), placed at the field's value
/// in the text when it is written there; a default out of range (or a field
/// the text does not hold) has no place: the file alone.
fn located(text: &str, path: &Path, message: String) -> SceneError {
    let field = message.split(' ').next().unwrap_or_default();
    match key_line_col(text, field) {
        Some((line, column)) => SceneError::Parse {
            path: path.to_path_buf(),
            line,
            column,
            message,
        },
        None => SceneError::Invalid {
            path: path.to_path_buf(),
            message,
        },
    }
}

/// 1-based (line, column) of the value of a dotted key (`head.albedo`) in
/// scene text that parsed.
fn key_line_col(text: &str, dotted: &str) -> Option<(usize, usize)> {
    let table = toml::de::DeTable::parse(text).ok()?;
    let mut table = table.get_ref();
    let mut parts = dotted.split('.').peekable();
    while let Some(part) = parts.next() {
        let (_, value) = table.iter().find(|(k, _)| k.get_ref() == part)?;
        if parts.peek().is_none() {
            return Some(line_col(text, value.span().start));
        }
        match value.get_ref() {
            toml::de::DeValue::Table(inner) => table = inner,
            _ => return None,
        }
    }
    None
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

/// serde's "unknown field `x`, expected one of `a`, `b`" (or "expected `a`
/// or `b`"), with "; did you mean `a`?" when one is close.
fn with_suggestion(message: &str) -> String {
    let Some(rest) = message.strip_prefix("unknown field `") else {
        return message.to_string();
    };
    let Some((name, expected)) = rest.split_once('`') else {
        return message.to_string();
    };
    // The names between backticks after the unknown one.
    let candidates = expected.split('`').skip(1).step_by(2);
    format!(
        "{message}{}",
        plait_graph::suggest::did_you_mean(name, candidates)
    )
}

/// Where `[hair] file = "…"` is written in scene text that parsed: read
/// apart from `Hair`, which serde builds without the text.
fn hair_file_span(text: &str) -> Option<std::ops::Range<usize>> {
    #[derive(Deserialize)]
    struct Root {
        hair: Option<HairFile>,
    }
    #[derive(Deserialize)]
    struct HairFile {
        file: Option<toml::Spanned<toml::Value>>,
    }
    let root: Root = toml::from_str(text).ok()?;
    Some(root.hair?.file?.span())
}

impl Scene {
    /// Parses scene text; `path` is used in messages and to resolve relative
    /// paths (against its directory).
    pub fn from_toml_str(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let mut parsed: SceneToml = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((1, 1), |s| line_col(text, s.start));
            SceneError::Parse {
                path: path.to_path_buf(),
                line,
                column,
                message: with_suggestion(e.message().trim()),
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
        let mesh_entries = std::mem::take(&mut parsed.meshes);
        let mut scene = Scene::from(parsed);
        scene.environment.declared_at = environment_at;
        scene.hair.declared_at = hair_file_span(text).map(|span| {
            let (line, column) = line_col(text, span.start);
            format!("{}:{line}:{column}", path.display())
        });
        let invalid = |message| SceneError::Invalid {
            path: path.to_path_buf(),
            message,
        };
        scene
            .validate()
            .map_err(|message| located(text, path, message))?;
        for (i, m) in mesh_entries.iter().enumerate() {
            m.validate(i).map_err(invalid)?;
        }
        let heads = mesh_entries.iter().filter(|m| m.is_head()).count();
        if heads > 1 {
            return Err(invalid(format!(
                "{heads} meshes have role = \"head\"; a scene has one head"
            )));
        }
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
        if plait_assets::is_builtin(path) {
            let mesh_files: Vec<PathBuf> =
                mesh_entries.iter().map(|m| dir.join(m.file())).collect();
            scene.check_builtin_files(path, &mesh_files)?;
        }
        for (i, m) in mesh_entries.iter().enumerate() {
            let (line, column) = line_col(text, m.file_span().start);
            let at = format!("{}:{line}:{column}", path.display());
            scene.meshes.push(m.load(i, dir, at)?);
        }
        Ok(scene)
    }

    /// A built-in copy of a scene (`<built-in>/examples/scenes/…`) carries
    /// its text only: a file it names (hair, background or environment
    /// image, mesh) is not built in, which is said here rather than as a missing
    /// `<built-in>/…` file at render time.
    fn check_builtin_files(&self, path: &Path, meshes: &[PathBuf]) -> Result<(), SceneError> {
        let mut named: Vec<&Path> = meshes.iter().map(PathBuf::as_path).collect();
        if let HairSource::File(p) = &self.hair.source {
            named.push(p);
        }
        if let Background::Image(p) = &self.background {
            named.push(p);
        }
        let environment = self.environment.files();
        named.extend(environment.iter().map(PathBuf::as_path));
        match named.first() {
            None => Ok(()),
            Some(file) => Err(SceneError::Invalid {
                path: path.to_path_buf(),
                message: format!(
                    "this built-in scene names {}, which plait does not carry built in; \
                     set {} to a plait checkout (or copy the scene next to its files)",
                    file.strip_prefix(path.parent().unwrap_or(Path::new("")))
                        .unwrap_or(file)
                        .display(),
                    plait_assets::SEARCH_PATH_VAR
                ),
            }),
        }
    }

    /// Loads a scene file, or a built-in copy (`<built-in>/…`, see
    /// `plait_assets`).
    pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let text = plait_assets::read_to_string(path).map_err(|error| SceneError::Io {
            path: path.to_path_buf(),
            error,
        })?;
        Scene::from_toml_str(&text, path)
    }
}
