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
