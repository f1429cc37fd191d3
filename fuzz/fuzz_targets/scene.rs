//! Scenes: load, validate, fit camera and light, apply follow strands and
//! the transform to a small groom.
#![no_main]
use glam::Vec3;
use libfuzzer_sys::fuzz_target;
use plait_hair::{Aabb, Scene, Strands};
use std::path::Path;

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    let Ok(mut scene) = Scene::from_toml_str(text, Path::new("examples/scenes/fuzz.toml")) else {
        return;
    };
    let mut strands = Strands::new();
    for i in 0..4 {
        let pts: Vec<Vec3> = (0..6)
            .map(|k| Vec3::new(i as f32, -(k as f32), 0.0))
            .collect();
        strands.push_strand(&pts, |_| 1.0, |_| 1.0, Vec3::ONE);
    }
    if let Some(follow) = &scene.hair.follow
        && follow.check_size(&strands).is_ok_and(|n| n < 1 << 20)
    {
        strands = follow.apply(&strands);
    }
    if let Some(t) = &scene.hair.transform {
        let _ = t.apply(&mut strands);
    }
    scene.frame(strands.bounds());
    let _ = scene.light.view_proj(strands.bounds(), Aabb::EMPTY);
    let _ = scene.camera.view_proj(4.0 / 3.0);
});
