//! `renderer = "plait"` in a path-traced reference: plait's own GPU path
//! tracer renders the reference of `plait ab` with no Mitsuba at all, its
//! image the mean of the file's two seeds exactly as `plait render` of the
//! path tracer's pipeline gives them; values only Mitsuba takes are refused
//! at file:line:col.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::{root, text};

fn reference_file(dir: &Path, name: &str, body: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, format!("[path_traced]\n{body}")).unwrap();
    path
}

/// `plait` with Mitsuba made unreachable: a run that needed it would fail.
fn plait_without_mitsuba(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .args(args)
        .env("PLAIT_MITSUBA_PYTHON", "/nonexistent/python")
        .output()
        .expect("run plait")
}

fn linear(path: &Path) -> image::Rgba32FImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .into_rgba32f()
}

#[test]
fn plait_path_traces_the_reference_as_the_mean_of_its_two_seeds() {
    let tmp = tempfile::tempdir().unwrap();
    let reference = reference_file(
        tmp.path(),
        "pt.toml",
        "renderer = \"plait\"\nspp = 4\nmax_depth = 8\nseeds = [3, 5]\nmax_noise_rmse = 1.0\n",
    );
    let out = tmp.path().join("r");
    let scene = ["--scene", "examples/scenes/small.toml", "--size", "32x24"];
    let mut args = vec!["ab", "pipelines/forward.toml", "--reference"];
    args.push(reference.to_str().unwrap());
    args.extend(scene);
    args.extend(["--repeats", "1", "--out", out.to_str().unwrap()]);
    let o = plait_without_mitsuba(&args);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let described = report["variants"]
        .as_array()
        .unwrap()
        .iter()
        .find(|v| v["is_reference"] == true)
        .expect("the reference")
        .clone();
    assert!(
        described["schedule_name"]
            .as_str()
            .is_some_and(|s| s.starts_with("plait ")),
        "{described}"
    );
    assert!(
        described["label"]
            .as_str()
            .is_some_and(|l| l.contains("plait's GPU path tracer") && l.contains("noise RMSE")),
        "{described}"
    );

    // Each seed as `plait render` makes it, averaged: the reference.
    let seeds: Vec<image::Rgba32FImage> = [3, 5]
        .iter()
        .map(|seed| {
            let exr = tmp.path().join(format!("seed{seed}.exr"));
            let seed_set = format!("params.seed={seed}");
            let mut args = vec!["render", "pipelines/physical/path_traced.toml"];
            args.extend(scene);
            args.extend(["--set", "params.spp=4", "--set", "params.max_depth=8"]);
            args.extend(["--set", &seed_set, "--out", exr.to_str().unwrap()]);
            let o = plait_without_mitsuba(&args);
            assert!(o.status.success(), "{}", text(&o.stderr));
            linear(&exr)
        })
        .collect();
    let got = linear(&out.join("small-reference.exr"));
    assert_eq!(got.dimensions(), (32, 24));
    let (mut largest, mut apart) = (0.0f32, 0.0f32);
    for ((p, a), b) in got.pixels().zip(seeds[0].pixels()).zip(seeds[1].pixels()) {
        for c in 0..3 {
            largest = largest.max((p.0[c] - 0.5 * (a.0[c] + b.0[c])).abs());
            apart = apart.max((a.0[c] - b.0[c]).abs());
        }
    }
    assert!(
        largest < 1e-6,
        "the reference is not the seeds' mean: {largest}"
    );
    // Two seeds, two images: the noise estimate measures something.
    assert!(apart > 1e-3, "seeds 3 and 5 rendered the same image");
}

#[test]
fn values_only_mitsuba_takes_are_refused_at_file_line_col() {
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        (
            "renderer = \"plaid\"\nspp = 4\nmax_depth = 8\nseeds = [0, 1]\nmax_noise_rmse = 1.0\n",
            "renderer.toml:2:12",
            "did you mean \"plait\"",
        ),
        (
            "renderer = \"plait\"\nspp = 4\nmax_depth = -1\nseeds = [0, 1]\nmax_noise_rmse = 1.0\n",
            "depth.toml:4:13",
            "max_depth from 1 to 64",
        ),
        (
            "renderer = \"plait\"\nspp = 5000\nmax_depth = 8\nseeds = [0, 1]\nmax_noise_rmse = 1.0\n",
            "spp.toml:3:7",
            "at most 4096 spp",
        ),
    ];
    for (body, place, message) in cases {
        let name = place.split(':').next().unwrap();
        let file = reference_file(tmp.path(), name, body);
        let out = tmp.path().join(format!("out-{name}"));
        let o = plait_without_mitsuba(&[
            "ab",
            "pipelines/forward.toml",
            "--reference",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
        assert!(
            stderr.contains(place) && stderr.contains(message),
            "{name}: wanted {place} and {message:?} in: {stderr}"
        );
        assert!(!out.exists(), "{name}: a report was written");
    }
}
