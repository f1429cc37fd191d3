//! `plait export mitsuba` rendered by Mitsuba 3 (`scripts/mitsuba/render.py`):
//! a tiny scene end to end (the ground's radiance against Lambert's analytic
//! value, the strand where plait's camera projects it), and Mitsuba's
//! failures as exit 2 with its message. Mitsuba is installed by
//! `scripts/ensure-mitsuba.sh` (pinned, in the build folder); without it
//! these tests fail with that script's message, they are never skipped.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use glam::Vec3;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The Python of Mitsuba's venv and the environment render.py needs, from
/// `scripts/ensure-mitsuba.sh` (which installs what is missing).
fn mitsuba_env() -> Vec<(String, String)> {
    let out = Command::new("bash")
        .arg(repo().join("scripts/ensure-mitsuba.sh"))
        .output()
        .expect("bash runs");
    assert!(
        out.status.success(),
        "scripts/ensure-mitsuba.sh failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| l.strip_prefix("export "))
        .filter_map(|l| l.split_once('='))
        .map(|(k, v)| (k.to_string(), v.trim_matches('\'').to_string()))
        .collect()
}

fn render_py(env: &[(String, String)], args: &[&Path]) -> Output {
    render_py_spp(env, args, 16)
}

fn render_py_spp(env: &[(String, String)], args: &[&Path], spp: u32) -> Output {
    let python = &env
        .iter()
        .find(|(k, _)| k == "PLAIT_MITSUBA_PYTHON")
        .expect("python")
        .1;
    Command::new(python)
        .arg(repo().join("scripts/mitsuba/render.py"))
        .args(args)
        .args(["--spp", &spp.to_string(), "--max-depth", "2"])
        .args(["--coverage-spp", "64"])
        .envs(env.iter().map(|(k, v)| (k, v)))
        .output()
        .expect("python runs")
}

const SCENE: &str = r#"
ambient = 0.0
hair = { file = "line.hair" }
[ground]
height = -1.0
half_size = 10.0
albedo = [0.5, 0.5, 0.5]
[camera]
eye = [0.0, 0.0, 5.0]
target = [0.0, 0.0, 0.0]
fov_y_degrees = 30.0
[light]
type = "directional"
direction = [0.0, -1.0, -1.0]
intensity = 2.0
[background]
color = [0.0, 0.0, 0.0]
"#;

/// One opaque strand from x = -0.2 to x = 1.2 at y = 0.3, 0.3 thick (about
/// 2.7 pixels at 32×24): not symmetric, so a mirrored camera shows.
fn write_scene(dir: &Path) -> PathBuf {
    let hair = plait_hair::HairFile {
        hair_count: 1,
        points: (0..=8)
            .map(|i| [-0.2 + 1.4 * i as f32 / 8.0, 0.3, 0.0])
            .collect(),
        default_segments: 8,
        default_thickness: 0.3,
        default_transparency: 0.0,
        default_color: [0.5, 0.5, 0.5],
        ..Default::default()
    };
    hair.write(dir.join("line.hair")).expect("hair written");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, SCENE).expect("scene written");
    scene
}

/// `plait export mitsuba SCENE --size 32x24 --out DIR/mitsuba`.
fn export(scene: &Path, dir: &Path) -> PathBuf {
    let folder = dir.join("mitsuba");
    let out = Command::new(env!("CARGO_BIN_EXE_plait"))
        .args(["export", "mitsuba"])
        .arg(scene)
        .args(["--size", "32x24", "--out"])
        .arg(&folder)
        .output()
        .expect("plait runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    folder
}

fn pixel(img: &image::Rgb32FImage, x: u32, y: u32) -> f32 {
    img.get_pixel(x, y).0[0]
}

#[test]
fn a_tiny_scene_renders_in_plaits_units_and_plaits_camera() {
    let env = mitsuba_env();
    let tmp = tempfile::tempdir().expect("temp dir");
    let scene = write_scene(tmp.path());
    let folder = export(&scene, tmp.path());
    let (exr, cov) = (tmp.path().join("out.exr"), tmp.path().join("cov.exr"));
    let started = std::time::Instant::now();
    let out = render_py(&env, &[&folder, &exr, Path::new("--coverage"), &cov]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    eprintln!(
        "Mitsuba render of 32x24, 16 spp: {:.1} s",
        started.elapsed().as_secs_f32()
    );
    let img = image::open(&exr).expect("EXR reads").to_rgb32f();
    let cov = image::open(&cov).expect("coverage EXR reads").to_rgb32f();
    assert_eq!(img.dimensions(), (32, 24));

    // Lit ground in the bottom row: Lambert ρ/π · E · cos θ, θ = 45°.
    let want = 0.5 / std::f32::consts::PI * 2.0 * std::f32::consts::FRAC_1_SQRT_2;
    for x in [1, 16, 30] {
        let got = pixel(&img, x, 23);
        assert!(
            (got / want - 1.0).abs() < 0.01,
            "ground at ({x}, 23): {got}, analytic {want}"
        );
    }

    // The strand is where plait's camera projects it.
    let camera = plait_hair::Camera {
        eye: [0.0, 0.0, 5.0],
        target: [0.0, 0.0, 0.0],
        up: [0.0, 1.0, 0.0],
        fov_y_degrees: 30.0,
        near: 0.1,
        far: 100.0,
    };
    let to_pixel = |p: Vec3| {
        let ndc = camera.view_proj(32.0 / 24.0).project_point3(p);
        (((ndc.x + 1.0) * 16.0) as u32, ((1.0 - ndc.y) * 12.0) as u32)
    };
    let (x, y) = to_pixel(Vec3::new(1.0, 0.3, 0.0));
    assert!(
        pixel(&cov, x, y) >= 0.9,
        "strand at ({x}, {y}): coverage {}",
        pixel(&cov, x, y)
    );
    for (x, y) in [(x, y - 4), (x, y + 4), to_pixel(Vec3::new(-1.0, 0.3, 0.0))] {
        assert_eq!(pixel(&cov, x, y), 0.0, "no strand at ({x}, {y})");
    }
}

#[test]
fn a_mitsuba_failure_is_exit_2_with_its_message() {
    let env = mitsuba_env();
    let tmp = tempfile::tempdir().expect("temp dir");
    // An export whose hair shape is then given a type Mitsuba has not.
    let folder = export(&write_scene(tmp.path()), tmp.path());
    let xml = std::fs::read_to_string(folder.join("scene.xml")).unwrap();
    assert!(xml.contains("type=\"bsplinecurve\""), "{xml}");
    std::fs::write(
        folder.join("scene.xml"),
        xml.replace("type=\"bsplinecurve\"", "type=\"nosuch\""),
    )
    .unwrap();
    let out = render_py(&env, &[&folder, &tmp.path().join("out.exr")]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.starts_with("error: "), "{err}");
    assert!(
        err.contains("mitsuba:") && err.contains("nosuch"),
        "Mitsuba's message: {err}"
    );
    assert!(
        err.contains(&folder.display().to_string()),
        "names the scene: {err}"
    );
    assert!(!tmp.path().join("out.exr").exists(), "no image written");
}

/// Mitsuba's hair BSDF shades a fibre about its frame's second axis; the
/// export must make that the strand's tangent. Two straight strands, one
/// along x (A, at y = −0.6) and one along y (B, at x = −0.6), backlit by a
/// light travelling along (−0.3, −0.3, 1): swapping x and y maps the scene
/// (camera, light, strands, the square pixel grid) onto itself and A onto
/// B, so shaded about their own axes the two carry the same light (their
/// forward scattering, Chiang et al. 2016's TT lobe, towards the eye). A
/// frame built from the normal alone (a `linearcurve` export, Mitsuba
/// 3.9.1) is right for B and off by up to 90° for A.
#[test]
fn each_fibre_is_shaded_about_its_strands_axis() {
    let env = mitsuba_env();
    let tmp = tempfile::tempdir().expect("temp dir");
    let scene = write_scene(tmp.path());
    let toml = std::fs::read_to_string(&scene).expect("scene reads");
    // The ground far below: out of the picture, which stays symmetric.
    let toml = toml
        .replace(
            "direction = [0.0, -1.0, -1.0]",
            "direction = [-0.3, -0.3, 1.0]",
        )
        .replace("height = -1.0", "height = -50.0");
    std::fs::write(&scene, toml).expect("scene written");
    let along = |i: usize| 0.2 + 0.2 * i as f32;
    let hair = plait_hair::HairFile {
        hair_count: 2,
        points: (0..8)
            .map(|i| [along(i), -0.6, 0.0])
            .chain((0..8).map(|i| [-0.6, along(i), 0.0]))
            .collect(),
        default_segments: 7,
        default_thickness: 0.3,
        default_transparency: 0.0,
        default_color: [0.5, 0.5, 0.5],
        ..Default::default()
    };
    hair.write(tmp.path().join("line.hair"))
        .expect("hair written");
    let folder = export(&scene, tmp.path());
    let exr = tmp.path().join("out.exr");
    let out = render_py_spp(&env, &[&folder, &exr], 64);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let img = image::open(&exr).expect("EXR reads").to_rgb32f();
    // Mirror windows across each strand (pixel 5/44.8 world units at z = 0):
    // A around x = 0.95, columns 23–25, rows 14–20; B its swap.
    let sum = |cols: std::ops::Range<u32>, rows: std::ops::Range<u32>| -> f32 {
        cols.flat_map(|x| rows.clone().map(move |y| (x, y)))
            .map(|(x, y)| pixel(&img, x, y))
            .sum()
    };
    let (a, b) = (sum(23..26, 14..21), sum(7..14, 2..5));
    eprintln!(
        "strand A (along x) {a}, strand B (along y) {b}: A/B {}",
        a / b
    );
    assert!(
        (a / b - 1.0).abs() < 0.25,
        "the two strands differ only by x <-> y: A {a}, B {b}"
    );
}
