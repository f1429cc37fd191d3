//! The built-in default scene, what `plait` renders without a scene file;
//! `examples/scenes/default.toml` must stay equal to it (a test checks).

use super::{
    Background, Camera, Framing, Ground, Hair, HairMaterial, HairSource, Head, Light, LightKind,
    Scene,
};
use crate::environment::Environment;
use crate::groom::{GroomSpec, HeadShape, ScalpRegion, Style};

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
            hair: Hair::from(HairSource::Procedural(GroomSpec {
                style: Style::Wavy,
                strands: 10_000,
                segments: 32,
                head,
                scalp: ScalpRegion {
                    max_polar_degrees: 105.0,
                    face_polar_degrees: 50.0,
                    face_half_width_degrees: 70.0,
                },
                // Material, gravity and the rest: the groom's defaults.
                ..GroomSpec::default()
            })),
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
            meshes: Vec::new(),
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
            framing: Framing::default(),
            background: Background::Color([0.05, 0.06, 0.08]),
            material: HairMaterial::default(),
            ambient: 0.15,
            environment: Environment::default(),
            animation: None,
        }
    }
}
