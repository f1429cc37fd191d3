//! Light in physical units (docs/formats.md, "Light and units"): a white
//! Lambertian plane under irradiance E reads E/π (the white furnace of the
//! opaque shading), a uniform environment of radiance L_a reads ρ·L_a, and the
//! default scene's ground and hair radiance, measured in the float `scene`
//! target. The fibre furnace and one fibre's radiance are in
//! `tests/fibre.rs`.

use std::f64::consts::PI;

use glam::{Mat4, Vec3, Vec4};
use plait::session::{SceneData, prepare};
use plait_gpu::Gpu;
use plait_tests::{hair_taken_away, open_gpu, repo_root};

/// IEEE half to f32.
fn half(bits: u16) -> f32 {
    let sign = if bits & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exp = ((bits >> 10) & 0x1f) as i32;
    let mantissa = (bits & 0x3ff) as f32;
    sign * match exp {
        0 => mantissa * 2f32.powi(-24),
        31 => f32::INFINITY,
        _ => (1.0 + mantissa / 1024.0) * 2f32.powi(exp - 15),
    }
}

/// A rendered rgba16float target as linear floats, row-major.
struct Linear {
    width: u32,
    texels: Vec<[f32; 4]>,
}

impl Linear {
    fn at(&self, x: u32, y: u32) -> [f32; 4] {
        self.texels[(y * self.width + x) as usize]
    }
}

const SIZE: (u32, u32) = (160, 120);

/// The opaque pipeline's `scene` target (rgba16float): the head, the ground
/// and the strands drawn opaque, before any display transform. The `display`
/// helper's EXR output will replace this read once it lands.
fn scene_target(gpu: &Gpu, data: &SceneData) -> Linear {
    let pipeline = repo_root().join("pipelines/opaque.toml");
    let prepared = prepare(gpu, &pipeline, &[], data, SIZE).expect("opaque.toml prepares");
    prepared.render_unchecked().expect("renders");
    let read = prepared.read_resource("scene").expect("scene");
    assert_eq!(
        read.bytes.len(),
        (SIZE.0 * SIZE.1 * 8) as usize,
        "rgba16float"
    );
    let texels = read
        .bytes
        .chunks_exact(8)
        .map(|t| std::array::from_fn(|c| half(u16::from_le_bytes([t[2 * c], t[2 * c + 1]]))))
        .collect();
    Linear {
        width: read.width,
        texels,
    }
}

/// The pixel a world point falls in.
fn pixel_of(data: &SceneData, world: Vec3) -> (u32, u32) {
    let frame = data.frame(SIZE, 0);
    let clip = Mat4::from_cols_array_2d(&frame.camera_view_proj) * Vec4::from((world, 1.0));
    let ndc = clip.truncate() / clip.w;
    let x = (ndc.x * 0.5 + 0.5) * SIZE.0 as f32;
    let y = (0.5 - ndc.y * 0.5) * SIZE.1 as f32;
    assert!(
        x >= 0.0 && y >= 0.0 && x < SIZE.0 as f32 && y < SIZE.1 as f32,
        "{world} is out of view"
    );
    (x as u32, y as u32)
}

/// A scene whose only light on the ground is `light` (irradiance facing it)
/// from straight above and `ambient` radiance, over a white ground, seen from
/// above a corner of the ground far from the head's and the hair's shadow.
fn furnace_scene(intensity: f32, ambient: f32) -> SceneData {
    furnace_lit_by(
        &format!("type = \"directional\"\ndirection = [0.0, -1.0, 0.0]\nintensity = {intensity}"),
        ambient,
    )
}

/// The furnace scene under the `[light]` table's body `light`.
fn furnace_lit_by(light: &str, ambient: f32) -> SceneData {
    let text = format!(
        "ambient = {ambient}\n\
         [hair.procedural]\nstrands = 50\nsegments = 8\n\
         [head]\ncenter = [0.0, 0.0, 0.0]\nradii = [0.9, 1.05, 1.0]\n\
         [ground]\nheight = -2.7\nhalf_size = 12.0\nalbedo = [1.0, 1.0, 1.0]\n\
         [camera]\neye = [7.0, 1.0, 7.0]\ntarget = [7.5, -2.7, 6.0]\nfov_y_degrees = 30.0\n\
         [light]\n{light}\n\
         [background]\ncolor = [0.0, 0.0, 0.0]\n"
    );
    let path = repo_root().join("tests/radiometry-furnace.toml");
    let scene = plait_hair::Scene::from_toml_str(&text, &path).expect("the furnace scene parses");
    SceneData::new(scene).expect("loads")
}

/// Every pixel of the centre quarter of the image (all ground) within 1 % of
/// `want`, or the worst one's message.
fn centre_reads(image: &Linear, want: f64) -> Result<(), String> {
    let (w, h) = SIZE;
    let mut worst = (0.0f64, 0, 0, 0.0f32);
    for y in h / 4..3 * h / 4 {
        for x in w / 4..3 * w / 4 {
            let got = image.at(x, y);
            for c in got.iter().take(3) {
                let err = (*c as f64 - want).abs() / want;
                if err > worst.0 {
                    worst = (err, x, y, *c);
                }
            }
        }
    }
    if worst.0 > 0.01 {
        return Err(format!(
            "pixel ({}, {}) reads {}, want {want:.5} ({:.2} % off)",
            worst.1,
            worst.2,
            worst.3,
            worst.0 * 100.0
        ));
    }
    Ok(())
}

/// The white furnace of the opaque shading: a white Lambertian ground under
/// irradiance E = 2 from its normal reads E/π = 0.6366, and under a uniform
/// environment of radiance 0.5 alone reads 0.5, within 1 % at every pixel of
/// the image's centre (read in the float `scene` target). Dropping the 1/π in
/// `shaders/passes/opaque_shade.wgsl` reads 2.0 (214 % off).
#[test]
fn a_white_lambertian_plane_reads_irradiance_over_pi() {
    let (_lock, gpu) = open_gpu();
    let lit = scene_target(&gpu, &furnace_scene(2.0, 0.0));
    let direct = centre_reads(&lit, 2.0 / PI);
    let ambient = scene_target(&gpu, &furnace_scene(0.0, 0.5));
    let environment = centre_reads(&ambient, 0.5);
    assert!(
        direct.is_ok() && environment.is_ok(),
        "irradiance 2: {direct:?}; ambient 0.5: {environment:?}"
    );
}

/// Measures the default scene (the built-in one) through the opaque
/// pipeline: the ground's radiance at a lit pixel against
/// E·cos θ·ρ/π + ρ·L_a (θ from the scene's light direction and the ground's
/// normal), and the mean radiance of the hair's pixels (those that change
/// when the hair is taken away). Prints both; holds the ground within 1 %.
#[test]
fn default_scene_ground_and_hair_radiance() {
    let (_lock, gpu) = open_gpu();
    let data = SceneData::load(None).expect("the default scene");
    let s = &data.scene;
    let light = match s.light.kind {
        plait_hair::LightKind::Directional { direction } => -Vec3::from(direction).normalize(),
        _ => panic!("the default light is directional"),
    };
    let cos = light.dot(Vec3::Y) as f64;
    let ground = s.ground.as_ref().expect("a ground");
    let point = Vec3::new(2.0, ground.height, 0.5);
    let (x, y) = pixel_of(&data, point);
    let with_hair = scene_target(&gpu, &data);
    let mut bare = data.clone();
    bare.strands = hair_taken_away(&data.strands);
    let without = scene_target(&gpu, &bare);
    let got = with_hair.at(x, y);
    println!(
        "theta {:.2} deg; ground at {point} (pixel {x}, {y}): {:?}",
        cos.acos().to_degrees(),
        &got[..3]
    );
    let mut failures = Vec::new();
    for (c, (&value, (&albedo, &color))) in got
        .iter()
        .zip(ground.albedo.iter().zip(&s.light.color))
        .enumerate()
    {
        let (rho, e) = (albedo as f64, (s.light.intensity * color) as f64);
        let want = e * cos * rho / PI + rho * s.ambient as f64;
        println!("  channel {c}: {value:.4}, expected {want:.4}");
        if (value as f64 - want).abs() > 0.01 * want {
            failures.push(format!("channel {c}: {value} vs {want:.4}"));
        }
    }
    let (mut sum, mut n) = ([0.0f64; 3], 0usize);
    for (a, b) in with_hair.texels.iter().zip(&without.texels) {
        if (0..3).any(|c| a[c] != b[c]) {
            (0..3).for_each(|c| sum[c] += a[c] as f64);
            n += 1;
        }
    }
    let mean = sum.map(|v| v / n.max(1) as f64);
    let luminance = 0.2126 * mean[0] + 0.7152 * mean[1] + 0.0722 * mean[2];
    println!("hair: {n} pixels, mean radiance {mean:.4?}, luminance {luminance:.4}");
    assert!(failures.is_empty(), "{}", failures.join("; "));
}

/// A spot light's intensity is radiant intensity I: a point of the white
/// ground at distance d from it, the light at angle θ from the normal,
/// reads I·cos θ/(π d²) — checked under the light (d = 5) and 1 and 0.8 units
/// aside along the ground (both ways), within 1 %. Without the 1/d² of
/// `plait::frame::light_irradiance` every point reads d² (25 to 26) times
/// more: 15.91 under the light.
#[test]
fn a_spot_light_falls_off_with_the_squared_distance() {
    let (_lock, gpu) = open_gpu();
    let intensity: f64 = 50.0;
    let foot = Vec3::new(7.5, -2.7, 6.0);
    let light = foot + Vec3::new(0.0, 5.0, 0.0);
    let data = furnace_lit_by(
        &format!(
            "type = \"spot\"\nposition = [{}, {}, {}]\ndirection = [0.0, -1.0, 0.0]\n\
             cone_degrees = 90.0\nintensity = {intensity}",
            light.x, light.y, light.z
        ),
        0.0,
    );
    let image = scene_target(&gpu, &data);
    let mut failures = Vec::new();
    for aside in [0.0, 1.0, -0.8] {
        let point = foot + Vec3::new(aside, 0.0, 0.0);
        let (x, y) = pixel_of(&data, point);
        let d = (light - point).length() as f64;
        let want = intensity * (5.0 / d) / (PI * d * d);
        let got = image.at(x, y)[0] as f64;
        println!("{aside} aside (pixel {x}, {y}): {got:.5}, expected {want:.5}");
        if (got - want).abs() > 0.01 * want {
            failures.push(format!("{aside} aside: {got:.5} vs {want:.5}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("; "));
}
