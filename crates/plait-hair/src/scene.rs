//! The scene file every pipeline renders (TOML; see `examples/scenes/`).
//!
//! A scene names its hair (a `.hair` or `.tfx` file or a procedural groom,
//! with optional follow strands and placement: [`crate::hair_source`]), the
//! opaque geometry (head, ground), a camera (look-at, or `"fit"` to the
//! hair), one light (or `"fit"`), the background and the hair material.
//! Unknown fields are errors, reported as `path:line:column: message`.
//! Relative paths are resolved against the directory of the scene file.

use std::path::{Path, PathBuf};

use glam::Vec3;
use serde::Deserialize;

pub use crate::animation::Animation;
use crate::asset::{Asset, AssetError};
use crate::camera::CameraSetting;
pub use crate::camera::{Camera, CameraFit};
use crate::environment::{Environment, EnvironmentError, EnvironmentSetting};
use crate::groom::{GroomSpec, HeadShape, ScalpRegion, Style};
use crate::hair_file::HairError;
pub use crate::hair_source::{Hair, HairSource};
use crate::light::LightSetting;
pub use crate::light::{Light, LightKind};
use crate::mesh::Mesh;
use crate::strands::{Aabb, Strands};
use crate::tfx::TfxError;

/// Errors loading a scene or its hair.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("{}: {error}", path.display())]
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
    /// The hair file could not be read (the error names it).
    #[error(transparent)]
    Hair(#[from] HairError),
    /// The `.tfx` file could not be read (the error names it).
    #[error(transparent)]
    Tfx(#[from] TfxError),
    /// The hair file is of neither format (the error names it).
    #[error("{0}")]
    UnknownAsset(String),
    /// The environment image could not be used (the error names it).
    #[error(transparent)]
    Environment(#[from] EnvironmentError),
}

impl From<AssetError> for SceneError {
    fn from(e: AssetError) -> Self {
        match e {
            AssetError::Hair(e) => SceneError::Hair(e),
            AssetError::Tfx(e) => SceneError::Tfx(e),
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
            diffuse: 0.8,
            specular: 0.3,
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
    /// The built-in default scene (equal to `examples/scenes/default.toml`):
    /// about 10,000 wavy strands × 32 segments on a head, lit from above,
    /// front and side, over a ground that catches the shadow.
    pub fn builtin_default() -> Scene {
        let head = HeadShape {
            center: [0.0, 0.0, 0.0],
            radii: [0.9, 1.05, 1.0],
        };
        Scene {
            hair: Hair::from(HairSource::Procedural(GroomSpec {
                style: Style::Wavy,
                strands: 10_000,
                segments: 32,
                seed: 1,
                length: 2.0,
                length_variation: 0.15,
                thickness: 0.006,
                thickness_variation: 0.2,
                tip_thickness: 0.4,
                alpha: 0.6,
                alpha_variation: 0.1,
                color: [0.32, 0.2, 0.11],
                color_variation: 0.15,
                head,
                scalp: ScalpRegion {
                    max_polar_degrees: 105.0,
                    face_polar_degrees: 50.0,
                    face_half_width_degrees: 70.0,
                },
                gravity: 2.5,
                wave_amplitude: None,
                wave_period: None,
                stray_strands: 0,
                guides: None,
            })),
            head: Some(Head {
                center: head.center,
                radii: head.radii,
                albedo: [0.75, 0.55, 0.45],
            }),
            ground: Some(Ground {
                height: -2.7,
                half_size: 6.0,
                albedo: [0.6, 0.6, 0.6],
            }),
            camera: Camera {
                eye: [2.0, 0.5, 7.6],
                target: [0.0, -0.6, 0.0],
                up: [0.0, 1.0, 0.0],
                fov_y_degrees: 35.0,
                near: 0.1,
                far: 100.0,
            },
            light: Light {
                kind: LightKind::Directional {
                    direction: [-0.5, -1.0, -0.6],
                },
                color: [1.0, 0.97, 0.92],
                intensity: 3.0,
            },
            framing: Framing::default(),
            background: Background::Color([0.05, 0.06, 0.08]),
            material: HairMaterial::default(),
            ambient: 0.15,
            environment: Environment::default(),
            animation: None,
        }
    }

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

    /// Range checks after parsing; messages name the field.
    pub fn validate(&self) -> Result<(), String> {
        self.hair.validate()?;
        if let Some(fit) = &self.framing.camera {
            fit.validate()?;
        }
        let c = &self.camera;
        if !(c.fov_y_degrees > 0.0 && c.fov_y_degrees < 180.0) {
            return Err(format!(
                "camera.fov_y_degrees must be in (0, 180), got {}",
                c.fov_y_degrees
            ));
        }
        if !(c.near > 0.0 && c.far > c.near) {
            return Err(format!(
                "camera needs 0 < near < far, got near {} far {}",
                c.near, c.far
            ));
        }
        if Vec3::from(c.eye) == Vec3::from(c.target) {
            return Err("camera.eye and camera.target must differ".into());
        }
        // NaN or infinity anywhere would reach the shaders as black or
        // garbage pixels, so every number is checked here, by name.
        let l = &self.light;
        let m = &self.material;
        let mut numbers: Vec<(&str, &[f32])> = vec![
            ("camera.eye", &c.eye),
            ("camera.target", &c.target),
            ("camera.up", &c.up),
            ("light.color", &l.color),
            ("light.intensity", std::slice::from_ref(&l.intensity)),
            ("material.color", &m.color),
            ("material.alpha", std::slice::from_ref(&m.alpha)),
            ("material.diffuse", std::slice::from_ref(&m.diffuse)),
            ("material.specular", std::slice::from_ref(&m.specular)),
            (
                "material.specular_exponent",
                std::slice::from_ref(&m.specular_exponent),
            ),
            (
                "material.specular_shift",
                std::slice::from_ref(&m.specular_shift),
            ),
            ("ambient", std::slice::from_ref(&self.ambient)),
        ];
        if let LightKind::Spot { position, .. } = &l.kind {
            numbers.push(("light.position", position));
        }
        if let Some(h) = &self.head {
            numbers.extend([
                ("head.center", &h.center[..]),
                ("head.albedo", &h.albedo[..]),
            ]);
        }
        if let Some(g) = &self.ground {
            numbers.extend([
                ("ground.height", std::slice::from_ref(&g.height)),
                ("ground.albedo", &g.albedo[..]),
            ]);
        }
        if let Background::Color(color) = &self.background {
            numbers.push(("background.color", color));
        }
        if let Some((name, _)) = numbers
            .iter()
            .find(|(_, v)| !v.iter().all(|x| x.is_finite()))
        {
            return Err(format!("{name} must be finite"));
        }
        if let Some(h) = &self.head
            && h.radii.iter().any(|r| r.is_nan() || *r <= 0.0)
        {
            return Err("head.radii must be > 0".into());
        }
        if let Some(g) = &self.ground
            && (g.half_size.is_nan() || g.half_size <= 0.0)
        {
            return Err("ground.half_size must be > 0".into());
        }
        Ok(())
    }

    /// The strands to render: the file's or the generated groom, with its
    /// follow strands, placed by its transform.
    pub fn strands(&self) -> Result<Strands, SceneError> {
        let (mut strands, origin) = match &self.hair.source {
            HairSource::File(path) => {
                let (asset, _warnings) = Asset::read(path)?;
                (asset.strands(), path.clone())
            }
            HairSource::Procedural(spec) => (
                crate::groom::generate(spec),
                PathBuf::from("<procedural groom>"),
            ),
        };
        let invalid = |message: String| SceneError::Invalid {
            path: origin.clone(),
            message,
        };
        if let Some(follow) = &self.hair.follow {
            follow
                .check_size(&strands)
                .map_err(|m| invalid(format!("hair.{m}")))?;
            strands = follow.apply(&strands);
        }
        if let Some(transform) = &self.hair.transform {
            transform.apply(&mut strands).map_err(invalid)?;
        }
        Ok(strands)
    }

    /// [`Scene::strands`], then the camera and light given as `"fit"` are
    /// fitted to the hair (and head): what a renderer calls.
    pub fn load_hair(&mut self) -> Result<Strands, SceneError> {
        let strands = self.strands()?;
        self.frame(strands.bounds());
        Ok(strands)
    }

    /// Fits the camera and light given as `"fit"` to `hair` (the head is
    /// added; the ground only widens the depth range).
    pub fn frame(&mut self, hair: Aabb) {
        let head = self
            .head
            .as_ref()
            .map(|h| {
                let (c, r) = (Vec3::from(h.center), Vec3::from(h.radii));
                Aabb::new(c - r, c + r)
            })
            .unwrap_or(Aabb::EMPTY);
        let subject = hair.union(&head);
        if let Some(fit) = &self.framing.camera {
            self.camera = fit.camera(subject, subject.union(&self.opaque_bounds()));
        }
        if self.framing.light {
            let fitted = Light::fitted(&self.camera, self.light.intensity);
            self.light.kind = fitted.kind;
        }
    }

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

#[cfg(test)]
mod tests {
    use super::*;

    fn examples() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes")
    }

    #[test]
    fn default_toml_equals_builtin() {
        let s = Scene::load(examples().join("default.toml")).expect("default.toml loads");
        assert_eq!(s, Scene::builtin_default());
    }

    #[test]
    fn all_example_scenes_load_and_validate() {
        for name in [
            "small.toml",
            "default.toml",
            "dense.toml",
            "stray.toml",
            "head_turn.toml",
            "stray_shake.toml",
        ] {
            let s = Scene::load(examples().join(name)).unwrap_or_else(|e| panic!("{e}"));
            let HairSource::Procedural(g) = &s.hair.source else {
                panic!("{name}: procedural expected")
            };
            match name {
                "small.toml" => assert!(g.strands <= 1000 && g.segments <= 16),
                "dense.toml" => assert!(g.strands >= 20_000),
                "stray.toml" | "stray_shake.toml" => assert!(g.stray_strands > 0),
                _ => {}
            }
        }
        let small = Scene::load(examples().join("small.toml")).expect("small");
        let strands = small.strands().expect("generate");
        assert!(strands.strand_count() >= 100);
    }

    #[test]
    fn builtin_default_frames_the_hair() {
        let s = Scene::builtin_default();
        let hair = s.strands().expect("procedural");
        assert!((9_000..=11_000).contains(&hair.strand_count()));
        assert_eq!(hair.segment_count(), hair.strand_count() * 32);
        let vp = s.camera.view_proj(16.0 / 9.0);
        let b = hair.bounds();
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for c in b.corners() {
            let p = vp.project_point3(c);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        // the hair's bounds cover most of the view height and stay inside it
        assert!(
            hi.y - lo.y > 1.2,
            "hair spans {} of NDC height 2",
            hi.y - lo.y
        );
        assert!(
            lo.y > -1.2 && hi.y < 1.2 && lo.x > -1.2 && hi.x < 1.2,
            "{lo} {hi}"
        );
        assert!(lo.z > 0.0 && hi.z < 1.0);
        // light from above (travels downward)
        assert!(s.light.direction_to_light().y > 0.5);
        // the ground is below the hair
        let ground = s.ground.as_ref().expect("ground");
        assert!(ground.height < b.min.y);
        assert_eq!(s.opaque_meshes().len(), 2);
    }

    #[test]
    fn the_head_turn_turns_the_head_and_comes_back() {
        let s = Scene::load(examples().join("head_turn.toml")).expect("head_turn.toml");
        assert_eq!(s.head_model(0.0), glam::Mat4::IDENTITY);
        assert!(s.head_model(2.0).abs_diff_eq(glam::Mat4::IDENTITY, 1e-6));
        // At 1 s the face (+Z) looks 45° towards +X.
        let forward = s.head_model(1.0).transform_vector3(Vec3::Z);
        let yaw = forward.x.atan2(forward.z).to_degrees();
        assert!((yaw - 45.0).abs() < 0.5, "yaw {yaw}");
        let still = Scene::load(examples().join("small.toml")).expect("small");
        assert_eq!(still.head_model(1.0), glam::Mat4::IDENTITY);
    }

    #[test]
    fn bad_keyframes_are_reported_at_their_line_and_column() {
        let p = Path::new("s.toml");
        let keys = |second: &str| {
            format!(
                "[hair.procedural]\n{MINIMAL}[[animation.keys]]\ntime = 0.5\n[[animation.keys]]\n{second}\n"
            )
        };
        // MINIMAL is 7 lines; the second key's body is line 12.
        for (second, column, needle) in [
            ("time = 0.25", 8, "key times must increase"),
            ("time = nan", 8, "animation.keys[1].time must be finite"),
            (
                "time = 1.0\nrotate_degrees = [0, 30]",
                18,
                "expected an array of length 3",
            ),
            (
                "time = 1.0\ntranslate = [0, inf, 0]",
                13,
                "animation.keys[1].translate must be finite",
            ),
            ("time = 1.0\nspin = 3", 1, "unknown field `spin`"),
        ] {
            let e = Scene::from_toml_str(&keys(second), p)
                .unwrap_err()
                .to_string();
            let line = if second.contains('\n') { 13 } else { 12 };
            assert!(
                e.starts_with(&format!("s.toml:{line}:{column}: ")) && e.contains(needle),
                "{second}: {e}"
            );
        }
        let e = Scene::from_toml_str(
            &format!("[hair.procedural]\n{MINIMAL}[animation]\nkeys = []\n"),
            p,
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("s.toml:10:8: ") && e.contains("empty"), "{e}");
    }

    #[test]
    fn parse_errors_have_line_and_column() {
        let p = Path::new("dir/scene.toml");
        let text = "[hair.procedural]\nstrands = 10\n\n[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\nfov_y_degrees = 40\nfov = 3\n";
        let e = Scene::from_toml_str(text, p).unwrap_err();
        let msg = e.to_string();
        assert!(msg.starts_with("dir/scene.toml:8:1:"), "{msg}");
        assert!(msg.contains("fov"), "{msg}");
        let e = Scene::from_toml_str("[hair.procedural]\nstyle = \"frizzy\"\n", p).unwrap_err();
        assert!(e.to_string().starts_with("dir/scene.toml:2:"), "{e}");
    }

    const MINIMAL: &str = "[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\nfov_y_degrees = 40\n[light]\ntype = \"directional\"\ndirection = [0, -1, 0]\n";

    #[test]
    fn relative_paths_resolve_against_scene_dir_and_missing_hair_is_named() {
        let dir = tempfile::tempdir().expect("tempdir");
        let text = format!(
            "hair = {{ file = \"models/x.hair\" }}\nbackground = {{ image = \"env.png\" }}\n{MINIMAL}"
        );
        let path = dir.path().join("s.toml");
        std::fs::write(&path, text).expect("write");
        let s = Scene::load(&path).expect("loads");
        assert_eq!(
            s.hair.source,
            HairSource::File(dir.path().join("models/x.hair"))
        );
        assert_eq!(s.background, Background::Image(dir.path().join("env.png")));
        let e = s.strands().unwrap_err();
        assert!(e.to_string().contains("x.hair"), "{e}");
        // and a real file loads
        std::fs::create_dir(dir.path().join("models")).expect("mkdir");
        let mut hs = Strands::new();
        hs.push_strand(&[Vec3::ZERO, Vec3::Y], |_| 0.1, |_| 1.0, Vec3::ONE);
        hs.to_hair_file()
            .expect("file")
            .write(dir.path().join("models/x.hair"))
            .expect("write");
        assert_eq!(s.strands().expect("reads").point_count(), 2);
    }

    #[test]
    fn invalid_values_name_the_field() {
        let p = Path::new("s.toml");
        let e = Scene::from_toml_str(&format!("[hair.procedural]\nsegments = 0\n{MINIMAL}"), p)
            .unwrap_err();
        assert!(e.to_string().contains("hair.procedural.segments"), "{e}");
        let bad_light = MINIMAL.replace("directional", "spot");
        let e = Scene::from_toml_str(&format!("hair = {{ file = \"a.hair\" }}\n{bad_light}"), p)
            .unwrap_err();
        assert!(e.to_string().contains("position"), "{e}");
    }
}
