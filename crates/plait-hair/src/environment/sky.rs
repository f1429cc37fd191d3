//! The built-in procedural sky: the environment of a scene that names none,
//! so environment lighting works without downloading an image. A blue
//! gradient from the horizon to the zenith, a warm sun above and in front of
//! the default camera's right, and a darker ground.

use glam::Vec3;

use super::image::{EnvironmentImage, LinearImage, equirect_direction};

/// Direction towards the sun.
pub fn sun_direction() -> Vec3 {
    Vec3::new(0.45, 0.6, 0.65).normalize()
}

/// Radiance of the sky from unit direction `d` (linear RGB).
pub fn radiance(d: Vec3) -> Vec3 {
    let zenith = Vec3::new(0.18, 0.34, 0.75);
    let horizon = Vec3::new(0.75, 0.78, 0.8);
    let ground = Vec3::new(0.16, 0.14, 0.12);
    let sky = if d.y >= 0.0 {
        horizon.lerp(zenith, d.y.powf(0.5))
    } else {
        horizon.lerp(ground, (-d.y * 6.0).min(1.0))
    };
    // A sun about 5° wide with a glow: most of the sky's energy, so hair
    // shows a direction-dependent highlight.
    let c = d.dot(sun_direction());
    let sun = Vec3::new(1.0, 0.9, 0.75)
        * (60.0 * ((c - 1.0) * 1500.0).exp() + 1.5 * ((c - 1.0) * 12.0).exp());
    sky + sun
}

/// The sky as an equirectangular image `width` × `width`/2.
pub fn image(width: u32) -> EnvironmentImage {
    let height = width / 2;
    let texels = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let d = equirect_direction(
                (x as f32 + 0.5) / width as f32,
                (y as f32 + 0.5) / height as f32,
            );
            radiance(d).to_array()
        })
        .collect();
    EnvironmentImage {
        image: LinearImage {
            width,
            height,
            texels,
        },
    }
}
