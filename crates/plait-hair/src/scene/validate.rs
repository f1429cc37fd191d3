//! Range checks of a parsed scene, each message naming the field: camera
//! geometry, and every number finite so no NaN reaches the shaders.

use glam::Vec3;

use super::{Background, LightKind, Scene};

impl Scene {
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
        self.validate_radiometry()
    }

    /// The ranges the units of docs/formats.md ("Light and units") allow:
    /// light and radiance are not negative, and an albedo is a fraction of
    /// the light received (0 to 1), so no surface or fibre reflects more
    /// than it receives. Numbers are finite here (`validate`).
    fn validate_radiometry(&self) -> Result<(), String> {
        let l = &self.light;
        let m = &self.material;
        let mut not_negative: Vec<(&str, &[f32])> = vec![
            ("light.intensity", std::slice::from_ref(&l.intensity)),
            ("light.color", &l.color),
            ("ambient", std::slice::from_ref(&self.ambient)),
            ("material.diffuse", std::slice::from_ref(&m.diffuse)),
            ("material.specular", std::slice::from_ref(&m.specular)),
        ];
        if let Background::Color(color) = &self.background {
            not_negative.push(("background.color", color));
        }
        if let Some((name, v)) = not_negative
            .iter()
            .find(|(_, v)| v.iter().any(|x| *x < 0.0))
        {
            return Err(format!(
                "{name} must be ≥ 0 (light and radiance are not negative), got {v:?}"
            ));
        }
        let mut albedos: Vec<(&str, &[f32])> = vec![("material.color", &m.color)];
        if let Some(h) = &self.head {
            albedos.push(("head.albedo", &h.albedo));
        }
        if let Some(g) = &self.ground {
            albedos.push(("ground.albedo", &g.albedo));
        }
        if let Some((name, v)) = albedos
            .iter()
            .find(|(_, v)| v.iter().any(|x| !(0.0..=1.0).contains(x)))
        {
            return Err(format!(
                "{name} must be in [0, 1] (an albedo: the fraction of the light reflected), got {v:?}"
            ));
        }
        if m.diffuse + m.specular > 1.0 {
            return Err(format!(
                "material.diffuse + material.specular must be ≤ 1 (a white fibre reflecting no more than it receives), got {} + {}",
                m.diffuse, m.specular
            ));
        }
        Ok(())
    }
}
