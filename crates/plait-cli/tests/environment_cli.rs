//! Environment lighting from the command line: a bad environment image or
//! an out-of-range map param is an error naming the file (and the scene
//! key's line:column) or the flag, exit code 2, and no image is written.

mod common;

use common::{plait, text};

/// `plait render` with `args`; asserts exit 2, no output written, and that
/// stderr contains every one of `expect`.
fn fails(args: &[&str], out: &std::path::Path, expect: &[&str]) {
    let mut all = vec![
        "render",
        "--size",
        "32x24",
        "--out",
        out.to_str().expect("utf-8"),
    ];
    all.extend_from_slice(args);
    let output = plait(&all);
    let stderr = text(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(!out.exists(), "{args:?} wrote {}", out.display());
    for e in expect {
        assert!(stderr.contains(e), "{args:?}: expected {e:?} in: {stderr}");
    }
}

#[test]
fn bad_environment_images_exit_2_naming_the_file_and_key() {
    let dir = tempfile::tempdir().expect("tempdir");
    let p = dir.path();
    let scene = |name: &str, environment: &str| {
        let path = p.join(name);
        let base = std::fs::read_to_string(common::root().join("examples/scenes/small.toml"))
            .expect("small scene");
        std::fs::write(&path, format!("{environment}\n{base}")).expect("write scene");
        path.to_str().expect("utf-8").to_owned()
    };
    std::fs::write(p.join("notes.hdr"), "plain text").expect("write");
    image::Rgb32FImage::from_pixel(40, 40, image::Rgb([1.0, 1.0, 1.0]))
        .save(p.join("square.exr"))
        .expect("write");
    let mut nan = image::Rgb32FImage::from_pixel(8, 4, image::Rgb([1.0, 1.0, 1.0]));
    nan.put_pixel(5, 1, image::Rgb([0.0, f32::NAN, 0.0]));
    nan.save(p.join("nan.exr")).expect("write");
    let out = p.join("out.png");
    for (name, key, expect) in [
        (
            "missing.toml",
            "environment = \"gone.hdr\"",
            vec!["gone.hdr", "missing.toml:1:15"],
        ),
        (
            "text.toml",
            "environment = \"notes.hdr\"",
            vec!["notes.hdr", "text.toml:1:15"],
        ),
        (
            "cross.toml",
            "environment = { image = \"square.exr\", layout = \"cube_cross\" }",
            vec!["square.exr", "4:3", "cross.toml:1:15"],
        ),
        (
            "nan.toml",
            "environment = \"nan.exr\"",
            vec!["nan.exr", "NaN in texel (5, 1)", "nan.toml:1:15"],
        ),
        (
            "key.toml",
            "environment = { image = \"x.hdr\", layot = \"equirect\" }",
            vec!["key.toml:1:", "layot"],
        ),
    ] {
        let path = scene(name, key);
        fails(
            &[
                "--scene",
                &path,
                "--set",
                "techniques.lighting=irradiance_maps",
            ],
            &out,
            &expect,
        );
    }
}

#[test]
fn map_params_out_of_range_name_the_flag() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("out.png");
    let small = "examples/scenes/small.toml";
    for (technique, flag, expect) in [
        (
            "irradiance_maps",
            "params.specular_intervals=0",
            "out of range 1..=32",
        ),
        (
            "irradiance_maps",
            "params.specular_intervals=33",
            "out of range 1..=32",
        ),
        (
            "sh_irradiance_maps",
            "params.sh_bands=17",
            "out of range 1..=16",
        ),
        (
            "sh_irradiance_maps",
            "params.diffuse_bands=0",
            "out of range 1..=16",
        ),
    ] {
        let lighting = format!("techniques.lighting={technique}");
        let flag_text = format!("--set {flag}");
        fails(
            &["--scene", small, "--set", &lighting, "--set", flag],
            &out,
            &[&flag_text, expect],
        );
    }
}

/// The brute-force reference sums every cube texel in every fragment, a
/// loop lavapipe would cut past its budget: its cube is capped at load
/// (docs/design.md, "Loop budgets"), and the maps, which sum once, are not.
#[test]
fn the_reference_refuses_an_environment_past_the_loop_budget() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("out.png");
    let small = "examples/scenes/small.toml";
    let reference = "techniques.lighting=environment_reference";
    fails(
        &[
            "--scene",
            small,
            "--set",
            reference,
            "--set",
            "params.environment_size=65",
        ],
        &out,
        &[
            "environment_reference",
            "65,535",
            "--set params.environment_size=64",
        ],
    );
    let check = |sets: &[&str]| {
        let mut args = vec!["check", "pipelines/occupancy.toml"];
        for s in sets {
            args.extend(["--set", s]);
        }
        plait(&args)
    };
    let at_cap = check(&[reference, "params.environment_size=64"]);
    assert!(at_cap.status.success(), "{}", text(&at_cap.stderr));
    let maps = check(&[
        "techniques.lighting=irradiance_maps",
        "params.environment_size=65",
    ]);
    assert!(maps.status.success(), "{}", text(&maps.stderr));
}
