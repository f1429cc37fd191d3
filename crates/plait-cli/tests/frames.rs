//! `plait render --frames`: a sequence of PNGs, an animated PNG preview and
//! frames.json, all or nothing; bad keyframes and flags exit 2 and leave
//! nothing behind.

mod common;

use common::{plait, root, text};
use std::path::Path;

/// Files and folders in `dir` (hidden temporaries included).
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("list")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_sequence_writes_every_frame_a_preview_and_medians() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("seq");
    let o = plait(&[
        "render",
        "--scene",
        "examples/scenes/head_turn.toml",
        "--frames",
        "4",
        "--fps",
        "2",
        "--size",
        "64x48",
        "--set",
        "params.light_size=128",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    let stdout = text(&o.stdout);
    assert!(o.status.success(), "{}{stdout}", text(&o.stderr));
    assert!(stdout.contains("median frame"), "{stdout}");
    assert!(
        stdout.contains("medians over 4 frames at 2 fps"),
        "{stdout}"
    );
    assert_eq!(
        entries(&out),
        [
            "0000.png",
            "0001.png",
            "0002.png",
            "0003.png",
            "animation.png",
            "frames.json"
        ]
    );
    assert_eq!(entries(dir.path()), ["seq"], "no temporaries left");
    // The preview is an animated PNG of 4 frames, 500 ms each.
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(out.join("animation.png")).expect("open"),
    ));
    let mut reader = decoder.read_info().expect("a PNG");
    let animation = reader.info().animation_control.expect("an APNG");
    assert_eq!(animation.num_frames, 4);
    let mut frames = 0;
    let mut buffer = vec![0; reader.output_buffer_size().expect("size")];
    while let Ok(info) = reader.next_frame(&mut buffer) {
        assert_eq!((info.width, info.height), (64, 48));
        frames += 1;
    }
    assert_eq!(frames, 4);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("frames.json")).expect("read"))
            .expect("JSON");
    let per_frame = json["sequence"]["per_frame"].as_array().expect("per_frame");
    assert_eq!(per_frame.len(), 4);
    assert_eq!(per_frame[3]["time"], 1.5);
    assert!(
        json["total_gpu_ms"].as_f64().is_some_and(|ms| ms > 0.0),
        "{json}"
    );
    // The turned frame (1 s) differs from the first.
    let image = |name: &str| image::open(out.join(name)).expect(name).to_rgba8();
    assert_ne!(image("0000.png"), image("0002.png"));
}

#[test]
fn bad_keyframes_fail_at_their_line_and_column_and_write_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = std::fs::read_to_string(root().join("examples/scenes/head_turn.toml"))
        .expect("head_turn.toml");
    let bad = scene.replacen("time = 2.0", "time = 0.5", 1);
    let line = bad
        .lines()
        .position(|l| l == "time = 0.5")
        .expect("the edited key")
        + 1;
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, bad).expect("write");
    let out = dir.path().join("seq");
    let o = plait(&[
        "render",
        "--scene",
        path.to_str().expect("utf-8"),
        "--frames",
        "2",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(&format!("bad.toml:{line}:8: animation.keys[2].time is 0.5")),
        "{stderr}"
    );
    assert_eq!(entries(dir.path()), ["bad.toml"], "nothing written");
}

#[test]
fn flags_of_a_sequence_are_checked_before_any_work() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("seq.png");
    for (args, needle) in [
        (
            vec!["--frames", "2", "--out", file.to_str().expect("utf-8")],
            "with --frames, --out is a folder",
        ),
        (vec!["--frames", "2", "--fps", "0"], "frames per second"),
        (vec!["--frames", "0"], "--frames"),
        (vec!["--fps", "24"], "--frames"),
        (
            vec!["--frames", "2", "--set", "params.light_sise=1"],
            "light_sise",
        ),
    ] {
        let mut all = vec!["render", "--size", "32x24"];
        all.extend(&args);
        let o = plait(&all);
        let stderr = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    }
    assert!(entries(dir.path()).is_empty(), "nothing written");
    assert!(!root().join("frames").exists(), "no default folder left");
}

#[test]
fn ab_with_frames_reports_flicker() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("report");
    let o = plait(&[
        "ab",
        "pipelines/deep_opacity.toml",
        "--reference",
        "pipelines/occupancy.toml",
        "--scene",
        "examples/scenes/head_turn.toml",
        "--frames",
        "2",
        "--fps",
        "4",
        "--size",
        "48x36",
        "--repeats",
        "1",
        "--set",
        "params.light_size=128",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let markdown = std::fs::read_to_string(out.join("report.md")).expect("report.md");
    assert!(
        markdown.contains("| image flicker | visibility flicker |"),
        "{markdown}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).expect("json"))
            .expect("JSON");
    let temporal = &json["scenes"][0]["runs"][0]["temporal"];
    assert_eq!(temporal["frames"], 2, "{temporal}");
    assert_eq!(temporal["fps"], 4.0);
    // The head turns between the two frames: the image changes.
    assert!(
        temporal["image_change_mean"]
            .as_f64()
            .is_some_and(|c| c > 0.0),
        "{temporal}"
    );
}
