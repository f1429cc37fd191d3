//! The light's frustum holds every occluder and receiver, whatever the
//! light's direction. A directional light straight down (the way it travels
//! exactly −y) sees the ground square-on: every ground point at one depth.
//! Fitted with that depth as its far plane, rounding put the ground outside
//! the light's map: the head cast no shadow on it. Its image must be the
//! image of a light a thousandth of a radian off vertical, where the ground's
//! corners lie at different depths.

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (160, 120);

/// The small scene under a directional light travelling along `direction`,
/// through `pipelines/occupancy.toml`: the displayed image's RGB.
fn render(direction: [f32; 3]) -> Vec<[u8; 3]> {
    let (_lock, gpu) = open_gpu();
    let path = repo_root().join("examples/scenes/small.toml");
    let text = std::fs::read_to_string(&path).expect("small.toml");
    let from = "direction = [-0.5, -1.0, -0.6]";
    assert!(text.contains(from), "small.toml's light direction moved");
    let text = text.replace(from, &format!("direction = {direction:?}"));
    let scene = plait_hair::Scene::from_toml_str(&text, &path).expect("the scene parses");
    let scene = SceneData::new(scene).expect("the scene loads");
    let pipeline = repo_root().join("pipelines/occupancy.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, SIZE).expect("prepares");
    prepared.render().expect("renders");
    let image = prepared.image().expect("reads back");
    image.pixels().map(|p| [p.0[0], p.0[1], p.0[2]]).collect()
}

#[test]
fn a_light_straight_down_shadows_as_one_a_hairs_breadth_off_it() {
    let down = render([0.0, -1.0, 0.0]);
    let off = render([0.001, -1.0, 0.0]);
    let (mut differing, mut sum) = (0usize, 0u64);
    for (a, b) in down.iter().zip(&off) {
        let d = (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0);
        sum += u64::from(d);
        if d > 8 {
            differing += 1;
        }
    }
    let mean = sum as f64 / down.len() as f64;
    eprintln!(
        "straight down against 0.001 rad off: {differing} pixels differ by more than 8/255, mean {mean:.3}/255"
    );
    assert!(
        differing <= 20 && mean < 0.3,
        "a light straight down renders otherwise than one 0.001 rad off it: {differing} pixels differ by more than 8/255, mean {mean:.3}/255"
    );
}
