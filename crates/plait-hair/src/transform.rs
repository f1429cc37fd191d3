//! Placing a groom in the scene: scale, rotation, translation (the scene's
//! `[hair.transform]`). Assets come in their tool's units and axes — the
//! TressFX samples are in centimetres (the ponytail) or metres (the mohawk),
//! Y up — so a scene scales and turns them into its own.

use glam::{Mat4, Quat, Vec3};
use serde::Deserialize;

use crate::strands::Strands;

/// A uniform scale or one per axis.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(untagged, expecting = "a number or an array [x, y, z]")]
pub enum Scale {
    /// The same factor on every axis.
    Uniform(f32),
    /// One factor per axis.
    PerAxis([f32; 3]),
}

impl Scale {
    /// The factors per axis.
    pub fn vector(self) -> Vec3 {
        match self {
            Scale::Uniform(s) => Vec3::splat(s),
            Scale::PerAxis(v) => Vec3::from(v),
        }
    }
}

impl Default for Scale {
    fn default() -> Self {
        Scale::Uniform(1.0)
    }
}

/// Scale, then rotate about X, then Y, then Z (degrees, right-handed), then
/// translate.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Transform {
    /// Scale factor(s).
    pub scale: Scale,
    /// Rotation about X, Y and Z in degrees, applied in that order.
    pub rotate_degrees: [f32; 3],
    /// Translation, applied last.
    pub translate: [f32; 3],
}

impl Transform {
    /// The matrix `T · Rz · Ry · Rx · S`.
    pub fn matrix(&self) -> Mat4 {
        let [x, y, z] = self.rotate_degrees.map(f32::to_radians);
        let rotation =
            Quat::from_rotation_z(z) * Quat::from_rotation_y(y) * Quat::from_rotation_x(x);
        Mat4::from_scale_rotation_translation(
            self.scale.vector(),
            rotation,
            Vec3::from(self.translate),
        )
    }

    /// Finite numbers and an invertible matrix; the message names the field.
    pub fn validate(&self) -> Result<(), String> {
        self.validate_named("hair.transform")
    }

    /// [`Transform::validate`] for the transform at `field` (e.g.
    /// `meshes[0].transform`).
    pub fn validate_named(&self, field: &str) -> Result<(), String> {
        let finite = |v: &[f32]| v.iter().all(|c| c.is_finite());
        if !finite(&self.scale.vector().to_array()) {
            return Err(format!(
                "{field}.scale must be finite, got {:?}",
                self.scale.vector().to_array()
            ));
        }
        if !finite(&self.rotate_degrees) {
            return Err(format!("{field}.rotate_degrees must be finite"));
        }
        if !finite(&self.translate) {
            return Err(format!("{field}.translate must be finite"));
        }
        // The rotation has determinant 1, so the scale decides; a
        // determinant that underflows to 0 or a subnormal is as singular as 0
        // for an f32 inverse.
        let m = self.matrix();
        let det = m.determinant();
        if !det.is_normal() || !m.inverse().is_finite() {
            return Err(format!(
                "{field} is not invertible: scale {:?} has determinant {det}",
                self.scale.vector().to_array()
            ));
        }
        Ok(())
    }

    /// Moves every point; thickness scales with the cube root of the volume
    /// change. Fails (naming the strand) if a point leaves the f32 range.
    pub fn apply(&self, strands: &mut Strands) -> Result<(), String> {
        let m = self.matrix();
        let thickness_scale = m.determinant().abs().cbrt();
        for p in &mut strands.points {
            *p = m.transform_point3(*p);
        }
        for t in &mut strands.thickness {
            *t *= thickness_scale;
        }
        if let Some(i) = strands.points.iter().position(|p| !p.is_finite()) {
            let strand = strands.offsets.partition_point(|&o| o as usize <= i) - 1;
            return Err(format!(
                "hair.transform moves strand {strand} out of the f32 range"
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_then_rotate_then_translate() {
        let t = Transform {
            scale: Scale::Uniform(2.0),
            rotate_degrees: [0.0, 90.0, 0.0],
            translate: [0.0, 1.0, 0.0],
        };
        t.validate().expect("valid");
        // +X scaled to 2, turned about +Y to -Z, lifted by 1
        let p = t.matrix().transform_point3(Vec3::X);
        assert!((p - Vec3::new(0.0, 1.0, -2.0)).length() < 1e-5, "{p}");
        // X first, then Y: +Y about X by 90 → +Z, about Y by 90 → +X
        let t = Transform {
            rotate_degrees: [90.0, 90.0, 0.0],
            ..Transform::default()
        };
        let p = t.matrix().transform_point3(Vec3::Y);
        assert!((p - Vec3::X).length() < 1e-5, "{p}");
    }

    #[test]
    fn singular_and_non_finite_transforms_are_named() {
        for scale in [
            Scale::Uniform(0.0),
            Scale::PerAxis([1.0, 0.0, 1.0]),
            Scale::Uniform(1e-20),
        ] {
            let t = Transform {
                scale,
                ..Transform::default()
            };
            let e = t.validate().unwrap_err();
            assert!(e.contains("not invertible"), "{e}");
        }
        let t = Transform {
            translate: [f32::NAN, 0.0, 0.0],
            ..Transform::default()
        };
        assert!(
            t.validate()
                .unwrap_err()
                .contains("hair.transform.translate")
        );
        let t = Transform {
            scale: Scale::Uniform(f32::INFINITY),
            ..Transform::default()
        };
        assert!(t.validate().unwrap_err().contains("hair.transform.scale"));
    }

    #[test]
    fn apply_moves_points_scales_thickness_and_catches_overflow() {
        let mut s = Strands::new();
        s.push_strand(&[Vec3::ZERO, Vec3::Y], |_| 0.5, |_| 1.0, Vec3::ONE);
        s.push_strand(&[Vec3::X, Vec3::splat(1e30)], |_| 0.5, |_| 1.0, Vec3::ONE);
        let mut a = s.clone();
        let t = Transform {
            scale: Scale::Uniform(3.0),
            ..Transform::default()
        };
        t.apply(&mut a).expect("finite");
        assert_eq!(a.points[1], Vec3::new(0.0, 3.0, 0.0));
        assert!((a.thickness[0] - 1.5).abs() < 1e-5);
        let big = Transform {
            scale: Scale::Uniform(1e10),
            ..Transform::default()
        };
        let e = big.apply(&mut s).unwrap_err();
        assert!(e.contains("strand 1"), "{e}");
    }
}
