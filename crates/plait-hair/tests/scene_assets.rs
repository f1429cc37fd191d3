//! Scenes naming real assets: a `.tfx` groom with follow strands, placed by
//! a transform, with the camera and light fitted to it; and the errors a
//! scene author can make with those fields.

use std::path::{Path, PathBuf};

use glam::Vec3;
use plait_hair::{HairSource, Scene, Strands, TfxFile};

const LIGHT: &str = "[light]\ntype = \"directional\"\ndirection = [0, -1, 0]\n";

/// Guides standing on a small patch, in "centimetres", Z up: 12 strands of
/// 8 vertices each, written through plait's `.tfx` writer (its layout is
/// checked byte by byte in `tests/tfx.rs`).
fn write_groom(dir: &Path) -> PathBuf {
    let mut s = Strands::new();
    for i in 0..12 {
        let root = Vec3::new((i % 4) as f32 * 2.0, (i / 4) as f32 * 2.0, 150.0);
        let pts: Vec<Vec3> = (0..8)
            .map(|k| root + Vec3::new(0.5 * k as f32, 0.0, -3.0 * k as f32))
            .collect();
        s.push_strand(&pts, |_| 1.0, |_| 1.0, Vec3::ONE);
    }
    let path = dir.join("groom.tfx");
    let bytes = TfxFile::from_strands(&s, None)
        .expect("tfx")
        .to_bytes()
        .expect("bytes");
    std::fs::write(&path, bytes).expect("write");
    path
}

fn scene(dir: &Path, text: &str) -> Scene {
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).expect("write scene");
    Scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn load_error(text: &str) -> String {
    Scene::from_toml_str(text, Path::new("dir/s.toml"))
        .expect_err("must be refused")
        .to_string()
}

/// The NDC bounds of `strands`' bounding box seen by the scene's camera (4:3).
fn ndc_bounds(scene: &Scene, strands: &Strands) -> (Vec3, Vec3) {
    let vp = scene.camera.view_proj(4.0 / 3.0);
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for c in strands.bounds().corners() {
        let p = vp.project_point3(c);
        lo = lo.min(p);
        hi = hi.max(p);
    }
    (lo, hi)
}

#[test]
fn a_tfx_groom_with_follow_strands_placed_and_framed() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_groom(dir.path());
    let mut s = scene(
        dir.path(),
        "camera = \"fit\"\nlight = \"fit\"\n[hair]\nfile = \"groom.tfx\"\nfollow_strands = 3\n\
         follow_radius = 0.5\nfollow_tip_spread = 1.0\n\
         [hair.transform]\nscale = 0.01\nrotate_degrees = [-90, 0, 0]\ntranslate = [0, -1, 0]\n",
    );
    assert_eq!(
        s.hair.source,
        HairSource::File(dir.path().join("groom.tfx"))
    );
    let strands = s.load_hair().expect("loads");
    assert_eq!(strands.strand_count(), 12 * 4);
    assert_eq!(strands.point_count(), 12 * 4 * 8);
    // Z up in centimetres → Y up in metres: roots at y = 1.5 - 1, tips below.
    let root = strands.strand(0)[0];
    assert!((root - Vec3::new(0.0, 0.5, 0.0)).length() < 1e-5, "{root}");
    assert!(strands.strand(0)[7].y < root.y);
    // The fitted camera sees the whole groom, filling most of the height.
    let (lo, hi) = ndc_bounds(&s, &strands);
    assert!(
        lo.x >= -1.0 && hi.x <= 1.0 && lo.y >= -1.0 && hi.y <= 1.0,
        "{lo} {hi}"
    );
    assert!(hi.y - lo.y > 1.2 || hi.x - lo.x > 1.2, "{lo} {hi}");
    assert!(lo.z > 0.0 && hi.z < 1.0, "inside near/far: {lo} {hi}");
    // The fitted light shines from above the camera's side.
    assert!(s.light.direction_to_light().y > 0.5);
    assert_eq!(s.light.intensity, 3.0);
}

#[test]
fn fitting_frames_grooms_of_any_size_and_place() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_groom(dir.path());
    for (scale, translate) in [
        (1e-4, [0.0; 3]),
        (1.0, [500.0, -20.0, 3.0]),
        (1e3, [0.0; 3]),
    ] {
        let mut s = scene(
            dir.path(),
            &format!(
                "[camera]\nfit = true\ndirection = [1, 0.2, 0]\nfov_y_degrees = 50\n{LIGHT}\
                 [hair]\nfile = \"groom.tfx\"\n[hair.transform]\nscale = {scale:e}\ntranslate = {translate:?}\n"
            ),
        );
        let strands = s.load_hair().expect("loads");
        let (lo, hi) = ndc_bounds(&s, &strands);
        assert!(
            lo.x >= -1.0 && hi.x <= 1.0 && lo.y >= -1.0 && hi.y <= 1.0,
            "{scale}: {lo} {hi}"
        );
        assert!(hi.y - lo.y > 1.2 || hi.x - lo.x > 1.2, "{scale}: {lo} {hi}");
        assert!(lo.z > 0.0 && hi.z < 1.0, "{scale}: {lo} {hi}");
        assert_eq!(s.camera.fov_y_degrees, 50.0);
        // looking along -direction
        let view_dir = Vec3::from(s.camera.target) - Vec3::from(s.camera.eye);
        assert!(
            view_dir
                .normalize()
                .dot(-Vec3::new(1.0, 0.2, 0.0).normalize())
                > 0.999
        );
    }
}

#[test]
fn light_type_fit_keeps_colour_and_intensity() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_groom(dir.path());
    let mut s = scene(
        dir.path(),
        "camera = \"fit\"\nhair = { file = \"groom.tfx\" }\n[light]\ntype = \"fit\"\nintensity = 2\ncolor = [1, 0.5, 0.5]\n",
    );
    s.load_hair().expect("loads");
    assert_eq!((s.light.intensity, s.light.color), (2.0, [1.0, 0.5, 0.5]));
    assert!(s.framing.light);
}

#[test]
fn scene_errors_name_the_field_and_position() {
    let hair = "hair = { file = \"g.tfx\" }\n";
    let cases: &[(&str, &str)] = &[
        // (scene text, what the message must contain)
        (
            &format!("camera = \"fitt\"\n{hair}{LIGHT}"),
            "dir/s.toml:1:10",
        ),
        (
            &format!("{hair}{LIGHT}[camera]\nfit = true\neye = [0, 0, 1]\n"),
            "camera.eye is computed",
        ),
        (
            &format!("{hair}{LIGHT}[camera]\nfit = true\nzoom = 2\n"),
            "zoom",
        ),
        (
            &format!("{hair}{LIGHT}[camera]\neye = [0, 0, 1]\nfov_y_degrees = 40\n"),
            "camera.target is missing",
        ),
        (
            &format!("{hair}{LIGHT}[camera]\nfit = true\nmargin = 0.5\n"),
            "camera.margin",
        ),
        (
            &format!("{hair}{LIGHT}[camera]\nfit = true\ndirection = [0, 1, 0]\n"),
            "camera.up",
        ),
        (
            &format!("camera = \"fit\"\n{LIGHT}[hair]\nfile = \"g.tfx\"\nfollow_strands = 4\n"),
            "follow_radius",
        ),
        (
            &format!("camera = \"fit\"\n{LIGHT}[hair]\nfile = \"g.tfx\"\nfollow_radius = 1\n"),
            "follow_strands",
        ),
        (
            &format!(
                "camera = \"fit\"\n{LIGHT}[hair]\nfile = \"g.tfx\"\nfollow_strands = 2\nfollow_radius = -1\n"
            ),
            "hair.follow_radius",
        ),
        (
            &format!(
                "camera = \"fit\"\n{LIGHT}[hair]\nfile = \"g.tfx\"\n[hair.transform]\nscale = [1, 0, 1]\n"
            ),
            "not invertible",
        ),
        (
            &format!(
                "camera = \"fit\"\n{LIGHT}[hair]\nfile = \"g.tfx\"\n[hair.transform]\nscale = \"big\"\n"
            ),
            "a number or an array",
        ),
        (
            &format!("camera = \"fit\"\n{LIGHT}[hair]\nfollow_strands = 1\n"),
            "exactly one of `file` or `procedural`",
        ),
        (
            &format!("camera = \"fit\"\n{hair}[light]\ntype = \"fit\"\ndirection = [0, 1, 0]\n"),
            "placed from the camera",
        ),
        (
            &format!("camera = \"fit\"\n{hair}light = \"sun\"\n"),
            "expected \"fit\"",
        ),
    ];
    for (text, want) in cases {
        let msg = load_error(text);
        assert!(msg.contains(want), "{text}\n→ {msg}\n(wanted {want:?})");
        assert!(msg.starts_with("dir/s.toml"), "{msg}");
    }
}

#[test]
fn bad_assets_are_named_when_the_hair_loads() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("bad.tfx"), [0u8; 10]).expect("write");
    std::fs::write(dir.path().join("bad.bin"), b"not hair at all").expect("write");
    for (name, want) in [
        ("bad.tfx", "field `version` is 0"),
        ("bad.bin", "not a hair asset"),
        ("missing.tfx", "missing.tfx"),
        ("/dev/zero", "not a regular file"),
        (".", "not a regular file"),
    ] {
        let s = scene(
            dir.path(),
            &format!("camera = \"fit\"\nhair = {{ file = \"{name}\" }}\n{LIGHT}"),
        );
        let msg = s.strands().unwrap_err().to_string();
        assert!(msg.contains(name) && msg.contains(want), "{msg}");
    }
    // absurd follow counts are refused before allocating
    write_groom(dir.path());
    let s = scene(
        dir.path(),
        &format!(
            "camera = \"fit\"\n{LIGHT}[hair]\nfile = \"groom.tfx\"\nfollow_strands = 4000000000\nfollow_radius = 1\n"
        ),
    );
    let msg = s.strands().unwrap_err().to_string();
    assert!(
        msg.contains("groom.tfx") && msg.contains("hair.follow_strands"),
        "{msg}"
    );
}
