//! `plait ab` end to end through the binary (issue 6, issue 10): the report
//! directory, identical pipelines compare as identical, a sweep gives one
//! row per value, two sweeps a grid, bad input exits 2. The run itself is
//! tested in-process in `crates/plait/tests/ab.rs`.

mod common;
use common::{plait, text};

use std::path::Path;

fn read_json(dir: &Path) -> serde_json::Value {
    let bytes = std::fs::read(dir.join("report.json")).expect("report.json");
    serde_json::from_slice(&bytes).expect("valid JSON")
}

#[test]
fn forward_against_itself_is_identical_and_report_is_complete() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("report");
    let o = plait(&[
        "ab",
        "pipelines/forward.toml",
        "--reference",
        "pipelines/forward.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "128x96",
        "--repeats",
        "2",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(
        o.status.success(),
        "stderr: {}\nstdout: {}",
        text(&o.stderr),
        text(&o.stdout)
    );
    // Not a terminal: plain progress lines.
    assert!(text(&o.stdout).contains("[1/"), "{}", text(&o.stdout));
    let html = std::fs::read_to_string(out.join("report.html")).expect("report.html");
    assert!(html.contains("<svg") && html.contains("flip") && html.contains("Provenance"));
    // Provenance names each file once: hair_shade.wgsl serves six pass types,
    // forward.toml is both the variant and the reference.
    assert_eq!(
        html.matches("<code>shaders/passes/hair_shade.wgsl").count(),
        1,
        "hair_shade.wgsl listed more than once"
    );
    assert_eq!(
        html.matches("<code>pipelines/forward.toml ").count(),
        1,
        "forward.toml listed more than once"
    );
    assert!(
        !html.contains("<script src") && !html.contains("<link "),
        "self-contained"
    );
    let v = read_json(&out);
    assert_eq!(v["schema"], "plait-ab/2");
    let variants = v["variants"].as_array().expect("variants");
    assert_eq!(variants.len(), 2, "the variant and the reference");
    assert_eq!(
        variants
            .iter()
            .filter(|x| x["is_reference"] == true)
            .count(),
        1
    );
    assert!(
        variants
            .iter()
            .all(|x| x["memory"]["peak_bytes"].as_u64().unwrap_or(0) > 0)
    );
    assert!(variants.iter().all(|x| {
        !x["memory"]["resources"]
            .as_array()
            .expect("resources")
            .is_empty()
    }));
    let scenes = v["scenes"].as_array().expect("scenes");
    assert_eq!(scenes.len(), 1);
    let runs = scenes[0]["runs"].as_array().expect("runs");
    assert_eq!(runs.len(), 2);
    for run in runs {
        let m = &run["metrics"];
        assert_eq!(m["rmse"].as_f64(), Some(0.0), "{run}");
        assert!(m["psnr_db"].is_null(), "identical images: infinite PSNR");
        assert!((m["ssim"].as_f64().expect("ssim") - 1.0).abs() < 1e-9);
        assert!(m["flip_mean"].as_f64().expect("flip").abs() < 1e-6);
        // forward.toml self-shadows with the modified shadow map: probed, and
        // identical to itself.
        let vis = &run["visibility"];
        assert_eq!(vis["provider"], "modified_shadow_map", "{vis}");
        assert_eq!(vis["mean_abs_error"].as_f64(), Some(0.0), "{vis}");
        assert!(
            vis["curves"].as_array().is_some_and(|c| !c.is_empty()),
            "{vis}"
        );
        assert_eq!(
            run["timing"]["wall_ms"]["samples"]
                .as_array()
                .expect("samples")
                .len(),
            2
        );
        for key in ["image", "diff_image", "flip_image"] {
            let name = run[key].as_str().expect("file name");
            assert!(out.join(name).is_file(), "{name}");
            if run["variant"] != "reference" {
                assert!(html.contains(name), "{name} not in report.html");
            }
        }
        if !run["timing"]["total_gpu_ms"].is_null() {
            assert_eq!(
                run["timing"]["total_gpu_ms"]["samples"]
                    .as_array()
                    .expect("samples")
                    .len(),
                2
            );
            assert!(
                !run["timing"]["passes"]
                    .as_array()
                    .expect("passes")
                    .is_empty()
            );
        }
    }
    assert!(
        out.join(scenes[0]["reference_image"].as_str().expect("ref"))
            .is_file()
    );
    let p = &v["provenance"];
    assert_eq!(p["plait_version"], env!("CARGO_PKG_VERSION"));
    assert!(p["adapter"]["name"].as_str().is_some_and(|s| !s.is_empty()));
    assert!(
        p["command_line"]
            .as_str()
            .expect("command")
            .contains("--repeats 2")
    );
    let pipelines = p["pipelines"].as_array().expect("pipelines");
    assert!(
        pipelines[0]["files"][0]["sha256"]
            .as_str()
            .expect("hash")
            .len()
            == 64
    );
    assert!(
        !pipelines[0]["shaders"]
            .as_array()
            .expect("shaders")
            .is_empty()
    );
    assert!(!p["builtin_shaders"].as_array().expect("builtin").is_empty());
    // No temporary directory left beside the report.
    let leftovers: Vec<_> = std::fs::read_dir(tmp.path())
        .expect("list")
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with(".plait-ab"))
        .collect();
    assert!(leftovers.is_empty());
}

#[test]
fn sweep_gives_one_row_per_value() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("sweep");
    let o = plait(&[
        "ab",
        "pipelines/forward.toml",
        "--reference",
        "pipelines/forward.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "64x48",
        "--repeats",
        "1",
        "--sweep",
        "params.hair_density=10,40",
        "--set",
        "params.light_size=256",
        // The reference at one of the sweep's values (forward.toml's own is 264.2).
        "--set",
        "params.hair_density=40",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "stderr: {}", text(&o.stderr));
    let v = read_json(&out);
    assert_eq!(v["sweeps"][0]["key"], "params.hair_density");
    assert_eq!(v["sweeps"].as_array().map(Vec::len), Some(1));
    let variants = v["variants"].as_array().expect("variants");
    assert_eq!(variants.len(), 3, "two sweep rows and the reference");
    let values: Vec<_> = variants
        .iter()
        .filter(|x| x["is_reference"] == false)
        .map(|x| x["sweep_values"]["params.hair_density"].clone())
        .collect();
    assert_eq!(values, [serde_json::json!("10"), serde_json::json!("40")]);
    let runs = v["scenes"][0]["runs"].as_array().expect("runs");
    assert_eq!(runs.len(), 3);
    // density 40 is the reference's own value: identical; 10 differs.
    let by = |id: &str| {
        runs.iter()
            .find(|r| r["variant"] == id)
            .expect("run")
            .clone()
    };
    assert_eq!(by("forward@40")["metrics"]["rmse"].as_f64(), Some(0.0));
    assert!(by("forward@10")["metrics"]["rmse"].as_f64().expect("rmse") > 0.0);
    let html = std::fs::read_to_string(out.join("report.html")).expect("html");
    assert!(html.contains("vs params.hair_density"), "sweep curves");
}

/// `--sweep` twice: every combination, rows = the first key's values,
/// columns = the second's, in one report.
#[test]
fn two_sweeps_make_a_grid() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("grid");
    let o = plait(&[
        "ab",
        "pipelines/forward.toml",
        "--reference",
        "pipelines/forward.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "64x48",
        "--repeats",
        "1",
        "--sweep",
        "params.hair_density=10,40",
        "--sweep",
        "params.light_size=128,256",
        "--set",
        "params.light_size=256",
        // The reference at one of the sweep's values (forward.toml's own is 264.2).
        "--set",
        "params.hair_density=40",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "stderr: {}", text(&o.stderr));
    let v = read_json(&out);
    let keys: Vec<_> = v["sweeps"]
        .as_array()
        .expect("sweeps")
        .iter()
        .map(|s| s["key"].clone())
        .collect();
    assert_eq!(keys, ["params.hair_density", "params.light_size"]);
    let ids: Vec<_> = v["variants"]
        .as_array()
        .expect("variants")
        .iter()
        .map(|x| x["id"].as_str().expect("id").to_string())
        .collect();
    assert_eq!(
        ids,
        [
            "forward@10@128",
            "forward@10@256",
            "forward@40@128",
            "forward@40@256",
            "reference"
        ]
    );
    assert_eq!(
        v["variants"][1]["sweep_values"]["params.hair_density"],
        "10"
    );
    assert_eq!(v["variants"][1]["sweep_values"]["params.light_size"], "256");
    // The grid point with the reference's own values renders the reference.
    let rmse = |id: &str| {
        v["scenes"][0]["runs"]
            .as_array()
            .expect("runs")
            .iter()
            .find(|r| r["variant"] == id)
            .and_then(|r| r["metrics"]["rmse"].as_f64())
            .expect("rmse")
    };
    assert_eq!(rmse("forward@40@256"), 0.0);
    assert!(rmse("forward@10@128") > 0.0);
    let html = std::fs::read_to_string(out.join("report.html")).expect("html");
    assert!(
        html.contains("params.hair_density (rows) × params.light_size (columns)"),
        "grid tables"
    );
    assert!(html.contains(
        "<th class=l>params.hair_density \\ params.light_size</th><th>128</th><th>256</th>"
    ));
    assert!(
        html.contains("ꟻLIP mean vs params.hair_density"),
        "sweep curves"
    );
}

#[test]
fn bad_input_exits_2_naming_the_flag_or_file() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("r");
    let out = out.to_str().expect("utf-8");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "ab",
                "pipelines/nope.toml",
                "--reference",
                "pipelines/forward.toml",
                "--out",
                out,
            ],
            "nope.toml",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/missing.toml",
                "--out",
                out,
            ],
            "--reference",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--sweep",
                "params.x",
                "--out",
                out,
            ],
            "--sweep",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--sweep",
                "params.x=1,,2",
                "--out",
                out,
            ],
            "--sweep",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--size",
                "0x3",
                "--out",
                out,
            ],
            "--size",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--repeats",
                "0",
                "--out",
                out,
            ],
            "--repeats",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--out",
                "/proc/plait-cannot-write/r",
            ],
            "--out",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--out",
                "Cargo.toml",
            ],
            "--out",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--sweep",
                "params.no_such_param_anywhere.x=1,2",
                "--out",
                out,
            ],
            "--sweep",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--scene",
                "nope.toml",
                "--out",
                out,
            ],
            "nope.toml",
        ),
        (
            vec!["ab", "--reference", "pipelines/forward.toml", "--out", out],
            "PIPELINE",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--sweep",
                "params.a=1,2",
                "--sweep",
                "params.b=1,2",
                "--sweep",
                "params.c=1,2",
                "--out",
                out,
            ],
            "at most two sweeps",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--sweep",
                "params.light_size=128",
                "--sweep",
                "params.light_size=256",
                "--out",
                out,
            ],
            "--sweep params.light_size: the key is swept twice",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--sweep",
                "params.light_size=128,256",
                "--sweep",
                "params.light_sise=1,2",
                "--out",
                out,
            ],
            "(--sweep params.light_size=128 --sweep params.light_sise=1)",
        ),
        (
            vec![
                "ab",
                "pipelines/forward.toml",
                "--reference",
                "pipelines/forward.toml",
                "--repeats",
                "2",
                "--reference-repeats",
                "3",
                "--out",
                out,
            ],
            "--reference-repeats 3",
        ),
    ];
    for (args, needle) in cases {
        let o = plait(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o.stderr));
        assert!(
            text(&o.stderr).contains(needle),
            "{args:?}: stderr does not name {needle}: {}",
            text(&o.stderr)
        );
        assert!(!Path::new(out).exists(), "{args:?} left a report behind");
    }
}

/// Technique keys sweep like any other: a self-shadowing × transparency grid
/// in one report, whose point equal to the reference renders it exactly.
#[test]
fn technique_sweeps_make_a_grid() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("grid");
    let o = plait(&[
        "ab",
        "pipelines/occupancy.toml",
        "--reference",
        "pipelines/reference.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "48x36",
        "--repeats",
        "1",
        "--sweep",
        "techniques.self_shadow=deep_opacity,exact",
        "--sweep",
        "techniques.transparency=weighted_average,depth_peeling",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "stderr: {}", text(&o.stderr));
    // The terminal table has the HTML report's |ΔV| column (the variants'
    // self-shadowing differs from the reference's), and one repeat is one.
    let stdout = text(&o.stdout);
    let header = stdout
        .lines()
        .find(|l| l.starts_with("variant "))
        .expect("a table");
    assert!(header.contains("mean / max |ΔV|"), "{stdout}");
    let md = std::fs::read_to_string(out.join("report.md")).expect("report.md");
    assert!(md.contains("(1 repeat,"), "{md}");
    let v = read_json(&out);
    let runs = v["scenes"][0]["runs"].as_array().expect("runs");
    assert_eq!(runs.len(), 5, "2 × 2 grid + the reference");
    let rmse = |self_shadow: &str, transparency: &str| {
        let variant = v["variants"]
            .as_array()
            .expect("variants")
            .iter()
            .find(|x| {
                x["sweep_values"]["techniques.self_shadow"] == self_shadow
                    && x["sweep_values"]["techniques.transparency"] == transparency
            })
            .expect("grid point");
        runs.iter()
            .find(|r| r["variant"] == variant["id"])
            .and_then(|r| r["metrics"]["rmse"].as_f64())
            .expect("rmse")
    };
    assert_eq!(
        rmse("exact", "depth_peeling"),
        0.0,
        "the reference's own choices"
    );
    assert!(rmse("deep_opacity", "weighted_average") > 0.0);
}

/// `--supersample N`: the reference rendered N × N times larger and filtered
/// down to `--size`, so strand coverage can be measured against the truth of
/// anti-aliasing; coverage is closer to it than one-pixel lines. Out of
/// range: exit 2 naming the flag.
#[test]
fn supersampled_reference_measures_strand_coverage() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("coverage");
    let o = plait(&[
        "ab",
        "pipelines/forward.toml",
        "--reference",
        "pipelines/forward.toml",
        "--supersample",
        "4",
        "--sweep",
        "params.strand_coverage=true,false",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "64x48",
        "--repeats",
        "2",
        "--reference-repeats",
        "1",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "stderr: {}", text(&o.stderr));
    let v = read_json(&out);
    // The slow reference is timed once, the variants twice.
    let timed = |id: &str| {
        v["scenes"][0]["runs"]
            .as_array()
            .expect("runs")
            .iter()
            .find(|r| r["variant"] == id)
            .and_then(|r| r["timing"]["wall_ms"]["samples"].as_array())
            .map_or(0, Vec::len)
    };
    assert_eq!(
        (timed("reference"), timed("forward@true")),
        (1, 2),
        "{}",
        v["scenes"][0]
    );
    assert_eq!(v["provenance"]["reference_repeats"], 1);
    let reference = v["variants"]
        .as_array()
        .expect("variants")
        .iter()
        .find(|x| x["is_reference"] == true)
        .expect("reference")
        .clone();
    assert!(
        reference["label"]
            .as_str()
            .is_some_and(|l| l.contains("4× supersampled")),
        "{reference}"
    );
    let image = image::open(out.join("small-reference.png")).expect("reference image");
    assert_eq!(
        (image.width(), image.height()),
        (64, 48),
        "filtered down to --size"
    );
    let runs = v["scenes"][0]["runs"].as_array().expect("runs");
    let rmse = |id: &str| {
        runs.iter()
            .find(|r| r["variant"] == id)
            .and_then(|r| r["metrics"]["rmse"].as_f64())
            .unwrap_or_else(|| panic!("no rmse for {id}: {runs:?}"))
    };
    assert!(
        rmse("forward@true") < rmse("forward@false"),
        "coverage {} should be closer to the supersampled reference than none {}",
        rmse("forward@true"),
        rmse("forward@false")
    );

    let bad = plait(&[
        "ab",
        "pipelines/forward.toml",
        "--reference",
        "pipelines/forward.toml",
        "--supersample",
        "0",
        "--out",
        tmp.path().join("bad").to_str().expect("utf-8"),
    ]);
    assert_eq!(bad.status.code(), Some(2), "stderr: {}", text(&bad.stderr));
    assert!(
        text(&bad.stderr).contains("--supersample"),
        "{}",
        text(&bad.stderr)
    );
    assert!(!tmp.path().join("bad").exists(), "nothing written");
}
