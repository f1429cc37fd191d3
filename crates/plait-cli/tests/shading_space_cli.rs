//! Strand-space shading's count of shading points from the command line:
//! 0, or more than the scene's strands have points, exits 2 with an error
//! naming the param and the flag, and writes no image.

mod common;
use common::{plait, text};

#[test]
fn shading_points_out_of_range_exit_2_naming_the_param_and_flag() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("out.png");
    // The small scene's strands have 17 points.
    for points in ["0", "18"] {
        let flag = format!("params.shading_points={points}");
        let o = plait(&[
            "render",
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            "64x48",
            "--set",
            "techniques.shading_space=strand",
            "--set",
            &flag,
            "--out",
            png.to_str().expect("utf-8 path"),
        ]);
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "shading_points={points}: {err}");
        assert!(
            err.contains(&format!("--set {flag}")) && err.contains("`shading_points`"),
            "shading_points={points}: the error names neither the flag nor the param:\n{err}"
        );
        assert!(!png.exists(), "shading_points={points} wrote an image");
    }
}

/// The technique's default K (16) is more than the mesh_head groom's
/// strands have points (13): the user never chose it, so it is fitted to
/// the scene with a note; the same value given by a flag stays an error.
#[test]
fn default_shading_points_fit_the_scene_but_a_set_value_does_not() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("out.png");
    let out = png.to_str().expect("utf-8 path");
    let mut args = vec![
        "render",
        "--scene",
        "examples/scenes/mesh_head.toml",
        "--size",
        "160x120",
        "--set",
        "techniques.shading_space=strand",
        "--out",
        out,
    ];
    let o = plait(&args);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "the default did not fit:\n{err}");
    assert!(
        err.contains("note: shading_points = 13 (the technique's default 16"),
        "no note says the default was fitted:\n{err}"
    );
    assert!(png.exists(), "no image written");
    std::fs::remove_file(&png).expect("remove image");

    args.extend(["--set", "params.shading_points=64"]);
    let o = plait(&args);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "a set value was fitted:\n{err}");
    assert!(
        err.contains("error: --set params.shading_points=64: param `shading_points`")
            && err.contains("must be at most 13"),
        "the error does not start with the flag:\n{err}"
    );
    assert!(!png.exists(), "a refused render wrote an image");
}
