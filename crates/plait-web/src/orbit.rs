//! The page's camera: the scene's own camera turned about its target by the
//! mouse (yaw about the camera's up, pitch toward it), at its distance.

use glam::Vec3;
use plait_hair::camera::Camera;

/// Pitch stops short of the poles so the view never flips.
const MAX_PITCH: f32 = 1.5;

/// `camera` orbited by `yaw` and `pitch` radians about its target.
pub fn orbit(camera: &Camera, yaw: f32, pitch: f32) -> Camera {
    let target = Vec3::from(camera.target);
    let up = Vec3::from(camera.up).normalize_or(Vec3::Y);
    let offset = Vec3::from(camera.eye) - target;
    let distance = offset.length();
    let dir = offset / distance.max(f32::MIN_POSITIVE);
    // Elevation and azimuth of the eye about `up`, then turned.
    let elevation = dir.dot(up).clamp(-1.0, 1.0).asin();
    let flat = (dir - up * dir.dot(up)).normalize_or(up.any_orthonormal_vector());
    let side = up.cross(flat);
    let elevation = (elevation + pitch).clamp(-MAX_PITCH, MAX_PITCH);
    let (sy, cy) = yaw.sin_cos();
    let azimuth = flat * cy + side * sy;
    let dir = azimuth * elevation.cos() + up * elevation.sin();
    Camera {
        eye: (target + dir * distance).into(),
        ..camera.clone()
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
    fn no_turn_keeps_the_scene_camera() {
        let c = orbit(&camera(), 0.0, 0.0);
        for (a, b) in c.eye.iter().zip(camera().eye) {
            assert!((a - b).abs() < 1e-5, "{:?}", c.eye);
        }
    }

    #[test]
    fn a_half_turn_puts_the_eye_behind_the_target_at_the_same_distance() {
        let c = orbit(&camera(), std::f32::consts::PI, 0.0);
        assert!((c.eye[0] + 2.0).abs() < 1e-4 && (c.eye[2] + 7.6).abs() < 1e-4);
        assert!((c.eye[1] - 0.5).abs() < 1e-4, "{:?}", c.eye);
    }
}
