//! Orbit, zoom and pan of the scene camera, and the light's direction as two
//! angles.

use glam::Vec3;
use plait_hair::scene::Camera;

/// The camera as a point on a sphere around its target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    pub target: Vec3,
    pub distance: f32,
    /// Around +Y, radians; 0 looks along −Z.
    pub yaw: f32,
    /// Above the horizon, radians.
    pub pitch: f32,
}

/// Short of straight up or down, where look-at with +Y up degenerates.
const MAX_PITCH: f32 = 1.5;

impl Orbit {
    pub fn from_camera(c: &Camera) -> Self {
        let target = Vec3::from(c.target);
        let offset = Vec3::from(c.eye) - target;
        let distance = offset.length().max(1e-3);
        Orbit {
            target,
            distance,
            yaw: offset.x.atan2(offset.z),
            pitch: (offset.y / distance).clamp(-1.0, 1.0).asin(),
        }
    }

    pub fn eye(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + self.distance * Vec3::new(cp * sy, sp, cp * cy)
    }

    /// `base` moved to this orbit (field of view and clip planes kept).
    pub fn camera(&self, base: &Camera) -> Camera {
        Camera {
            eye: self.eye().into(),
            target: self.target.into(),
            up: [0.0, 1.0, 0.0],
            ..base.clone()
        }
    }

    /// Drag by (dx, dy) pixels: a full turn per 600 pixels.
    pub fn rotate(&mut self, dx: f32, dy: f32) {
        let per_pixel = std::f32::consts::TAU / 600.0;
        self.yaw -= dx * per_pixel;
        self.pitch = (self.pitch + dy * per_pixel).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Scroll by `steps` (positive: closer), 10% per step.
    pub fn zoom(&mut self, steps: f32) {
        self.distance = (self.distance * 0.9f32.powf(steps)).clamp(0.05, 500.0);
    }

    /// Drag by (dx, dy) pixels of a view `height` pixels tall with vertical
    /// field of view `fov_y` (radians): the target follows the cursor.
    pub fn pan(&mut self, dx: f32, dy: f32, height: f32, fov_y: f32) {
        let eye = self.eye();
        let forward = (self.target - eye).normalize_or(Vec3::NEG_Z);
        let right = forward.cross(Vec3::Y).normalize_or(Vec3::X);
        let up = right.cross(forward);
        let world_per_pixel = 2.0 * self.distance * (fov_y * 0.5).tan() / height.max(1.0);
        self.target += (-dx * right + dy * up) * world_per_pixel;
    }
}

/// Where the light comes from: azimuth around +Y (degrees, 0 = from +Z) and
/// elevation above the horizon (degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightAngles {
    pub azimuth: f32,
    pub elevation: f32,
}

impl LightAngles {
    /// From the direction the light travels.
    pub fn from_direction(travel: Vec3) -> Self {
        let to_light = -travel.normalize_or(Vec3::NEG_Y);
        LightAngles {
            azimuth: to_light.x.atan2(to_light.z).to_degrees(),
            elevation: to_light.y.clamp(-1.0, 1.0).asin().to_degrees(),
        }
    }

    /// The direction the light travels.
    pub fn direction(&self) -> Vec3 {
        let (sa, ca) = self.azimuth.to_radians().sin_cos();
        let (se, ce) = self.elevation.to_radians().sin_cos();
        -Vec3::new(ce * sa, se, ce * ca)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            eye: [2.0, 0.5, 7.6],
            target: [0.0, -0.6, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_y_degrees: 35.0,
            near: 0.1,
            far: 100.0,
        }
    }

    #[test]
    fn an_orbit_starts_where_the_camera_is() {
        let o = Orbit::from_camera(&camera());
        let eye = o.camera(&camera()).eye;
        for (a, b) in eye.iter().zip(camera().eye) {
            assert!((a - b).abs() < 1e-5, "{eye:?}");
        }
    }

    #[test]
    fn rotating_keeps_the_distance_and_zooming_and_panning_move_as_asked() {
        let mut o = Orbit::from_camera(&camera());
        let d = o.distance;
        o.rotate(150.0, 40.0);
        assert!((o.eye() - o.target).length() - d < 1e-4);
        o.rotate(0.0, 1e6);
        assert_eq!(o.pitch, MAX_PITCH);
        o.zoom(1.0);
        assert!((o.distance - d * 0.9).abs() < 1e-4);
        let before = o.target;
        o.pan(10.0, 0.0, 100.0, 35f32.to_radians());
        assert!((o.target - before).length() > 0.0);
        assert!(
            ((o.target - before).y).abs() < 1e-6,
            "a sideways drag stays level"
        );
    }

    #[test]
    fn light_angles_round_trip() {
        let d = Vec3::new(-0.5, -1.0, -0.6).normalize();
        let back = LightAngles::from_direction(d).direction();
        assert!((back - d).length() < 1e-5, "{back:?}");
        // Straight overhead: travels down.
        let down = LightAngles {
            azimuth: 0.0,
            elevation: 90.0,
        }
        .direction();
        assert!((down - Vec3::NEG_Y).length() < 1e-5);
    }
}
