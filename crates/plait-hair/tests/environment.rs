//! The scene's `environment` key and the environment loader: every layout
//! reads to the same radiance, and every bad input is an error naming the
//! file (and the scene key's line:column).

use std::path::Path;

use glam::Vec3;
use plait_hair::environment::cube;
use plait_hair::environment::{Environment, EnvironmentSource, Layout};
use plait_hair::{Scene, SceneError};

const MINIMAL: &str = "[hair.procedural]\nstrands = 10\n[camera]\neye = [0, 0, 5]\ntarget = [0, 0, 0]\nfov_y_degrees = 40\n[light]\ntype = \"directional\"\ndirection = [0, -1, 0]\n";

fn scene(environment: &str, dir: &Path) -> Result<Scene, SceneError> {
    let path = dir.join("scene.toml");
    std::fs::write(&path, format!("{environment}\n{MINIMAL}")).expect("write scene");
    Scene::load(&path)
}

/// A colour per face, so a face that lands in the wrong place shows.
const FACE_COLOURS: [[f32; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 1.0],
    [1.0, 0.0, 1.0],
];

fn face_image(face: usize, n: u32) -> image::Rgb32FImage {
    image::Rgb32FImage::from_pixel(n, n, image::Rgb(FACE_COLOURS[face]))
}

fn assert_faces_land(env: &plait_hair::EnvironmentImage, what: &str) {
    for (face, colour) in FACE_COLOURS.iter().enumerate() {
        let d = cube::direction(face, 0.0, 0.0).normalize();
        let got = env.radiance(d);
        assert!(
            got.abs_diff_eq(Vec3::from(*colour), 1e-3),
            "{what}: face {face} reads {got}"
        );
    }
}

#[test]
fn a_path_a_table_or_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene("", dir.path()).expect("no key");
    assert_eq!(s.environment, Environment::default());
    assert_eq!(s.environment.source, EnvironmentSource::Sky);
    let s = scene("environment = \"sky.hdr\"", dir.path()).expect("a path");
    assert_eq!(
        s.environment.source,
        EnvironmentSource::Image {
            path: dir.path().join("sky.hdr"),
            layout: Layout::Equirect
        }
    );
    assert!(
        s.environment
            .declared_at
            .as_deref()
            .is_some_and(|at| at.ends_with("scene.toml:1:15"))
    );
    let s = scene(
        "[environment]\nimage = \"c.exr\"\nlayout = \"cube_cross\"\nrotate = 90\nintensity = 2",
        dir.path(),
    )
    .expect("a table");
    assert_eq!(s.environment.rotate_degrees, 90.0);
    assert_eq!(s.environment.intensity, 2.0);
}

#[test]
fn bad_keys_are_reported_at_their_line_and_column() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (text, expect) in [
        ("environment = 3", "scene.toml:1:15"),
        ("[environment]\nimag = \"x.hdr\"", "scene.toml:2:1"),
        ("[environment]\nlayout = \"sphere\"", "scene.toml:2:10"),
        (
            "[environment]\nlayout = \"cube_faces\"\nimage = \"x.hdr\"",
            "cube_faces",
        ),
        ("[environment]\nfaces = [\"a.hdr\"]", "6 images"),
        (
            "[environment]\nimage = \"x.hdr\"\nintensity = -1",
            "intensity",
        ),
        ("[environment]\nimage = \"x.hdr\"\nrotate = nan", "rotate"),
    ] {
        let e = scene(text, dir.path()).expect_err(text).to_string();
        assert!(e.contains(expect), "{text:?}: {e}");
        assert!(e.contains("scene.toml:"), "{text:?}: {e}");
    }
}

#[test]
fn every_layout_reads_the_same_directions() {
    let dir = tempfile::tempdir().expect("tempdir");
    let n = 8;
    // Six face files.
    let names: Vec<String> = (0..6).map(|f| format!("face{f}.exr")).collect();
    for (f, name) in names.iter().enumerate() {
        face_image(f, n)
            .save(dir.path().join(name))
            .expect("write face");
    }
    let list = names
        .iter()
        .map(|n| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ");
    let s = scene(&format!("[environment]\nfaces = [{list}]"), dir.path()).expect("faces");
    assert_faces_land(&s.environment.load().expect("faces load"), "cube_faces");
    // A face of another size is named.
    face_image(3, n / 2)
        .save(dir.path().join("small.exr"))
        .expect("write face");
    let odd = list.replace("face3.exr", "small.exr");
    let s = scene(&format!("[environment]\nfaces = [{odd}]"), dir.path()).expect("faces");
    let e = s
        .environment
        .load()
        .expect_err("a smaller face")
        .to_string();
    assert!(e.contains("small.exr") && e.contains("8×8"), "{e}");

    // A horizontal cross: +y above +z; -x, +z, +x, -z; -y below +z.
    let cells = [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (3, 1)];
    let mut cross = image::Rgb32FImage::new(4 * n, 3 * n);
    for (f, &(col, row)) in cells.iter().enumerate() {
        image::imageops::replace(
            &mut cross,
            &face_image(f, n),
            (col * n) as i64,
            (row * n) as i64,
        );
    }
    cross
        .save(dir.path().join("cross.exr"))
        .expect("write cross");
    let s = scene(
        "[environment]\nimage = \"cross.exr\"\nlayout = \"cube_cross\"",
        dir.path(),
    )
    .expect("cross");
    assert_faces_land(&s.environment.load().expect("cross loads"), "cube_cross");

    // An equirect made from the cube reads the same, turned by rotate.
    let env = s.environment.load().expect("cross loads");
    let mut equirect = image::Rgb32FImage::new(env.width(), env.height());
    for (x, y, p) in equirect.enumerate_pixels_mut() {
        p.0 = env.image.texels[(y * env.width() + x) as usize];
    }
    equirect
        .save(dir.path().join("sky.hdr"))
        .expect("write hdr");
    let s = scene("environment = \"sky.hdr\"", dir.path()).expect("hdr");
    assert_faces_land(&s.environment.load().expect("hdr loads"), "equirect .hdr");
    let s = scene(
        "[environment]\nimage = \"sky.hdr\"\nrotate = 90\nintensity = 2",
        dir.path(),
    )
    .expect("turned");
    let turned = s.environment.load().expect("turned loads");
    // Turned +90° about +y (right-handed: +x goes to -z), twice as bright.
    let got = turned.radiance(Vec3::NEG_Z);
    assert!(
        got.abs_diff_eq(2.0 * Vec3::from(FACE_COLOURS[0]), 2e-2),
        "rotate: {got}"
    );

    // An 8-bit PNG is sRGB: 188/255 decodes to about 0.5.
    image::RgbImage::from_pixel(16, 8, image::Rgb([188, 188, 188]))
        .save(dir.path().join("grey.png"))
        .expect("write png");
    let s = scene("environment = \"grey.png\"", dir.path()).expect("png");
    let grey = s.environment.load().expect("png loads").radiance(Vec3::Y);
    assert!((grey.x - 0.503).abs() < 0.01, "{grey}");
}

#[test]
fn bad_images_name_the_file_and_the_scene_key() {
    let dir = tempfile::tempdir().expect("tempdir");
    let p = dir.path();
    std::fs::write(p.join("notes.hdr"), "not an image at all").expect("write");
    image::Rgb32FImage::from_pixel(50, 30, image::Rgb([1.0, 1.0, 1.0]))
        .save(p.join("odd.exr"))
        .expect("write");
    let mut nan = image::Rgb32FImage::from_pixel(8, 4, image::Rgb([1.0, 1.0, 1.0]));
    nan.put_pixel(3, 2, image::Rgb([f32::NAN, 0.0, 0.0]));
    nan.save(p.join("nan.exr")).expect("write");
    let mut inf = image::Rgb32FImage::from_pixel(8, 4, image::Rgb([1.0, 1.0, 1.0]));
    inf.put_pixel(1, 1, image::Rgb([0.0, f32::INFINITY, 0.0]));
    inf.save(p.join("inf.exr")).expect("write");
    let mut negative = image::Rgb32FImage::from_pixel(8, 4, image::Rgb([1.0, 1.0, 1.0]));
    negative.put_pixel(0, 0, image::Rgb([0.0, 0.0, -1.0]));
    negative.save(p.join("negative.exr")).expect("write");
    for (key, file, expect) in [
        (
            "environment = \"missing.hdr\"",
            "missing.hdr",
            "cannot read",
        ),
        ("environment = \"notes.hdr\"", "notes.hdr", "image"),
        (
            "environment = \"odd.exr\"",
            "odd.exr",
            "twice as wide as high",
        ),
        (
            "[environment]\nimage = \"odd.exr\"\nlayout = \"cube_cross\"",
            "odd.exr",
            "a cube cross must be 4:3",
        ),
        (
            "environment = \"nan.exr\"",
            "nan.exr",
            "NaN in texel (3, 2)",
        ),
        (
            "environment = \"inf.exr\"",
            "inf.exr",
            "infinite radiance in texel (1, 1)",
        ),
        (
            "environment = \"negative.exr\"",
            "negative.exr",
            "negative radiance",
        ),
    ] {
        let s = scene(key, p).expect("the key parses");
        let e = s.environment.load().expect_err(key).to_string();
        assert!(e.contains(file) && e.contains(expect), "{key}: {e}");
        let line_col = if key.starts_with('[') {
            "scene.toml:1:1"
        } else {
            "scene.toml:1:15"
        };
        assert!(e.contains(line_col), "{key}: {e}");
    }
}
