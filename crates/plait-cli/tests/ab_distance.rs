//! `plait ab --camera-distance` and the camera dolly (issue 23, the
//! measurement part): each scene seen from each distance, the reference
//! too; a row per distance in the report; the level of detail's error is
//! not the same at every distance; a dollying scene runs under `--frames`;
//! a bad factor (flag or scene key) is an error naming it, exit 2.

mod common;
use common::{plait, root, text};

use std::path::Path;

fn read_json(dir: &Path) -> serde_json::Value {
    let bytes = std::fs::read(dir.join("report.json")).expect("report.json");
    serde_json::from_slice(&bytes).expect("valid JSON")
}

/// `(factor, ꟻLIP mean)` of variant `id` on every scene of the report.
fn flip_by_distance(json: &serde_json::Value, id: &str) -> Vec<(f64, f64)> {
    json["scenes"]
        .as_array()
        .expect("scenes")
        .iter()
        .map(|scene| {
            let factor = scene["distance"]["factor"].as_f64().expect("factor");
            let run = scene["runs"]
                .as_array()
                .expect("runs")
                .iter()
                .find(|r| r["variant"] == id)
                .unwrap_or_else(|| panic!("no run of {id}"));
            (factor, run["metrics"]["flip_mean"].as_f64().expect("flip"))
        })
        .collect()
}

#[test]
fn a_distance_sweep_has_a_row_per_distance_and_the_lod_error_moves() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("report");
    let o = plait(&[
        "ab",
        "pipelines/forward.toml",
        "--sweep",
        "techniques.geometry=strands,lod",
        "--reference",
        "pipelines/forward.toml",
        "--supersample",
        "2",
        "--camera-distance",
        "1,4",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "64x48",
        "--repeats",
        "1",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(
        o.status.success(),
        "stderr: {}\nstdout: {}",
        text(&o.stderr),
        text(&o.stdout)
    );
    let json = read_json(&out);
    assert_eq!(json["camera_distances"], serde_json::json!([1.0, 4.0]));
    let names: Vec<&str> = json["scenes"]
        .as_array()
        .expect("scenes")
        .iter()
        .map(|s| s["name"].as_str().expect("name"))
        .collect();
    assert_eq!(names, ["small@d1", "small@d4"]);
    // The reference is seen from each distance too: its images differ.
    let reference = |name: &str| {
        image::open(out.join(format!("{name}-reference.png")))
            .expect("reference image")
            .to_rgba8()
    };
    assert_ne!(reference("small@d1"), reference("small@d4"));

    let strands = flip_by_distance(&json, "forward@strands");
    let lod = flip_by_distance(&json, "forward@lod");
    // Far away the level of detail leaves strands out: more error than all
    // strands against the same supersampled reference, and not the error
    // it has near, where it draws every strand.
    assert!(
        lod[1].1 > strands[1].1,
        "lod {lod:?} vs strands {strands:?}"
    );
    assert!(
        (lod[1].1 - lod[0].1).abs() > 1e-4,
        "lod's error is the same at every distance: {lod:?}"
    );

    // report.md: a table with a row per distance, columns per variant.
    let md = std::fs::read_to_string(out.join("report.md")).expect("report.md");
    let header = md
        .lines()
        .find(|l| l.starts_with("| distance |"))
        .unwrap_or_else(|| panic!("no distance table:\n{md}"));
    assert!(
        header.contains(" forward@lod ꟻLIP |")
            && header.contains(" forward@strands ꟻLIP |")
            && header.contains(" reference "),
        "{header}"
    );
    let rows: Vec<&str> = md
        .lines()
        .filter(|l| l.starts_with("| 1× |") || l.starts_with("| 4× |"))
        .collect();
    assert_eq!(rows.len(), 2, "{md}");
    let html = std::fs::read_to_string(out.join("report.html")).expect("report.html");
    assert!(html.contains("<h2>Camera distance</h2>"));
    assert!(html.contains("small: error vs camera distance"));
    assert!(html.contains("small: frame time vs camera distance"));
}

#[test]
fn bad_camera_distances_exit_2_naming_the_flag() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("report");
    for bad in ["0", "-1", "nan", "inf", "1,1", "1,x", "1,,2", "101"] {
        let flag = format!("--camera-distance={bad}");
        let o = plait(&[
            "ab",
            "pipelines/forward.toml",
            "--reference",
            "pipelines/forward.toml",
            &flag,
            "--size",
            "64x48",
            "--out",
            out.to_str().expect("utf-8"),
        ]);
        let stderr = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{bad}: {stderr}");
        assert!(stderr.contains("--camera-distance"), "{bad}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(!out.exists(), "{bad}: no report for a bad flag");
    }
}

#[test]
fn a_bad_camera_distance_key_names_its_line_and_column() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let scene = std::fs::read_to_string(root().join("examples/scenes/dolly.toml"))
        .expect("dolly.toml")
        .replace("camera_distance = 6.0", "camera_distance = -6.0")
        .replace("\"smooth\"", "\"linear\"");
    let path = tmp.path().join("bad_dolly.toml");
    std::fs::write(&path, &scene).expect("write scene");
    let line = scene
        .lines()
        .position(|l| l.starts_with("camera_distance = -6.0"))
        .expect("the line")
        + 1;
    let o = plait(&[
        "ab",
        "pipelines/forward.toml",
        "--reference",
        "pipelines/forward.toml",
        "--scene",
        path.to_str().expect("utf-8"),
        "--size",
        "64x48",
        "--out",
        tmp.path().join("report").to_str().expect("utf-8"),
    ]);
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(&format!("bad_dolly.toml:{line}:19")),
        "line:column of the value: {stderr}"
    );
    assert!(
        stderr.contains("animation.keys[1].camera_distance") && stderr.contains("> 0"),
        "{stderr}"
    );
}

/// The dollying scene under `--frames`: the camera moves back, the level of
/// detail leaves strands out as it goes, and its change beyond the
/// reference's own is measured (popping).
#[test]
fn frames_on_a_dolly_measure_the_lod_against_the_reference() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("report");
    let o = plait(&[
        "ab",
        "pipelines/forward.toml",
        "--sweep",
        "techniques.geometry=lod",
        "--reference",
        "pipelines/forward.toml",
        "--scene",
        "examples/scenes/dolly.toml",
        "--frames",
        "4",
        "--fps",
        "4",
        "--size",
        "64x48",
        // The reference's frames are supersampled and filtered down like
        // its still image (they were once compared at twice the size).
        "--supersample",
        "2",
        "--repeats",
        "1",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(
        o.status.success(),
        "stderr: {}\nstdout: {}",
        text(&o.stderr),
        text(&o.stdout)
    );
    let json = read_json(&out);
    let runs = json["scenes"][0]["runs"].as_array().expect("runs");
    let flicker = |id: &str| {
        let run = runs.iter().find(|r| r["variant"] == id).expect("run");
        run["temporal"]["image_flicker_mean"]
            .as_f64()
            .expect("temporal")
    };
    assert_eq!(flicker("reference"), 0.0);
    assert!(
        flicker("forward@lod") > 0.0,
        "the lod changes beyond the reference as the camera backs off"
    );
}
