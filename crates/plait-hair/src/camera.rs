//! The camera: a look-at perspective camera given in the scene, or one
//! fitted to the groom's bounds (`camera = "fit"`), so an asset of any size,
//! units and position renders framed without hand-tuning.

use glam::{Mat4, Vec3};
use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

use crate::strands::Aabb;

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
    /// A camera at +Z looking at the origin: the stand-in a fitted camera
    /// has until the hair is loaded.
    pub fn looking_down_z() -> Camera {
        Camera {
            eye: [0.0, 0.0, 5.0],
            target: [0.0, 0.0, 0.0],
            up: default_up(),
            fov_y_degrees: 35.0,
            near: default_near(),
            far: default_far(),
        }
    }

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

    /// The camera moved along its view ray, `factor` times as far from its
    /// target (`eye = target + factor · (eye − target)`), looking the same
    /// way with the same field of view: the same scene, smaller on screen
    /// (`plait ab --camera-distance`, the `camera_distance` animation key).
    ///
    /// The depth range moves with the eye: everything the camera saw is
    /// `(factor − 1) · |eye − target|` deeper after a dolly out, so `far`
    /// grows by that much (nothing falls behind it), and `near` scales with
    /// the factor (nearest geometry is at least that far: `near` < the
    /// target's distance), keeping depth precision where the hair now is.
    /// A dolly in keeps `far` and scales `near` down, so no geometry that
    /// came nearer is clipped that was not in front of the old eye.
    pub fn dollied(&self, factor: f32) -> Camera {
        if factor == 1.0 {
            return self.clone();
        }
        let target = Vec3::from(self.target);
        let offset = Vec3::from(self.eye) - target;
        let moved_back = (factor - 1.0).max(0.0) * offset.length();
        Camera {
            eye: (target + factor * offset).to_array(),
            near: self.near * factor,
            far: self.far + moved_back,
            ..self.clone()
        }
    }
}

/// The largest `camera_distance` factor (`--camera-distance`, the animation
/// key): at 100× any framed groom covers a few pixels, and past it the
/// depth range of a fitted camera loses the precision a depth test needs.
pub const MAX_CAMERA_DISTANCE: f32 = 100.0;

/// Why a camera distance factor is refused (the caller names the flag or
/// field): it must be finite, > 0 and at most [`MAX_CAMERA_DISTANCE`].
pub fn check_camera_distance(factor: f64) -> Result<(), String> {
    if !factor.is_finite() {
        return Err(format!("{factor} is not a finite number"));
    }
    if factor <= 0.0 {
        return Err(format!(
            "{factor} must be > 0 (1 = the scene's camera, 2 = twice as far from its target)"
        ));
    }
    if factor > MAX_CAMERA_DISTANCE as f64 {
        return Err(format!(
            "{factor} is more than {MAX_CAMERA_DISTANCE} (the hair would cover a few pixels)"
        ));
    }
    Ok(())
}

/// How to fit a camera to the hair: from which direction, with which field
/// of view. In TOML, `camera = "fit"` or a `[camera]` table with
/// `fit = true` (or without `eye` and `target`) and any of these fields.
#[derive(Debug, Clone, PartialEq)]
pub struct CameraFit {
    /// Direction from the hair's centre toward the eye.
    pub direction: [f32; 3],
    /// Up direction.
    pub up: [f32; 3],
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f32,
    /// Room around the hair: 1 touches its bounds, 1.1 leaves 10 %.
    pub margin: f32,
}

impl Default for CameraFit {
    /// From the front, a little to the right and above — the view of the
    /// built-in scene.
    fn default() -> Self {
        CameraFit {
            direction: [0.25, 0.14, 1.0],
            up: default_up(),
            fov_y_degrees: 35.0,
            margin: 1.08,
        }
    }
}

impl CameraFit {
    /// Checks the numbers; the message names the field.
    pub fn validate(&self) -> Result<(), String> {
        let d = Vec3::from(self.direction);
        if !d.is_finite() || d.length_squared() == 0.0 {
            return Err("camera.direction must be a finite non-zero vector".into());
        }
        let up = Vec3::from(self.up);
        if !up.is_finite() || up.cross(d).length_squared() <= 1e-12 * up.length_squared() {
            return Err("camera.up must be finite and not parallel to camera.direction".into());
        }
        if !(self.fov_y_degrees > 0.0 && self.fov_y_degrees < 180.0) {
            return Err(format!(
                "camera.fov_y_degrees must be in (0, 180), got {}",
                self.fov_y_degrees
            ));
        }
        if !(self.margin.is_finite() && self.margin >= 1.0) {
            return Err(format!("camera.margin must be ≥ 1, got {}", self.margin));
        }
        Ok(())
    }

    /// The camera that sees all of `subject` (the hair, and the head if
    /// any), with near and far planes that also hold `scene` (everything,
    /// the ground included). The horizontal field of view is assumed at
    /// least the vertical one (landscape images).
    pub fn camera(&self, subject: Aabb, scene: Aabb) -> Camera {
        let subject = if subject.is_empty() {
            Aabb::new(Vec3::splat(-1.0), Vec3::ONE)
        } else {
            subject
        };
        let scene = if scene.is_empty() {
            subject
        } else {
            scene.union(&subject)
        };
        let forward = -Vec3::from(self.direction).normalize();
        let right = forward.cross(Vec3::from(self.up)).normalize();
        let up = right.cross(forward);
        let center = subject.center();
        let tan_half = (self.fov_y_degrees.to_radians() * 0.5).tan();
        // Each corner q (relative to the centre) is inside the view cone
        // when the eye is at least this far back along -forward.
        let distance = subject
            .corners()
            .iter()
            .map(|&c| {
                let q = c - center;
                let across = q.dot(up).abs().max(q.dot(right).abs());
                across * self.margin / tan_half - q.dot(forward)
            })
            .fold(0.0f32, f32::max)
            .max(subject.extent().length() * 1e-3)
            .max(1e-6);
        let eye = center - forward * distance;
        let depths = scene.corners().map(|c| (c - eye).dot(forward));
        let nearest = subject
            .corners()
            .iter()
            .map(|&c| (c - eye).dot(forward))
            .fold(f32::INFINITY, f32::min);
        let farthest = depths.iter().copied().fold(0.0f32, f32::max);
        let near = (nearest * 0.5).max(distance * 1e-3);
        Camera {
            eye: eye.to_array(),
            target: center.to_array(),
            up: up.to_array(),
            fov_y_degrees: self.fov_y_degrees,
            near,
            far: (farthest * 1.5).max(near * 2.0),
        }
    }
}

/// `camera` in a scene file: a fixed camera or a fit. A scene without
/// `camera`, and a `[camera]` table with neither `eye` nor `target` (nor
/// `fit = false`), is fitted: the only camera that frames any hair.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum CameraSetting {
    Fixed(Camera),
    Fit(CameraFit),
}

impl Default for CameraSetting {
    fn default() -> Self {
        CameraSetting::Fit(CameraFit::default())
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraTable {
    /// Left out: fitted unless the table gives `eye` or `target`.
    fit: Option<bool>,
    eye: Option<[f32; 3]>,
    target: Option<[f32; 3]>,
    up: Option<[f32; 3]>,
    fov_y_degrees: Option<f32>,
    near: Option<f32>,
    far: Option<f32>,
    direction: Option<[f32; 3]>,
    margin: Option<f32>,
}

impl TryFrom<CameraTable> for CameraSetting {
    type Error = String;
    fn try_from(t: CameraTable) -> Result<Self, String> {
        if t.fit.unwrap_or(t.eye.is_none() && t.target.is_none()) {
            let computed = [
                ("eye", t.eye.is_some()),
                ("target", t.target.is_some()),
                ("near", t.near.is_some()),
                ("far", t.far.is_some()),
            ];
            if let Some((name, _)) = computed.iter().find(|(_, given)| *given) {
                return Err(format!(
                    "camera.{name} is computed when the camera is fitted (fit = true, or no eye and target): give direction, up, fov_y_degrees or margin instead"
                ));
            }
            let d = CameraFit::default();
            return Ok(CameraSetting::Fit(CameraFit {
                direction: t.direction.unwrap_or(d.direction),
                up: t.up.unwrap_or(d.up),
                fov_y_degrees: t.fov_y_degrees.unwrap_or(d.fov_y_degrees),
                margin: t.margin.unwrap_or(d.margin),
            }));
        }
        if t.direction.is_some() || t.margin.is_some() {
            return Err("camera.direction and camera.margin need fit = true".into());
        }
        let need = |v: Option<[f32; 3]>, name: &str| {
            v.ok_or_else(|| format!("camera.{name} is missing (or use camera = \"fit\")"))
        };
        Ok(CameraSetting::Fixed(Camera {
            eye: need(t.eye, "eye")?,
            target: need(t.target, "target")?,
            up: t.up.unwrap_or_else(default_up),
            fov_y_degrees: t
                .fov_y_degrees
                .ok_or("camera.fov_y_degrees is missing (or use camera = \"fit\")")?,
            near: t.near.unwrap_or_else(default_near),
            far: t.far.unwrap_or_else(default_far),
        }))
    }
}

impl<'de> Deserialize<'de> for CameraSetting {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = CameraSetting;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("\"fit\" or a camera table")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<CameraSetting, E> {
                match s {
                    "fit" => Ok(CameraSetting::Fit(CameraFit::default())),
                    other => Err(E::custom(format!(
                        "camera = {other:?}: expected \"fit\" or a [camera] table"
                    ))),
                }
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<CameraSetting, A::Error> {
                let table = CameraTable::deserialize(de::value::MapAccessDeserializer::new(map))?;
                CameraSetting::try_from(table).map_err(de::Error::custom)
            }
        }
        d.deserialize_any(V)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The eye moves along its view ray, `d` times as far from the target;
    /// the view direction, fov and up stay; the depth range holds what it held.
    #[test]
    fn a_dollied_camera_is_d_times_farther_from_its_target() {
        let c = Camera {
            eye: [1.0, 2.0, 5.0],
            target: [0.0, 1.0, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_y_degrees: 30.0,
            near: 0.5,
            far: 20.0,
        };
        let distance = |c: &Camera| (Vec3::from(c.eye) - Vec3::from(c.target)).length();
        let direction = |c: &Camera| (Vec3::from(c.target) - Vec3::from(c.eye)).normalize();
        for d in [0.5f32, 1.0, 2.0, 8.0] {
            let far = c.dollied(d);
            assert!(
                (distance(&far) - d * distance(&c)).abs() < 1e-4 * d,
                "d = {d}: {} vs {}",
                distance(&far),
                d * distance(&c)
            );
            assert!((direction(&far) - direction(&c)).length() < 1e-5);
            assert_eq!(far.target, c.target);
            assert_eq!(far.fov_y_degrees, c.fov_y_degrees);
            assert!((far.near - c.near * d).abs() < 1e-6);
            // Every point the camera saw before is still before `far`.
            assert!(far.far - distance(&far) >= c.far - distance(&c) - 1e-4);
        }
        assert_eq!(c.dollied(1.0), c);
    }

    #[test]
    fn camera_distances_are_finite_positive_and_bounded() {
        assert!(check_camera_distance(1.0).is_ok());
        assert!(check_camera_distance(MAX_CAMERA_DISTANCE as f64).is_ok());
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 101.0] {
            assert!(check_camera_distance(bad).is_err(), "{bad}");
        }
    }
}
