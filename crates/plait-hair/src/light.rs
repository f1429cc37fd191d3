//! The one light of a scene, and its frustum fitted to the hair.
//!
//! [`Light::view_proj`] fits the light's frustum tightly to the hair
//! (Halén & Wester 2007 §5.7: near/far fitted to the model, the
//! field of view fitted to its extremes), with the depth range running from
//! the nearest occluder to the farthest receiver so hair shadows reach the
//! ground.

use glam::{Mat4, Vec3};
use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

use crate::camera::Camera;
use crate::strands::Aabb;

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
/// `type = "spot"` with `position`, `direction`, `cone_degrees`, or
/// `type = "fit"` (see [`Light::fitted`]); plus `color` and `intensity`.
/// `light = "fit"` is short for `type = "fit"`.
#[derive(Debug, Clone, PartialEq)]
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
    /// Left out: `"fit"`, so `[light]` with only `color`/`intensity` works.
    #[serde(rename = "type", default = "fit")]
    kind: String,
    direction: Option<[f32; 3]>,
    position: Option<[f32; 3]>,
    cone_degrees: Option<f32>,
    #[serde(default = "white")]
    color: [f32; 3],
    /// Left out: [`Light::FITTED_INTENSITY`] for a fitted light, 1 otherwise.
    intensity: Option<f32>,
}

fn white() -> [f32; 3] {
    [1.0, 1.0, 1.0]
}
fn fit() -> String {
    "fit".into()
}

/// `light` in a scene file: a given light, or one placed from the camera.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LightSetting {
    pub light: Light,
    pub fit: bool,
}

impl LightSetting {
    /// `light = "fit"`, also what a scene without `light` gets.
    pub(crate) fn fitted() -> LightSetting {
        LightSetting {
            light: Light::fitted(&Camera::looking_down_z(), Light::FITTED_INTENSITY),
            fit: true,
        }
    }
}

impl TryFrom<LightToml> for LightSetting {
    type Error = String;
    fn try_from(t: LightToml) -> Result<LightSetting, String> {
        if t.kind == "fit" {
            if t.direction.is_some() || t.position.is_some() || t.cone_degrees.is_some() {
                return Err(
                    "a light of type \"fit\" is placed from the camera: give only color and intensity"
                        .into(),
                );
            }
            return Ok(LightSetting {
                light: Light {
                    color: t.color,
                    ..Light::fitted(
                        &Camera::looking_down_z(),
                        t.intensity.unwrap_or(Light::FITTED_INTENSITY),
                    )
                },
                fit: true,
            });
        }
        let direction = t.direction.ok_or("light.direction is missing")?;
        if Vec3::from(direction).length_squared() == 0.0 || !Vec3::from(direction).is_finite() {
            return Err("light.direction must be a finite non-zero vector".into());
        }
        let t = LightToml {
            direction: Some(direction),
            ..t
        };
        let kind = match t.kind.as_str() {
            "directional" => {
                if t.position.is_some() || t.cone_degrees.is_some() {
                    return Err("a directional light has no position or cone_degrees".into());
                }
                LightKind::Directional { direction }
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
                    direction,
                    cone_degrees,
                }
            }
            other => {
                return Err(format!(
                    "unknown light type {other:?} (expected \"directional\", \"spot\" or \"fit\")"
                ));
            }
        };
        Ok(LightSetting {
            light: Light {
                kind,
                color: t.color,
                intensity: t.intensity.unwrap_or(1.0),
            },
            fit: false,
        })
    }
}

impl<'de> Deserialize<'de> for LightSetting {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = LightSetting;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("\"fit\" or a light table")
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<LightSetting, E> {
                match s {
                    "fit" => Ok(LightSetting::fitted()),
                    other => Err(E::custom(format!(
                        "light = {other:?}: expected \"fit\" or a [light] table"
                    ))),
                }
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<LightSetting, A::Error> {
                let table = LightToml::deserialize(de::value::MapAccessDeserializer::new(map))?;
                LightSetting::try_from(table).map_err(de::Error::custom)
            }
        }
        d.deserialize_any(V)
    }
}

impl Light {
    /// The intensity of a fitted light unless the scene gives one: the
    /// built-in scene's key light (3). Under it the default hair look
    /// (`GroomSpec::default()`, which a `.tfx` groom without colours gets
    /// too) stays below full scale but for the highlights: a file groom's
    /// hair pixels average 0.5–0.7 of full scale (docs/formats.md has the
    /// figures). Both `light = "fit"` and `[light] type = "fit"` use it.
    pub const FITTED_INTENSITY: f32 = 3.0;

    /// A white directional key light placed from `camera`'s view: from
    /// above, a little right of and in front of the hair, as in the built-in
    /// scene. Its shadow maps are fitted to the hair like any light's.
    pub fn fitted(camera: &Camera, intensity: f32) -> Light {
        let back = (Vec3::from(camera.eye) - Vec3::from(camera.target)).normalize_or(Vec3::Z);
        let right = Vec3::from(camera.up).cross(back).normalize_or(Vec3::X);
        let up = back.cross(right);
        let to_light = (right * 0.5 + up * 1.0 + back * 0.6).normalize();
        Light {
            kind: LightKind::Directional {
                direction: (-to_light).to_array(),
            },
            color: white(),
            intensity,
        }
    }

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

#[cfg(test)]
mod tests {
    use super::*;

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
    fn fitted_light_comes_from_above_the_camera_side() {
        let camera = Camera::looking_down_z();
        let light = Light::fitted(&camera, 2.0);
        let to_light = light.direction_to_light();
        assert!(
            to_light.y > 0.6 && to_light.z > 0.3 && to_light.x > 0.2,
            "{to_light}"
        );
        assert_eq!(light.radiance(), Vec3::splat(2.0));
    }
}
