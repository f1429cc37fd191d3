//! The scene file every pipeline renders (TOML; see `examples/scenes/`).
//!
//! A scene names its hair (a `.hair` file or a procedural groom), the opaque
//! geometry (head, ground), a look-at camera, one light, the background and
//! the hair material. Unknown fields are errors, reported as
//! `path:line:column: message`. Relative paths are resolved against the
//! directory of the scene file.
//!
//! [`Light::view_proj`] fits the light's frustum tightly to the hair
//! (Halén & Wester 2007 §5.7: near/far fitted to the model, the
//! field of view fitted to its extremes), with the depth range running from
//! the nearest occluder to the farthest receiver so hair shadows reach the
//! ground.

use std::path::{Path, PathBuf};

use glam::{Mat4, Vec3};
use serde::Deserialize;

use crate::groom::{GroomSpec, HeadShape, ScalpRegion, Style};
use crate::hair_file::{HairError, HairFile};
use crate::mesh::Mesh;
use crate::strands::{Aabb, Strands};

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
}

/// Where the hair comes from.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum HairSource {
    /// A `.hair` file (relative to the scene file).
    File(PathBuf),
    /// A procedural groom.
    Procedural(GroomSpec),
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

/// A look-at perspective camera.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// Eye position.
    pub eye: [f32; 3],
    /// Point looked at.
    pub target: [f32; 3],
    /// Up direction.
    #[serde(default = "default_up")]
    pub up: [f32; 3],
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f32,
    /// Near plane distance.
    #[serde(default = "default_near")]
    pub near: f32,
    /// Far plane distance.
    #[serde(default = "default_far")]
    pub far: f32,
}

fn default_up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}
fn default_near() -> f32 {
    0.1
}
fn default_far() -> f32 {
    100.0
}

impl Camera {
    /// Right-handed look-at view matrix.
    pub fn view(&self) -> Mat4 {
        Mat4::look_at_rh(self.eye.into(), self.target.into(), self.up.into())
    }

    /// Right-handed perspective, depth 0..1 (wgpu).
    pub fn projection(&self, aspect: f32) -> Mat4 {
        Mat4::perspective_rh(self.fov_y_degrees.to_radians(), aspect, self.near, self.far)
    }

    /// `projection(aspect) * view()`.
    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        self.projection(aspect) * self.view()
    }
}

/// Kind of light.
#[derive(Debug, Clone, PartialEq)]
pub enum LightKind {
    /// Parallel light travelling along `direction`.
    Directional {
        /// Direction the light travels (from the light toward the scene).
        direction: [f32; 3],
    },
    /// A spot light at `position` pointing along `direction`.
    Spot {
        /// Position.
        position: [f32; 3],
        /// Axis direction (from the light toward the scene).
        direction: [f32; 3],
        /// Full apex angle of the cone, degrees.
        cone_degrees: f32,
    },
}

/// The one light. In TOML: `type = "directional"` with `direction`, or
/// `type = "spot"` with `position`, `direction`, `cone_degrees`; plus
/// `color` and `intensity`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(try_from = "LightToml")]
pub struct Light {
    /// Directional or spot.
    pub kind: LightKind,
    /// Linear RGB color.
    pub color: [f32; 3],
    /// Scale on `color`.
    pub intensity: f32,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightToml {
    #[serde(rename = "type")]
    kind: String,
    direction: [f32; 3],
    position: Option<[f32; 3]>,
    cone_degrees: Option<f32>,
    #[serde(default = "white")]
    color: [f32; 3],
    #[serde(default = "one")]
    intensity: f32,
}

fn white() -> [f32; 3] {
    [1.0, 1.0, 1.0]
}
fn one() -> f32 {
    1.0
}

impl TryFrom<LightToml> for Light {
    type Error = String;
    fn try_from(t: LightToml) -> Result<Light, String> {
        if Vec3::from(t.direction).length_squared() == 0.0 || !Vec3::from(t.direction).is_finite() {
            return Err("light.direction must be a finite non-zero vector".into());
        }
        let kind = match t.kind.as_str() {
            "directional" => {
                if t.position.is_some() || t.cone_degrees.is_some() {
                    return Err("a directional light has no position or cone_degrees".into());
                }
                LightKind::Directional {
                    direction: t.direction,
                }
            }
            "spot" => {
                let position = t.position.ok_or("a spot light needs position")?;
                let cone_degrees = t.cone_degrees.ok_or("a spot light needs cone_degrees")?;
                if !(cone_degrees > 0.0 && cone_degrees < 179.0) {
                    return Err(format!(
                        "light.cone_degrees must be in (0, 179), got {cone_degrees}"
                    ));
                }
                LightKind::Spot {
                    position,
                    direction: t.direction,
                    cone_degrees,
                }
            }
            other => {
                return Err(format!(
                    "unknown light type {other:?} (expected \"directional\" or \"spot\")"
                ));
            }
        };
        Ok(Light {
            kind,
            color: t.color,
            intensity: t.intensity,
        })
    }
}

impl Light {
    /// Unit direction in which the light travels.
    pub fn direction(&self) -> Vec3 {
        let d = match &self.kind {
            LightKind::Directional { direction } | LightKind::Spot { direction, .. } => {
                Vec3::from(*direction)
            }
        };
        d.normalize_or(Vec3::NEG_Y)
    }

    /// Unit vector from the scene toward the light (for a spot: the reverse
    /// of its axis; use [`Light::direction_to_light_from`] per point).
    pub fn direction_to_light(&self) -> Vec3 {
        -self.direction()
    }

    /// Unit vector from `point` toward the light.
    pub fn direction_to_light_from(&self, point: Vec3) -> Vec3 {
        match &self.kind {
            LightKind::Directional { .. } => self.direction_to_light(),
            LightKind::Spot { position, .. } => {
                (Vec3::from(*position) - point).normalize_or(self.direction_to_light())
            }
        }
    }

    /// `color * intensity`.
    pub fn radiance(&self) -> Vec3 {
        Vec3::from(self.color) * self.intensity
    }

    fn up_for(dir: Vec3) -> Vec3 {
        if dir.cross(Vec3::Y).length_squared() < 1e-6 {
            Vec3::Z
        } else {
            Vec3::Y
        }
    }

    /// The light's view matrix (right-handed, looking along its direction).
    /// For a directional light the eye is placed behind `occluders`.
    pub fn view(&self, occluders: Aabb) -> Mat4 {
        let dir = self.direction();
        match &self.kind {
            LightKind::Directional { .. } => {
                let c = occluders.center();
                let radius = occluders.extent().length() * 0.5 + 1.0;
                Mat4::look_at_rh(c - dir * radius * 2.0, c, Self::up_for(dir))
            }
            LightKind::Spot { position, .. } => {
                let p = Vec3::from(*position);
                Mat4::look_at_rh(p, p + dir, Self::up_for(dir))
            }
        }
    }

    /// Light view-projection fitted tightly (Halén & Wester 2007 §5.7): x/y (for a spot, the
    /// frustum's side planes, capped by its cone) fitted to the occluders'
    /// bounds as seen from the light; depth from the nearest occluder point
    /// to the farthest receiver point, so shadows cast by the occluders reach
    /// every receiver. Depth maps to 0..1 (wgpu).
    pub fn view_proj(&self, occluders: Aabb, receivers: Aabb) -> Mat4 {
        let occ = if occluders.is_empty() {
            Aabb::new(Vec3::splat(-1.0), Vec3::ONE)
        } else {
            occluders
        };
        let rec = if receivers.is_empty() {
            occ
        } else {
            receivers.union(&occ)
        };
        let view = self.view(occ);
        let occ_v: Vec<Vec3> = occ
            .corners()
            .iter()
            .map(|&c| view.transform_point3(c))
            .collect();
        let rec_v: Vec<Vec3> = rec
            .corners()
            .iter()
            .map(|&c| view.transform_point3(c))
            .collect();
        // distances along the view axis (-z in a right-handed view)
        let near_occ = occ_v.iter().map(|p| -p.z).fold(f32::INFINITY, f32::min);
        let far_all = rec_v.iter().map(|p| -p.z).fold(f32::NEG_INFINITY, f32::max);
        let margin = (far_all - near_occ).abs().max(1e-3) * 0.01;
        match &self.kind {
            LightKind::Directional { .. } => {
                let (mut l, mut r, mut b, mut t) = (
                    f32::INFINITY,
                    f32::NEG_INFINITY,
                    f32::INFINITY,
                    f32::NEG_INFINITY,
                );
                for p in &occ_v {
                    l = l.min(p.x);
                    r = r.max(p.x);
                    b = b.min(p.y);
                    t = t.max(p.y);
                }
                let pad = ((r - l).max(t - b) * 0.01).max(1e-4);
                let proj = Mat4::orthographic_rh(
                    l - pad,
                    r + pad,
                    b - pad,
                    t + pad,
                    near_occ - margin,
                    far_all + margin,
                );
                proj * view
            }
            LightKind::Spot { cone_degrees, .. } => {
                let half_cone = (cone_degrees.to_radians() * 0.5).tan();
                let near = (near_occ - margin).max(far_all.max(1.0) * 1e-4).max(1e-3);
                let far = far_all.max(near * 2.0) + margin;
                // slopes x/-z, y/-z of occluder corners; corners behind the
                // light make the fit meaningless, so fall back to the cone
                let in_front = occ_v.iter().all(|p| -p.z > 1e-4);
                let (mut l, mut r, mut b, mut t) = (-half_cone, half_cone, -half_cone, half_cone);
                if in_front {
                    let (mut l2, mut r2, mut b2, mut t2) = (
                        f32::INFINITY,
                        f32::NEG_INFINITY,
                        f32::INFINITY,
                        f32::NEG_INFINITY,
                    );
                    for p in &occ_v {
                        let (sx, sy) = (p.x / -p.z, p.y / -p.z);
                        l2 = l2.min(sx);
                        r2 = r2.max(sx);
                        b2 = b2.min(sy);
                        t2 = t2.max(sy);
                    }
                    l = l2.max(-half_cone);
                    r = r2.min(half_cone);
                    b = b2.max(-half_cone);
                    t = t2.min(half_cone);
                    if l >= r || b >= t {
                        (l, r, b, t) = (-half_cone, half_cone, -half_cone, half_cone);
                    }
                }
                Mat4::frustum_rh(l * near, r * near, b * near, t * near, near, far) * view
            }
        }
    }
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
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// The hair.
    pub hair: HairSource,
    /// The opaque head, if any.
    #[serde(default)]
    pub head: Option<Head>,
    /// The ground, if any.
    #[serde(default)]
    pub ground: Option<Ground>,
    /// The camera.
    pub camera: Camera,
    /// The one light.
    pub light: Light,
    /// The background.
    #[serde(default = "default_background")]
    pub background: Background,
    /// Hair material.
    #[serde(default)]
    pub material: HairMaterial,
    /// Constant ambient light intensity.
    #[serde(default = "default_ambient")]
    pub ambient: f32,
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
            hair: HairSource::Procedural(GroomSpec {
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
            }),
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
            background: Background::Color([0.05, 0.06, 0.08]),
            material: HairMaterial::default(),
            ambient: 0.15,
        }
    }

    /// Parses scene text; `path` is used in messages and to resolve relative
    /// paths (against its directory).
    pub fn from_toml_str(text: &str, path: &Path) -> Result<Scene, SceneError> {
        let mut scene: Scene = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((1, 1), |s| line_col(text, s.start));
            SceneError::Parse {
                path: path.to_path_buf(),
                line,
                column,
                message: e.message().trim().to_string(),
            }
        })?;
        scene.validate().map_err(|message| SceneError::Invalid {
            path: path.to_path_buf(),
            message,
        })?;
        let dir = path.parent().unwrap_or(Path::new(""));
        if let HairSource::File(p) = &mut scene.hair
            && p.is_relative()
        {
            *p = dir.join(&*p);
        }
        if let Background::Image(p) = &mut scene.background
            && p.is_relative()
        {
            *p = dir.join(&*p);
        }
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
        if let HairSource::Procedural(g) = &self.hair {
            g.validate().map_err(|m| format!("hair.procedural.{m}"))?;
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

    /// The strands to render: the file's, or the generated groom.
    pub fn strands(&self) -> Result<Strands, SceneError> {
        match &self.hair {
            HairSource::File(path) => {
                let (file, _warnings) = HairFile::read(path)?;
                Ok(Strands::from_hair_file(&file))
            }
            HairSource::Procedural(spec) => Ok(crate::groom::generate(spec)),
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
        for name in ["small.toml", "default.toml", "dense.toml", "stray.toml"] {
            let s = Scene::load(examples().join(name)).unwrap_or_else(|e| panic!("{e}"));
            let HairSource::Procedural(g) = &s.hair else {
                panic!("{name}: procedural expected")
            };
            match name {
                "small.toml" => assert!(g.strands <= 1000 && g.segments <= 16),
                "dense.toml" => assert!(g.strands >= 20_000),
                "stray.toml" => assert!(g.stray_strands > 0),
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
    fn light_frustum_fits_occluders_and_reaches_receivers() {
        let occ = Aabb::new(Vec3::new(-1.0, -1.0, -1.0), Vec3::new(1.0, 1.0, 1.0));
        let rec = Aabb::new(Vec3::new(-6.0, -2.7, -6.0), Vec3::new(6.0, -2.7, 6.0));
        let lights = [
            Light {
                kind: LightKind::Directional {
                    direction: [-0.5, -1.0, -0.6],
                },
                color: [1.0; 3],
                intensity: 1.0,
            },
            Light {
                kind: LightKind::Spot {
                    position: [3.0, 6.0, 3.0],
                    direction: [-3.0, -6.0, -3.0],
                    cone_degrees: 60.0,
                },
                color: [1.0; 3],
                intensity: 1.0,
            },
        ];
        for light in lights {
            let m = light.view_proj(occ, rec);
            let proj: Vec<Vec3> = occ.corners().iter().map(|&c| m.project_point3(c)).collect();
            for p in &proj {
                assert!(p.x.abs() <= 1.0001 && p.y.abs() <= 1.0001, "{p}");
                assert!((-1e-4..=1.0001).contains(&p.z), "{p}");
            }
            // tight: some corner touches each side within 5%
            assert!(proj.iter().map(|p| p.x).fold(f32::MIN, f32::max) > 0.95);
            assert!(proj.iter().map(|p| p.x).fold(f32::MAX, f32::min) < -0.95);
            // the nearest occluder is near depth 0
            assert!(proj.iter().map(|p| p.z).fold(f32::MAX, f32::min) < 0.05);
            // the ground under the hair is inside the depth range
            let g = m.project_point3(Vec3::new(0.0, -2.7, 0.0));
            assert!((0.0..=1.0).contains(&g.z), "{g}");
        }
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
        assert_eq!(s.hair, HairSource::File(dir.path().join("models/x.hair")));
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
