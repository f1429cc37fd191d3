//! Keyframed motion of the head (the scene's `[animation]` table).
//!
//! ```toml
//! [animation]
//! pivot = [0.0, -0.9, 0.0]     # optional; default: the head's centre
//! interpolation = "smooth"     # "linear" (default) or "smooth" (ease in and out)
//!
//! [[animation.keys]]
//! time = 0.0                   # seconds, strictly increasing
//! rotate_degrees = [0, 0, 0]   # about X, then Y, then Z, as [hair.transform]
//! translate = [0, 0, 0]        # applied after the rotation
//! camera_distance = 1.0        # the camera's distance to its target, × (a dolly)
//!
//! [[animation.keys]]
//! time = 1.0
//! rotate_degrees = [0, 40, 0]
//! camera_distance = 2.0
//! ```
//!
//! The pose at time t is the head's world-from-rest matrix
//! `T(pivot + translate) · R · T(-pivot)`, interpolated between the keys
//! around t (rotations by slerp); before the first key the first pose holds,
//! after the last the last. `camera_distance` (1 when a key leaves it out)
//! moves the scene's camera along its view ray, that many times as far from
//! its target ([`crate::camera::Camera::dollied`]), interpolated like the
//! translation. Every bad value is reported at its line and
//! column: unsorted times, NaN or infinite numbers, wrong arity.

use glam::{Mat4, Quat, Vec3};
use serde::Deserialize;
use toml::Spanned;

/// How the pose moves between two keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Interpolation {
    /// Constant speed from key to key.
    #[default]
    Linear,
    /// Eased in and out at every key (smoothstep of the segment's time), so
    /// the head starts and stops without a jolt.
    Smooth,
}

/// One pose of the head at a time.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Key {
    /// Seconds from the start of the animation.
    pub time: Spanned<f32>,
    /// Rotation about X, then Y, then Z, in degrees, about the pivot.
    #[serde(default)]
    pub rotate_degrees: Option<Spanned<[f32; 3]>>,
    /// Translation, applied after the rotation.
    #[serde(default)]
    pub translate: Option<Spanned<[f32; 3]>>,
    /// The camera's distance to its target, as a factor of the scene's
    /// (1 = as the scene places it, 2 = twice as far): a dolly.
    #[serde(default)]
    pub camera_distance: Option<Spanned<f32>>,
}

/// The scene's `[animation]`: keyframes of the head (and of every opaque
/// object named `head`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Animation {
    /// The point the head turns about; the head's centre when not given.
    #[serde(default)]
    pub pivot: Option<Spanned<[f32; 3]>>,
    /// Between keys: linear or eased.
    #[serde(default)]
    pub interpolation: Interpolation,
    /// At least one key, times strictly increasing.
    pub keys: Spanned<Vec<Key>>,
}

/// A bad value of the animation, at a byte range of the scene text.
#[derive(Debug, Clone, PartialEq)]
pub struct AnimationError {
    pub span: std::ops::Range<usize>,
    pub message: String,
}

impl Animation {
    /// Checks what serde cannot: finite numbers, at least one key, times
    /// strictly increasing. The error points at the offending value.
    pub fn validate(&self) -> Result<(), AnimationError> {
        let error =
            |span: std::ops::Range<usize>, message: String| AnimationError { span, message };
        if self.keys.get_ref().is_empty() {
            return Err(error(
                self.keys.span(),
                "animation.keys is empty: give at least one key".into(),
            ));
        }
        if let Some(pivot) = &self.pivot
            && !pivot.get_ref().iter().all(|x| x.is_finite())
        {
            return Err(error(pivot.span(), "animation.pivot must be finite".into()));
        }
        let mut previous: Option<&Spanned<f32>> = None;
        for (i, key) in self.keys.get_ref().iter().enumerate() {
            let what = |field: &str| format!("animation.keys[{i}].{field}");
            if !key.time.get_ref().is_finite() {
                return Err(error(
                    key.time.span(),
                    format!("{} must be finite", what("time")),
                ));
            }
            for (field, value) in [
                ("rotate_degrees", &key.rotate_degrees),
                ("translate", &key.translate),
            ] {
                if let Some(value) = value
                    && !value.get_ref().iter().all(|x| x.is_finite())
                {
                    return Err(error(
                        value.span(),
                        format!("{} must be finite", what(field)),
                    ));
                }
            }
            if let Some(d) = &key.camera_distance
                && let Err(why) = crate::camera::check_camera_distance(*d.get_ref() as f64)
            {
                return Err(error(
                    d.span(),
                    format!("{}: {why}", what("camera_distance")),
                ));
            }
            if let Some(before) = previous
                && *key.time.get_ref() <= *before.get_ref()
            {
                return Err(error(
                    key.time.span(),
                    format!(
                        "{} is {}, not after the key before it ({}): key times must increase",
                        what("time"),
                        key.time.get_ref(),
                        before.get_ref()
                    ),
                ));
            }
            previous = Some(&key.time);
        }
        Ok(())
    }

    /// The head's world-from-rest matrix at `time` seconds; `head_center` is
    /// the pivot when the file gives none.
    pub fn head_model(&self, time: f32, head_center: Vec3) -> Mat4 {
        let pivot = self
            .pivot
            .as_ref()
            .map_or(head_center, |p| Vec3::from(*p.get_ref()));
        let (rotation, translation) = self.pose(time);
        Mat4::from_translation(pivot + translation)
            * Mat4::from_quat(rotation)
            * Mat4::from_translation(-pivot)
    }

    /// The camera's distance factor at `time` (a dolly; 1 = the scene's
    /// camera), between the keys around it.
    pub fn camera_distance(&self, time: f32) -> f32 {
        let at = |k: &Key| k.camera_distance.as_ref().map_or(1.0, |d| *d.get_ref());
        match self.segment(time) {
            Segment::Held(k) => at(k),
            Segment::Between(a, b, s) => at(a) + (at(b) - at(a)) * s,
            Segment::None => 1.0,
        }
    }

    /// Rotation and translation at `time`, between the keys around it.
    fn pose(&self, time: f32) -> (Quat, Vec3) {
        let at = |k: &Key| {
            (
                rotation(k),
                Vec3::from(k.translate.as_ref().map_or([0.0; 3], |t| *t.get_ref())),
            )
        };
        match self.segment(time) {
            Segment::Held(k) => at(k),
            Segment::Between(a, b, s) => {
                let (ra, ta) = at(a);
                let (rb, tb) = at(b);
                (ra.slerp(rb, s).normalize(), ta.lerp(tb, s))
            }
            Segment::None => (Quat::IDENTITY, Vec3::ZERO),
        }
    }

    /// The keys around `time` and how far between them (eased when the
    /// interpolation is smooth); before the first key the first holds,
    /// after the last the last.
    fn segment(&self, time: f32) -> Segment<'_> {
        let keys = self.keys.get_ref();
        let (Some(first), Some(last)) = (keys.first(), keys.last()) else {
            return Segment::None;
        };
        if time <= *first.time.get_ref() {
            return Segment::Held(first);
        }
        if time >= *last.time.get_ref() {
            return Segment::Held(last);
        }
        // The first key after `time`; the one before it starts the segment.
        let next = keys.partition_point(|k| *k.time.get_ref() <= time);
        let (a, b) = (&keys[next - 1], &keys[next]);
        let (ta, tb) = (*a.time.get_ref(), *b.time.get_ref());
        let mut s = ((time - ta) / (tb - ta)).clamp(0.0, 1.0);
        if self.interpolation == Interpolation::Smooth {
            s = s * s * (3.0 - 2.0 * s);
        }
        Segment::Between(a, b, s)
    }

    /// Time of the last key: how long the animation runs.
    pub fn duration(&self) -> f32 {
        self.keys
            .get_ref()
            .last()
            .map_or(0.0, |k| *k.time.get_ref())
    }
}

/// Where a time falls among the keys.
enum Segment<'k> {
    /// No keys (refused by `validate`).
    None,
    /// Before the first key or after the last: that key's values.
    Held(&'k Key),
    /// Between two keys, this fraction of the way (0..1).
    Between(&'k Key, &'k Key, f32),
}

/// `[x, y, z]` degrees about X, then Y, then Z (as `[hair.transform]`).
fn rotation(key: &Key) -> Quat {
    let degrees = key
        .rotate_degrees
        .as_ref()
        .map_or([0.0; 3], |r| *r.get_ref());
    let [x, y, z] = degrees.map(f32::to_radians);
    Quat::from_rotation_z(z) * Quat::from_rotation_y(y) * Quat::from_rotation_x(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Animation {
        #[derive(Deserialize)]
        struct Wrapper {
            animation: Animation,
        }
        toml::from_str::<Wrapper>(text).expect("parses").animation
    }

    const TURN: &str = "[animation]\npivot = [0, 0, 0]\n[[animation.keys]]\ntime = 0.0\n[[animation.keys]]\ntime = 1.0\nrotate_degrees = [0, 90, 0]\ntranslate = [0, 1, 0]\n";

    #[test]
    fn poses_are_interpolated_between_keys_and_held_outside() {
        let a = parse(TURN);
        a.validate().expect("valid");
        let at = |t: f32| a.head_model(t, Vec3::ZERO).transform_point3(Vec3::X);
        assert!((at(-1.0) - Vec3::X).length() < 1e-6);
        assert!((at(0.0) - Vec3::X).length() < 1e-6);
        // +X turned 90° about +Y is -Z, then lifted by 1.
        assert!(
            (at(1.0) - Vec3::new(0.0, 1.0, -1.0)).length() < 1e-5,
            "{}",
            at(1.0)
        );
        assert!((at(5.0) - at(1.0)).length() < 1e-6);
        // Halfway: 45° and half the lift, on the unit circle.
        let half = at(0.5);
        let s = std::f32::consts::FRAC_1_SQRT_2;
        assert!((half - Vec3::new(s, 0.5, -s)).length() < 1e-5, "{half}");
        assert_eq!(a.duration(), 1.0);
    }

    #[test]
    fn smooth_interpolation_eases_but_meets_the_keys() {
        let a = parse(&TURN.replace("pivot", "interpolation = \"smooth\"\npivot"));
        let linear = parse(TURN);
        let x = |a: &Animation, t: f32| a.head_model(t, Vec3::ZERO).transform_point3(Vec3::X);
        assert!(
            (x(&a, 0.5) - x(&linear, 0.5)).length() < 1e-5,
            "symmetric at the middle"
        );
        // Slower than linear near the keys.
        assert!(x(&a, 0.1).y < x(&linear, 0.1).y);
        assert!((x(&a, 1.0) - x(&linear, 1.0)).length() < 1e-6);
    }

    #[test]
    fn the_pivot_defaults_to_the_head_centre() {
        let a = parse(&TURN.replace("pivot = [0, 0, 0]\n", ""));
        let center = Vec3::new(0.0, 2.0, 0.0);
        let m = a.head_model(1.0, center);
        // The pivot itself only moves by the translation.
        assert!((m.transform_point3(center) - (center + Vec3::Y)).length() < 1e-5);
    }

    #[test]
    fn unsorted_and_non_finite_values_point_at_the_value() {
        let text = TURN.replace("time = 1.0", "time = 0.0");
        let e = parse(&text).validate().unwrap_err();
        assert_eq!(&text[e.span.clone()], "0.0");
        assert!(
            e.span.start > text.find("time = 0.0\nrot").unwrap(),
            "the second key"
        );
        assert!(
            e.message.contains("key times must increase"),
            "{}",
            e.message
        );
        let text = TURN.replace("translate = [0, 1, 0]", "translate = [0, nan, 0]");
        let e = parse(&text).validate().unwrap_err();
        assert_eq!(&text[e.span.clone()], "[0, nan, 0]");
        assert!(
            e.message
                .contains("animation.keys[1].translate must be finite")
        );
        let text = TURN.replace("time = 1.0", "time = inf");
        let e = parse(&text).validate().unwrap_err();
        assert_eq!(&text[e.span], "inf");
    }

    const DOLLY: &str = "[animation]\n[[animation.keys]]\ntime = 0.0\n[[animation.keys]]\ntime = 1.0\ncamera_distance = 5.0\n[[animation.keys]]\ntime = 2.0\n";

    /// The dolly is interpolated like the other fields, 1 where a key
    /// leaves it out, held outside the keys.
    #[test]
    fn the_camera_distance_is_interpolated_between_keys() {
        let a = parse(DOLLY);
        a.validate().expect("valid");
        for (t, d) in [
            (-1.0, 1.0),
            (0.0, 1.0),
            (0.25, 2.0),
            (0.5, 3.0),
            (1.0, 5.0),
            (1.5, 3.0),
            (2.0, 1.0),
            (9.0, 1.0),
        ] {
            assert!(
                (a.camera_distance(t) - d).abs() < 1e-5,
                "t = {t}: {} not {d}",
                a.camera_distance(t)
            );
        }
        let smooth =
            parse(&DOLLY.replace("[animation]\n", "[animation]\ninterpolation = \"smooth\"\n"));
        assert!(smooth.camera_distance(0.25) < a.camera_distance(0.25));
        assert!((smooth.camera_distance(0.5) - 3.0).abs() < 1e-5);
        // No key moves the camera: it stays where the scene puts it.
        assert_eq!(parse(TURN).camera_distance(0.5), 1.0);
    }

    #[test]
    fn a_bad_camera_distance_points_at_the_value() {
        for bad in ["0.0", "-2.0", "nan", "inf", "1000.0"] {
            let text = DOLLY.replace("camera_distance = 5.0", &format!("camera_distance = {bad}"));
            let e = parse(&text).validate().unwrap_err();
            assert_eq!(&text[e.span.clone()], bad);
            assert!(
                e.message.starts_with("animation.keys[1].camera_distance: "),
                "{}",
                e.message
            );
        }
    }
}
