//! The `geometry` point from the command line (issue 23): `--set
//! techniques.geometry=lod` works on any pipeline, with or without the point
//! in its `[techniques]`, and a screen fraction out of range is one error
//! naming the param, exit 2, no image written.

mod common;
use common::{plait, text};

#[test]
fn lod_renders_on_a_pipeline_that_does_not_list_the_point() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("lod.png");
    // forward.toml's [techniques] names shading, lighting and ambient_occlusion only.
    let run = plait(&[
        "render",
        "pipelines/forward.toml",
        "--scene",
        "tests/fixtures/golden_far.toml",
        "--size",
        "64x48",
        "--set",
        "techniques.geometry=lod",
        "--set",
        "params.lod_screen_fraction=1.0",
        "--out",
        out.to_str().expect("utf-8 path"),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(out.exists());
    assert!(
        text(&run.stdout).contains("geometry/lod"),
        "{}",
        text(&run.stdout)
    );
    // The strands left out are named, never silent.
    let stderr = text(&run.stderr);
    assert!(stderr.contains("note: geometry lod: "), "{stderr}");
    assert!(
        stderr.contains(" strands drawn from the camera, each for "),
        "{stderr}"
    );
}

#[test]
fn a_screen_fraction_out_of_range_is_one_error_naming_the_param() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("bad.png");
    for bad in ["1.5", "0"] {
        let flag = format!("params.lod_screen_fraction={bad}");
        let run = plait(&[
            "render",
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            "64x48",
            "--set",
            "techniques.geometry=lod",
            "--set",
            &flag,
            "--out",
            out.to_str().expect("utf-8 path"),
        ]);
        let stderr = text(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{stderr}");
        assert!(!out.exists(), "no image for a refused render");
        // Every hair draw takes the param: still one error, at the flag.
        assert_eq!(stderr.matches("error:").count(), 1, "{stderr}");
        assert!(
            stderr.contains(&format!(
                "--set {flag}: param `lod_screen_fraction` of passes"
            )),
            "{stderr}"
        );
        assert!(stderr.contains("out of range 0.001..=1"), "{stderr}");
    }
    let typo = plait(&[
        "check",
        "pipelines/occupancy.toml",
        "--set",
        "techniques.geometry=lods",
    ]);
    assert_eq!(typo.status.code(), Some(2));
    assert!(
        text(&typo.stderr).contains("did you mean `lod`?"),
        "{}",
        text(&typo.stderr)
    );
}

/// `geometry = "wisps"` renders on any pipeline, and says what it built:
/// how many wisps, and that the groom (no guides) lends its strands as guides.
#[test]
fn wisps_render_and_name_what_they_follow() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("wisps.png");
    let run = plait(&[
        "render",
        "pipelines/forward.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "64x48",
        "--set",
        "techniques.geometry=wisps",
        "--set",
        "params.wisp_count=50",
        "--set",
        "params.wisp_texture_size=32",
        "--out",
        out.to_str().expect("utf-8 path"),
    ]);
    let stderr = text(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(out.exists());
    assert!(
        stderr.contains("note: geometry wisps: 50 wisps for 400 strands"),
        "{stderr}"
    );
    assert!(
        stderr.contains(
            "the groom has no guide strands: each follows the strand rooted at its centre"
        ),
        "{stderr}"
    );
}

/// The wisps' level of detail leaves wisps out on purpose, never silently:
/// far away (the groom spans ~0.39 of the screen; every wisp drawn only
/// from a full screen's height) a note says how many are drawn and how much
/// wider; with it off (`wisp_lod_screen_fraction = 0`) no such note.
#[test]
fn fewer_wisps_far_away_are_named_in_a_note() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("far.png");
    for (fraction, noted) in [("1", true), ("0", false)] {
        let run = plait(&[
            "render",
            "pipelines/forward.toml",
            "--scene",
            "tests/fixtures/golden_far.toml",
            "--size",
            "64x48",
            "--set",
            "techniques.geometry=wisps",
            "--set",
            "params.wisp_count=100",
            "--set",
            "params.wisp_texture_size=32",
            "--set",
            &format!("params.wisp_lod_screen_fraction={fraction}"),
            "--out",
            out.to_str().expect("utf-8 path"),
        ]);
        let stderr = text(&run.stderr);
        assert!(run.status.success(), "{stderr}");
        let note =
            "note: geometry wisps: 39 of 100 wisps drawn from the camera, each 2.56× as wide";
        assert_eq!(stderr.contains(note), noted, "{fraction}: {stderr}");
        assert_eq!(
            stderr.contains("wisps drawn from the camera"),
            noted,
            "{fraction}: {stderr}"
        );
    }
}

/// Bad wisp params: one error each, naming the param (or the texture the
/// size makes, with the adapter's limit), exit 2, no image.
#[test]
fn bad_wisp_params_are_one_error_naming_the_param() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("bad.png");
    for (flag, says) in [
        ("params.wisp_count=0", "param `wisp_count` of passes"),
        ("params.wisp_count=5000", "param `wisp_count` of passes"),
        ("params.wisp_width=0", "param `wisp_width` of passes"),
        (
            "params.wisp_lod_screen_fraction=1.5",
            "param `wisp_lod_screen_fraction` of passes",
        ),
        (
            "params.wisp_lod_screen_fraction=-0.1",
            "param `wisp_lod_screen_fraction` of passes",
        ),
        ("params.wisp_texture_size=40000", "wisp_texture"),
    ] {
        let run = plait(&[
            "render",
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            "64x48",
            "--set",
            "techniques.geometry=wisps",
            "--set",
            flag,
            "--out",
            out.to_str().expect("utf-8 path"),
        ]);
        let stderr = text(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{flag}: {stderr}");
        assert!(!out.exists(), "no image for a refused render");
        assert_eq!(stderr.matches("error:").count(), 1, "{flag}: {stderr}");
        assert!(stderr.contains(says), "{flag}: {stderr}");
    }
}
