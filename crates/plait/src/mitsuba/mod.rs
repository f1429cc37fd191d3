//! Export a plait scene for Mitsuba 3, the path tracer plait's physical
//! checks compare against (issues 42 and 47).
//!
//! [`plan`] turns a loaded scene ([`SceneData`]: the same loading `plait
//! render` does, so the strands, camera and light are the ones plait draws)
//! into a [`MitsubaScene`]: hair grouped by colour and opacity (Mitsuba binds
//! one BSDF to a shape), the opaque meshes with their albedo, the camera, the
//! light, the ambient and the background. [`MitsubaScene::write`] writes it as
//! a folder `scripts/mitsuba/render.py` renders: `scene.xml`, one
//! `bsplinecurve` file per hair group, one OBJ per mesh and `plait.json`
//! (what the XML cannot hold: the background, and the notes).
//!
//! Nothing is dropped silently: what Mitsuba cannot express is an
//! [`ExportError`] (a spot light, a background image, a hair colour with no
//! finite absorption) or a note in [`MitsubaScene::notes`] (plait's shading
//! parameters Mitsuba does not use, an animation exported at time 0).

mod write;

pub use write::Written;

use std::path::PathBuf;

use glam::{Mat4, Vec3};

use crate::session::SceneData;
use plait_hair::{Background, LightKind};

/// Errors exporting a scene for Mitsuba.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A scene feature Mitsuba cannot be given as plait renders it.
    #[error("the Mitsuba export cannot express {0}")]
    Unsupported(String),
    /// A file of the export could not be written.
    #[error("{}: cannot write: {error}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        error: std::io::Error,
    },
}

/// The fibre model Mitsuba's `hair` BSDF is given (Chiang, Bitterli, Tappan
/// & Burley 2016, "A Practical and Controllable Hair and Fur Model for
/// Production Path Tracing", EGSR). [`Fibre::standard`] is the paper's
/// standard fibre, the one issue 47's measurement uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fibre {
    /// Longitudinal roughness β_m.
    pub longitudinal_roughness: f32,
    /// Azimuthal roughness β_n (also in the colour → absorption mapping).
    pub azimuthal_roughness: f32,
    /// Cuticle scale tilt α, degrees.
    pub scale_tilt_degrees: f32,
    /// Index of refraction η of the fibre.
    pub eta: f32,
}

impl Fibre {
    /// The shading point's fibre defaults in `library` (its
    /// `techniques/shading/point.toml`), which the chiang technique's are:
    /// one fibre for both sides, read from the library value the caller
    /// renders with, never from the search path behind its back. A default
    /// the point file lacks is NaN, which every fibre check refuses.
    pub fn standard(library: &plait_gpu::PassLibrary) -> Self {
        let value = |name: &str| match crate::passes::points::default(library, "shading", name) {
            Some(plait_graph::Value::Float(f)) => f as f32,
            _ => f32::NAN,
        };
        let [beta_m, beta_n, tilt, eta] = [
            "chiang_beta_m",
            "chiang_beta_n",
            "chiang_tilt",
            "chiang_eta",
        ]
        .map(value);
        Fibre {
            longitudinal_roughness: beta_m,
            azimuthal_roughness: beta_n,
            scale_tilt_degrees: tilt,
            eta,
        }
    }
}

/// Absorption coefficient σ_a (per unit fibre radius, as Mitsuba's and
/// pbrt's hair BSDF take it) that gives a fibre of azimuthal roughness
/// `beta_n` the colour `color` after multiple scattering: Chiang et al.
/// 2016 §4.2, σ_a = (ln c / (5.969 − 0.215 β_n + 2.532 β_n² − 10.73 β_n³ +
/// 5.574 β_n⁴ + 0.245 β_n⁵))². A channel outside (0, 1] has no such σ_a.
pub fn sigma_a_from_color(color: Vec3, beta_n: f32) -> Result<Vec3, ExportError> {
    if !color.cmpgt(Vec3::ZERO).all() || !color.cmple(Vec3::ONE).all() {
        return Err(ExportError::Unsupported(format!(
            "hair colour {:?}: Chiang 2016 §4.2 maps only channels in (0, 1] to an absorption",
            color.to_array()
        )));
    }
    let b = beta_n;
    let d = 5.969 - 0.215 * b + 2.532 * b.powi(2) - 10.73 * b.powi(3)
        + 5.574 * b.powi(4)
        + 0.245 * b.powi(5);
    Ok(Vec3::from_array(
        color.to_array().map(|c| (c.ln() / d).powi(2)),
    ))
}

/// Strands of one colour and opacity: one Mitsuba shape and BSDF.
#[derive(Debug, Clone, PartialEq)]
pub struct HairGroup {
    /// Linear RGB colour (the strand's colour times `material.color`).
    pub color: Vec3,
    /// Opacity (the strand's alpha times `material.alpha`); below 1 the
    /// BSDF is wrapped in Mitsuba's `mask`.
    pub alpha: f32,
    /// σ_a from `color` ([`sigma_a_from_color`]).
    pub sigma_a: Vec3,
    /// Each strand's control points: position and radius (plait's
    /// thickness is a diameter, Mitsuba's curves take radii).
    pub strands: Vec<Vec<(Vec3, f32)>>,
}

/// One opaque mesh with a diffuse BSDF.
#[derive(Debug, Clone, PartialEq)]
pub struct MitsubaMesh {
    /// plait's name ("head", "ground", or a `[[meshes]]` name).
    pub name: String,
    /// World-space positions and normals (the head posed at time 0).
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// Triangle list.
    pub indices: Vec<u32>,
    /// Diffuse albedo ρ (Lambert, radiance ρ/π · E).
    pub albedo: Vec3,
}

/// The perspective camera.
#[derive(Debug, Clone, PartialEq)]
pub struct MitsubaCamera {
    pub eye: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    /// Vertical field of view, degrees (Mitsuba's `fov_axis = "y"`).
    pub fov_y_degrees: f32,
    pub near: f32,
    pub far: f32,
    /// Image width and height in pixels.
    pub size: (u32, u32),
}

/// Everything Mitsuba is given, in plait's units: a directional light's
/// irradiance, the ambient's and the background's radiance.
#[derive(Debug, Clone, PartialEq)]
pub struct MitsubaScene {
    pub hair: Vec<HairGroup>,
    pub meshes: Vec<MitsubaMesh>,
    pub camera: MitsubaCamera,
    pub light: MitsubaLight,
    /// Radiance of the uniform environment (`ambient`), none when 0.
    pub ambient: Vec3,
    /// Radiance seen where a camera ray hits nothing.
    pub background: Vec3,
    pub fibre: Fibre,
    /// What the export leaves out or changes, each said once.
    pub notes: Vec<String>,
}

/// The scene's key light as a Mitsuba emitter.
#[derive(Debug, Clone, PartialEq)]
pub enum MitsubaLight {
    /// `directional`: the direction the light travels (unit), and its
    /// irradiance on a surface facing it (`intensity × color`).
    Directional { direction: Vec3, irradiance: Vec3 },
    /// `point`: a spot light's position and radiant intensity
    /// (`intensity × color`). plait's spot light has no angular falloff —
    /// a surface at distance d receives I / d² (docs/formats.md, "Light and
    /// units") — and its cone bounds only the light's shadow frustum, so it
    /// is Mitsuba's point light exactly when every occluder lies inside that
    /// frustum ([`spot_as_point`] checks it).
    Point { position: Vec3, intensity: Vec3 },
}

/// A spot light as Mitsuba's `point` emitter, or why not: plait shadows
/// only inside the light's frustum (fitted to the hair, at most the cone),
/// so a strand point or an occluding mesh vertex outside it would cast a
/// shadow in Mitsuba that plait does not have. The ground, below
/// everything, occludes nothing and may reach past the cone.
fn spot_as_point(data: &SceneData, position: Vec3) -> Result<MitsubaLight, ExportError> {
    let scene = &data.scene;
    let frame = data.frame((1, 1), 0);
    let light = Mat4::from_cols_array_2d(&frame.light_view_proj);
    let head = scene.head_model(0.0);
    let inside = |p: Vec3| {
        let c = light * p.extend(1.0);
        c.w > 0.0 && c.x.abs() <= c.w && c.y.abs() <= c.w
    };
    let outside_hair = data.strands.points.iter().filter(|p| !inside(**p)).count();
    let mut outside = Vec::new();
    if outside_hair > 0 {
        outside.push(format!("{outside_hair} strand points"));
    }
    for mesh in &data.meshes {
        if mesh.name == "ground" && scene.ground.is_some() {
            continue;
        }
        let pose = if mesh.head { head } else { Mat4::IDENTITY };
        let n = mesh
            .vertices
            .iter()
            .filter(|v| !inside(pose.transform_point3(v.position.into())))
            .count();
        if n > 0 {
            outside.push(format!("{n} vertices of mesh \"{}\"", mesh.name));
        }
    }
    if !outside.is_empty() {
        return Err(ExportError::Unsupported(format!(
            "a spot light whose shadow frustum leaves out occluders ({}): plait shadows only inside its cone, Mitsuba's point light everywhere; widen `light.cone_degrees` or use a directional light",
            outside.join(", ")
        )));
    }
    Ok(MitsubaLight::Point {
        position,
        intensity: scene.light.radiance(),
    })
}

/// The scene `data` as Mitsuba is to render it at `size` pixels.
pub fn plan(data: &SceneData, size: (u32, u32), fibre: Fibre) -> Result<MitsubaScene, ExportError> {
    let scene = &data.scene;
    let light = match scene.light.kind {
        LightKind::Directional { .. } => MitsubaLight::Directional {
            direction: scene.light.direction_to_light() * -1.0,
            irradiance: scene.light.radiance(),
        },
        LightKind::Spot { position, .. } => spot_as_point(data, Vec3::from(position))?,
    };
    let background = match &scene.background {
        Background::Color(c) => Vec3::from(*c),
        Background::Image(p) => {
            return Err(ExportError::Unsupported(format!(
                "a background image ({}): use `background.color`",
                p.display()
            )));
        }
    };
    let mut notes = Vec::new();
    let head = scene.head_model(0.0);
    if scene.animation.is_some() {
        notes.push("the scene is animated: exported as at time 0 (its first pose)".to_string());
    }
    if scene.environment.declared_at.is_some() {
        notes.push(format!(
            "the environment ({}) lights only plait's `lighting` techniques: not exported; Mitsuba is lit by the light and `ambient`",
            scene.environment.declared_at.as_deref().unwrap_or("")
        ));
    }
    notes.push(format!(
        "hair is shaded by Mitsuba's `hair` BSDF (Chiang et al. 2016: β_m {}, β_n {}, α {}°, η {}); \
         plait's Kajiya-Kay material keys (diffuse, specular, specular_exponent, specular_shift) are not used",
        fibre.longitudinal_roughness, fibre.azimuthal_roughness, fibre.scale_tilt_degrees, fibre.eta
    ));
    notes.push(
        "each hair file ends with one segment of radius 0 at its last strand's tip (no surface): \
         Mitsuba 3.9.1's bsplinecurve reads one segment past the end for a hit at the end of a file's last segment"
            .to_string(),
    );
    let mut hair = hair_groups(data, head, fibre, None, &mut notes)?;
    if hair.len() > MAX_EXACT_GROUPS {
        // Rebuilt with every value rounded; the notes said of the exact
        // grouping hold for the rounded one (they count strands).
        let mut rounded = Quantized::default();
        let mut again = Vec::new();
        hair = hair_groups(data, head, fibre, Some(&mut rounded), &mut again)?;
        notes.extend(again);
        notes.push(rounded.note(hair.len()));
    }
    let c = scene.camera.dollied(scene.camera_distance(0.0));
    Ok(MitsubaScene {
        hair,
        meshes: meshes(data, head),
        camera: MitsubaCamera {
            eye: c.eye.into(),
            target: c.target.into(),
            up: c.up.into(),
            fov_y_degrees: c.fov_y_degrees,
            near: c.near,
            far: c.far,
            size,
        },
        light,
        ambient: Vec3::splat(scene.ambient),
        background,
        fibre,
        notes,
    })
}

/// Strands grouped by (colour, alpha), exactly (the f32 bits) or, with
/// `round`, rounded to multiples of 1 / [`LEVELS`], in the order each group
/// first appears. A strand whose colour or alpha changes along it takes its
/// root's, and a note counts such strands.
fn hair_groups(
    data: &SceneData,
    head: Mat4,
    fibre: Fibre,
    mut round: Option<&mut Quantized>,
    notes: &mut Vec<String>,
) -> Result<Vec<HairGroup>, ExportError> {
    let s = &data.strands;
    let m = &data.scene.material;
    let mut groups: Vec<HairGroup> = Vec::new();
    let mut index = std::collections::HashMap::new();
    let mut varying = 0usize;
    for w in s.offsets.windows(2) {
        let (a, b) = (w[0] as usize, w[1] as usize);
        if a == b {
            continue;
        }
        let (color, alpha) = (s.color[a] * Vec3::from(m.color), s.alpha[a] * m.alpha);
        let (color, alpha) = match round.as_deref_mut() {
            Some(q) => q.take(color, alpha),
            None => (color, alpha),
        };
        if (a..b).any(|i| s.color[i] != s.color[a] || s.alpha[i] != s.alpha[a]) {
            varying += 1;
        }
        let key = (color.to_array().map(f32::to_bits), alpha.to_bits());
        let g = match index.get(&key) {
            Some(&g) => g,
            None => {
                groups.push(HairGroup {
                    color,
                    alpha,
                    sigma_a: sigma_a_from_color(color, fibre.azimuthal_roughness)?,
                    strands: Vec::new(),
                });
                index.insert(key, groups.len() - 1);
                groups.len() - 1
            }
        };
        let points = (a..b)
            .map(|i| (head.transform_point3(s.points[i]), 0.5 * s.thickness[i]))
            .collect();
        groups[g].strands.push(points);
    }
    let dips = groups
        .iter()
        .flat_map(|g| &g.strands)
        .filter(|strand| write::radius_dips_below_zero(strand))
        .count();
    if dips > 0 {
        notes.push(format!(
            "{dips} strand(s) taper so sharply that the B-spline through their radii dips below 0: Mitsuba is given radius 0 there"
        ));
    }
    if varying > 0 {
        notes.push(format!(
            "{varying} strand(s) change colour or alpha along their length: each takes its root's (Mitsuba has one BSDF per shape)"
        ));
    }
    Ok(groups)
}

/// Past this many (colour, alpha) groups, colours and opacities are
/// exported as multiples of 1 / [`LEVELS`]: Mitsuba's LLVM back end
/// compiles one kernel branch per BSDF, and a groom with a per-strand
/// colour or alpha (10,000 strands, 10,000 BSDFs) spent over 5 minutes and
/// 4.7 GB compiling without finishing one seed; rounded, a ±0.1 alpha
/// variation is ~50 BSDFs. Up to this many, the export is exact.
const MAX_EXACT_GROUPS: usize = 64;
const LEVELS: u32 = 256;

/// How many strands [`Quantized::take`] moved, and by how much at most.
#[derive(Default)]
struct Quantized {
    moved: usize,
    largest: f32,
}

impl Quantized {
    /// `color` and `alpha` rounded to multiples of 1 / LEVELS. A value
    /// below 1 / LEVELS is kept: rounded it could become 0 (a colour
    /// channel of 0 has no absorption in Chiang 2016 §4.2, an alpha of 0 no
    /// strand); so is one outside [0, 1], for the checks after to name.
    fn take(&mut self, color: Vec3, alpha: f32) -> (Vec3, f32) {
        let levels = LEVELS as f32;
        let round = |x: f32| {
            if (1.0 / levels..=1.0).contains(&x) {
                (x * levels).round() / levels
            } else {
                x
            }
        };
        let (c, a) = (color.to_array().map(round), round(alpha));
        let delta = (Vec3::from(c) - color)
            .abs()
            .max_element()
            .max((a - alpha).abs());
        if delta > 0.0 {
            self.moved += 1;
            self.largest = self.largest.max(delta);
        }
        (Vec3::from(c), a)
    }

    /// What the rounding did, for the export's notes.
    fn note(&self, groups: usize) -> String {
        format!(
            "{} strand(s) had their colour or alpha rounded to a multiple of 1/{LEVELS} (by at most {:.4}), {groups} groups after rounding: past {MAX_EXACT_GROUPS} distinct values Mitsuba would compile one BSDF each",
            self.moved, self.largest
        )
    }
}

/// The opaque meshes, the head's posed at time 0.
fn meshes(data: &SceneData, head: Mat4) -> Vec<MitsubaMesh> {
    data.meshes
        .iter()
        .map(|mesh| {
            let pose = if mesh.head { head } else { Mat4::IDENTITY };
            MitsubaMesh {
                name: mesh.name.clone(),
                positions: mesh
                    .vertices
                    .iter()
                    .map(|v| pose.transform_point3(v.position.into()))
                    .collect(),
                normals: mesh
                    .vertices
                    .iter()
                    .map(|v| pose.transform_vector3(v.normal.into()).normalize_or_zero())
                    .collect(),
                indices: mesh.indices.clone(),
                albedo: mesh.albedo.into(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
