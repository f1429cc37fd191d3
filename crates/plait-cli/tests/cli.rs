//! `plait` end to end: every bad-input class of issue 2 exits with code 2, an
//! error naming the file with line and column (or the flag), no panic and no
//! output file; and the good paths of check, graph, passes and render --json.
//!
//! Bad pipeline fixtures live in `tests/fixtures/bad/` at the checkout root;
//! the offending line of each carries a `<- error` comment, and the test
//! checks that the error points at that line.

mod common;
use common::{plait, root, text};

use std::path::{Path, PathBuf};
use std::process::Output;

fn fixture(name: &str) -> PathBuf {
    root().join("tests/fixtures/bad").join(name)
}

/// 1-based number of the line carrying the `<- error` marker.
fn marked_line(path: &Path) -> usize {
    let source =
        std::fs::read_to_string(path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()));
    source
        .lines()
        .position(|l| l.contains("<- error"))
        .unwrap_or_else(|| panic!("{} has no `<- error` marker", path.display()))
        + 1
}

/// Exit code 2, no panic, stderr has an `error:` and every `expected` part;
/// nothing left in `dir` (no output, no `.plait-*` temporary file).
fn assert_fails(what: &str, o: &Output, expected: &[&str], dir: Option<&Path>) -> String {
    let stderr = text(&o.stderr);
    let context = format!(
        "{what}\n--- exit: {:?}\n--- stderr:\n{stderr}\n--- stdout:\n{}",
        o.status.code(),
        text(&o.stdout)
    );
    assert_eq!(o.status.code(), Some(2), "expected exit code 2: {context}");
    assert!(!stderr.contains("panicked"), "panicked: {context}");
    assert!(stderr.contains("error"), "no `error` on stderr: {context}");
    for e in expected {
        assert!(stderr.contains(e), "stderr lacks `{e}`: {context}");
    }
    if let Some(dir) = dir {
        let left: Vec<String> = std::fs::read_dir(dir)
            .expect("list output dir")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        assert!(
            left.is_empty(),
            "files left behind in the output directory: {left:?}: {context}"
        );
    }
    stderr
}

/// One bad pipeline file: `check`, `graph --out` and `render --out` all fail
/// at the marked line (of `marked`, the pipeline itself unless a shader is at
/// fault) and leave no file.
fn bad_pipeline(name: &str, message: &str, marked: &str) {
    let path = fixture(name);
    let marked_path = fixture(marked);
    let line = marked_line(&marked_path);
    let at = format!("{marked}:{line}:");
    let p = path.to_str().expect("utf-8 path");
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("out.png");
    let svg = dir.path().join("graph.svg");
    let scene = root().join("examples/scenes/small.toml");
    let runs: [(&str, Vec<&str>); 3] = [
        ("check", vec!["check", p]),
        (
            "graph",
            vec![
                "graph",
                p,
                "--format",
                "svg",
                "--out",
                svg.to_str().expect("utf-8"),
            ],
        ),
        (
            "render",
            vec![
                "render",
                p,
                "--scene",
                scene.to_str().expect("utf-8"),
                "--size",
                "64x48",
                "--out",
                png.to_str().expect("utf-8"),
            ],
        ),
    ];
    for (cmd, args) in runs {
        let o = plait(&args);
        let stderr = assert_fails(
            &format!("plait {cmd} {name}"),
            &o,
            &[message, &at],
            Some(dir.path()),
        );
        // file:line:column — the column is a number too.
        let after = &stderr[stderr.find(&at).expect("checked above") + at.len()..];
        assert!(
            after.starts_with(|c: char| c.is_ascii_digit()),
            "`{at}` is not followed by a column: {stderr}"
        );
    }
}

#[test]
fn toml_syntax_error() {
    bad_pipeline("syntax.toml", "TOML syntax error", "syntax.toml");
}

#[test]
fn unknown_pass_type() {
    bad_pipeline(
        "unknown_pass_type.toml",
        "unknown pass type `shadow_mapp`",
        "unknown_pass_type.toml",
    );
}

#[test]
fn unknown_param() {
    bad_pipeline(
        "unknown_param.toml",
        "has no param `bias`",
        "unknown_param.toml",
    );
}

/// A typo in the pipeline's own `[params]` key is refused at the user's
/// line, with the nearest name in use (issue 41).
#[test]
fn pipeline_param_typo() {
    bad_pipeline(
        "pipeline_param_typo.toml",
        "unknown param `shadow_wieght`: no chosen technique defines it and nothing uses `${shadow_wieght}`; did you mean `shadow_weight`?",
        "pipeline_param_typo.toml",
    );
}

/// A param of a technique the pipeline does not choose (the base file's
/// `shadow_weight` after `--set techniques.self_shadow=none`) is a note
/// naming the technique, not an error: a one-key swap must not fail on the
/// base file's tuning of the technique it swapped out.
#[test]
fn a_param_of_a_technique_not_chosen_is_a_note() {
    let o = plait(&[
        "check",
        "pipelines/occupancy.toml",
        "--set",
        "techniques.self_shadow=none",
    ]);
    let stdout = text(&o.stdout);
    assert_eq!(o.status.code(), Some(0), "{stdout}{}", text(&o.stderr));
    assert!(
        stdout.contains("note: pipelines/occupancy.toml:")
            && stdout.contains(
                "param `shadow_weight` is for self_shadow technique deep_opacity, which this pipeline does not choose"
            ),
        "{stdout}"
    );
}

/// `--set params.X` for a param of a technique not chosen fails naming the
/// flag, the technique and the flag that would choose it.
#[test]
fn a_set_for_a_technique_not_chosen_names_it() {
    let o = plait(&[
        "check",
        "pipelines/linked_list.toml",
        "--set",
        "params.order_slices=3",
    ]);
    assert_fails(
        "--set params.order_slices on linked_list",
        &o,
        &[
            "--set params.order_slices=3: there is no param `order_slices`",
            "`order_slices` is for transparency technique occupancy_order, which this pipeline does not choose (choose it with --set techniques.transparency=occupancy_order)",
        ],
        None,
    );
}

#[test]
fn resource_read_but_never_written() {
    bad_pipeline(
        "never_written.toml",
        "resource `a` is read by pass `copy` but no pass writes it",
        "never_written.toml",
    );
}

#[test]
fn a_run_once_output_with_a_second_writer() {
    bad_pipeline(
        "run_once_second_writer.toml",
        "only that pass may write it",
        "run_once_second_writer.toml",
    );
}

#[test]
fn a_misspelt_run_suggests_once() {
    bad_pipeline("run_every.toml", "did you mean `once`", "run_every.toml");
}

#[test]
fn resource_written_by_two_unordered_passes() {
    bad_pipeline(
        "unordered_writers.toml",
        "with no order between them",
        "unordered_writers.toml",
    );
}

#[test]
fn cycle() {
    bad_pipeline("cycle.toml", "cycle between passes", "cycle.toml");
}

#[test]
fn writer_reader_format_mismatch() {
    bad_pipeline(
        "format_mismatch.toml",
        "accepts depth32float",
        "format_mismatch.toml",
    );
}

#[test]
fn undefined_param() {
    bad_pipeline(
        "undefined_param.toml",
        "`${side}` is not defined",
        "undefined_param.toml",
    );
}

#[test]
fn wgsl_that_does_not_parse() {
    // The pipeline line naming the shader, and naga's diagnostic with the shader's file and line.
    bad_pipeline("wgsl_parse.toml", "wgsl_parse.toml", "wgsl_parse.toml");
    bad_pipeline("wgsl_parse.toml", "wgsl_parse.wgsl", "wgsl_parse.wgsl");
}

#[test]
fn wgsl_that_does_not_validate() {
    bad_pipeline(
        "wgsl_validate.toml",
        "wgsl_validate.toml",
        "wgsl_validate.toml",
    );
    bad_pipeline(
        "wgsl_validate.toml",
        "wgsl_validate.wgsl",
        "wgsl_validate.wgsl",
    );
}

#[test]
fn shader_binding_not_provided() {
    bad_pipeline(
        "missing_binding.toml",
        "shader binding `src`",
        "missing_binding.toml",
    );
}

#[test]
fn texture_larger_than_the_limit() {
    let set = "params.light_size=100000";
    // Without a GPU, against WebGPU's default limit 8192.
    let o = plait(&["check", "pipelines/forward.toml", "--set", set]);
    assert_fails(
        "plait check --set light_size=100000",
        &o,
        &["opaque_shadow", "100000", "8192"],
        None,
    );
    // On the GPU: an error naming the resource and a limit, no file.
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("big.png");
    let o = plait(&[
        "render",
        "pipelines/forward.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "64x48",
        "--set",
        set,
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    let stderr = assert_fails(
        "plait render --set light_size=100000",
        &o,
        &["opaque_shadow", "100000", "limit"],
        Some(dir.path()),
    );
    assert!(
        stderr.contains(set) || stderr.contains("forward.toml:"),
        "error does not point at the flag or the file: {stderr}"
    );
}

#[test]
fn malformed_set() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    // A value that starts like structured TOML (`[1,`) must parse; a bare word
    // would be taken as a string.
    for bad in ["no_equals_sign", "=5", "params.light_size=[1,"] {
        let o = plait(&["check", "pipelines/forward.toml", "--set", bad]);
        assert_fails(
            &format!("plait check --set {bad}"),
            &o,
            &["--set", bad],
            None,
        );
        let o = plait(&[
            "render",
            "pipelines/forward.toml",
            "--size",
            "64x48",
            "--set",
            bad,
            "--out",
            png.to_str().expect("utf-8"),
        ]);
        assert_fails(
            &format!("plait render --set {bad}"),
            &o,
            &["--set", bad],
            Some(dir.path()),
        );
    }
}

#[test]
fn unwritable_output_path() {
    let o = plait(&[
        "render",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "64x48",
        "--out",
        "/nonexistent-dir/x.png",
    ]);
    assert_fails(
        "plait render --out /nonexistent-dir/x.png",
        &o,
        &["--out", "/nonexistent-dir/x.png"],
        None,
    );
    assert!(!Path::new("/nonexistent-dir").exists());
    // A directory is not a file either.
    let dir = tempfile::tempdir().expect("tempdir");
    let o = plait(&[
        "render",
        "--size",
        "64x48",
        "--out",
        dir.path().to_str().expect("utf-8"),
    ]);
    assert_fails(
        "plait render --out <a directory>",
        &o,
        &["--out"],
        Some(dir.path()),
    );
    let o = plait(&[
        "graph",
        "pipelines/forward.toml",
        "--format",
        "svg",
        "--out",
        "/nonexistent-dir/g.svg",
    ]);
    assert_fails(
        "plait graph --out /nonexistent-dir/g.svg",
        &o,
        &["--out", "/nonexistent-dir/g.svg"],
        None,
    );
}

#[test]
fn bad_size() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    for bad in ["abc", "0x10", "64", "64x", "4x-4", "20000x10"] {
        let o = plait(&[
            "render",
            "--size",
            bad,
            "--out",
            png.to_str().expect("utf-8"),
        ]);
        assert_fails(
            &format!("plait render --size {bad}"),
            &o,
            &["--size", bad],
            Some(dir.path()),
        );
    }
}

#[test]
fn unreadable_pipeline_and_scene() {
    let o = plait(&["check", "tests/fixtures/bad/does_not_exist.toml"]);
    assert_fails(
        "plait check <missing file>",
        &o,
        &["does_not_exist.toml"],
        None,
    );
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let o = plait(&[
        "render",
        "--scene",
        "tests/fixtures/bad/no_scene.toml",
        "--size",
        "64x48",
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    assert_fails(
        "plait render --scene <missing file>",
        &o,
        &["no_scene.toml"],
        Some(dir.path()),
    );
}

// ---- good paths ----

fn pipeline_files() -> Vec<String> {
    let mut files: Vec<String> = std::fs::read_dir(root().join("pipelines"))
        .expect("pipelines/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| {
            format!(
                "pipelines/{}",
                p.file_name().expect("name").to_string_lossy()
            )
        })
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no pipelines/*.toml");
    files
}

#[test]
fn check_accepts_every_shipped_pipeline() {
    let files = pipeline_files();
    let mut args = vec!["check"];
    args.extend(files.iter().map(String::as_str));
    let o = plait(&args);
    assert!(
        o.status.success(),
        "plait check {files:?} failed:\n{}",
        text(&o.stderr)
    );
    let stdout = text(&o.stdout);
    for f in &files {
        assert!(
            stdout.contains(&format!("ok  {f}")),
            "no `ok` line for {f}:\n{stdout}"
        );
    }
}

#[test]
fn graph_prints_dot_and_writes_svg() {
    let o = plait(&["graph", "pipelines/forward.toml"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let dot = text(&o.stdout);
    assert!(dot.trim_start().starts_with("digraph"), "not DOT:\n{dot}");
    for pass in ["opaque_shadow", "hair_depth", "opaque", "hair", "compose"] {
        assert!(dot.contains(pass), "DOT lacks pass `{pass}`:\n{dot}");
    }
    assert!(
        dot.contains("rgba16float"),
        "DOT edges lack resource formats:\n{dot}"
    );
    let dir = tempfile::tempdir().expect("tempdir");
    let svg = dir.path().join("forward.svg");
    let o = plait(&[
        "graph",
        "pipelines/forward.toml",
        "--format",
        "svg",
        "--out",
        svg.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let picture = std::fs::read_to_string(&svg).expect("SVG written");
    assert!(
        picture.contains("<svg"),
        "not an SVG: {}",
        &picture[..picture.len().min(200)]
    );
    assert!(picture.contains("compose"), "SVG lacks pass names");
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .expect("list")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert_eq!(left.len(), 1, "temporary files left: {left:?}");
}

#[test]
fn passes_lists_the_library() {
    let o = plait(&["passes"]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    for t in [
        "hair_shade",
        "shadow_map",
        "opaque_shade",
        "fullscreen",
        "compute",
    ] {
        assert!(
            out.lines().any(|l| l.starts_with(t)),
            "`plait passes` does not list `{t}`:\n{out}"
        );
    }
    assert!(
        out.contains("visibility"),
        "hair_shade params missing:\n{out}"
    );
}

#[test]
fn render_json_report() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("small.png");
    let o = plait(&[
        "render",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "128x96",
        "--json",
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    assert!(
        o.status.success(),
        "plait render failed:\n{}",
        text(&o.stderr)
    );
    assert!(!text(&o.stderr).contains("panicked"));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("stdout is not one JSON object ({e}):\n{}", text(&o.stdout)));
    let obj = v.as_object().expect("a JSON object");
    for key in [
        "pipeline",
        "adapter",
        "size",
        "passes",
        "resources",
        "memory",
        "output",
    ] {
        assert!(obj.contains_key(key), "JSON lacks `{key}`: {v:#}");
    }
    assert!(
        v["pipeline"].as_str().is_some_and(|p| p.ends_with(".toml")),
        "pipeline: {}",
        v["pipeline"]
    );
    assert!(
        v["adapter"]["name"].is_string() && v["adapter"]["backend"].is_string(),
        "adapter: {}",
        v["adapter"]
    );
    assert_eq!(v["size"], serde_json::json!([128, 96]));
    let passes = v["passes"].as_array().expect("passes array");
    assert!(!passes.is_empty());
    for p in passes {
        for key in ["name", "type", "reads", "writes", "gpu_ms", "culled"] {
            assert!(p.get(key).is_some(), "pass lacks `{key}`: {p}");
        }
        assert!(
            p["reads"].is_array() && p["writes"].is_array() && p["culled"].is_boolean(),
            "pass: {p}"
        );
        assert!(
            p["gpu_ms"].is_null() || p["gpu_ms"].as_f64().is_some_and(|ms| ms >= 0.0),
            "gpu_ms: {p}"
        );
    }
    assert!(
        passes
            .iter()
            .all(|p| p["name"].as_str().is_some_and(|n| !n.is_empty())),
        "unnamed pass: {v:#}"
    );
    let resources = v["resources"].as_array().expect("resources array");
    assert!(!resources.is_empty());
    for r in resources {
        for key in ["name", "kind", "format", "bytes", "shares_memory_with"] {
            assert!(r.get(key).is_some(), "resource lacks `{key}`: {r}");
        }
        assert!(
            r["bytes"].as_u64().is_some_and(|b| b > 0) && r["shares_memory_with"].is_array(),
            "resource: {r}"
        );
    }
    let (peak, unpooled) = (
        v["memory"]["peak_bytes"].as_u64(),
        v["memory"]["unpooled_bytes"].as_u64(),
    );
    assert!(
        peak.is_some_and(|p| p > 0) && unpooled.is_some_and(|u| u >= peak.unwrap_or(0)),
        "memory: {}",
        v["memory"]
    );
    assert_eq!(v["output"].as_str(), png.to_str());
    let img = image::open(&png).expect("the PNG exists and decodes");
    assert_eq!((img.width(), img.height()), (128, 96));
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .expect("list")
        .map(|e| e.expect("entry").file_name())
        .collect();
    assert_eq!(left.len(), 1, "temporary files left: {left:?}");
}

/// The sharing fixture through the CLI: `shares_memory_with` and a lower peak in the JSON.
#[test]
fn render_json_shows_memory_sharing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("sharing.png");
    let o = plait(&[
        "render",
        "tests/fixtures/sharing.toml",
        "--scene",
        "examples/scenes/small.toml",
        "--size",
        "64x48",
        "--json",
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    assert!(
        o.status.success(),
        "plait render sharing.toml failed:\n{}",
        text(&o.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    let a = v["resources"]
        .as_array()
        .expect("resources")
        .iter()
        .find(|r| r["name"] == "a")
        .expect("resource a")
        .clone();
    assert_eq!(a["shares_memory_with"], serde_json::json!(["c"]), "{v:#}");
    assert!(
        v["memory"]["peak_bytes"].as_u64() < v["memory"]["unpooled_bytes"].as_u64(),
        "memory: {}",
        v["memory"]
    );
}

#[test]
fn missing_background_image_names_the_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("x.png");
    let o = plait(&[
        "render",
        "pipelines/forward.toml",
        "--scene",
        "tests/fixtures/missing_background.toml",
        "--size",
        "64x48",
        "--out",
        png.to_str().expect("utf-8"),
    ]);
    assert_fails(
        "plait render --scene missing_background.toml",
        &o,
        &["no-such-backdrop.png"],
        Some(dir.path()),
    );
}

/// `plait check` refuses, before any GPU work, what rendering would refuse:
/// sizes a pass cannot index, buffers past the storage-binding limit, sample
/// counts no format allows.
#[test]
fn check_rejects_what_rendering_would() {
    let cases: [(&str, &str, &[&str]); 6] = [
        (
            "pipelines/occupancy.toml",
            "params.slices=48",
            &["occupancy/technique.toml:", "light_bits", "multiple of 32"],
        ),
        (
            "pipelines/occupancy.toml",
            "params.light_size=8192",
            // Used inside the size expression `${light_size} * … / 8`:
            // the flag is what to fix, so the error names it (issue 41).
            &[
                "--set params.light_size=8192: resource `light_bits`",
                "1 GiB",
                "128.0 MiB",
            ],
        ),
        (
            "pipelines/alpha_to_coverage.toml",
            "params.samples=3",
            // `samples = "${samples}"`: a whole value given by a flag is
            // reported at the flag.
            &["--set params.samples=3:", "samples is 3"],
        ),
        (
            "pipelines/occupancy.toml",
            "params.light_size=16384",
            // `size = ["${light_size}", "${light_size}"]`: a list made of
            // the flag's value is reported at the flag (issue 41).
            &["--set params.light_size=16384: texture", "16384", "8192"],
        ),
        (
            // depth_range tests the opaque depth texel for texel.
            "pipelines/occupancy.toml",
            "resources.opaque_shadow.size=[256, 256]",
            &[
                "light_range.toml:17:9",
                "`opaque_shadow`",
                "256x256",
                "512x512",
            ],
        ),
        (
            // One sample leaves nothing to resolve (wgpu refused it mid-frame).
            "pipelines/alpha_to_coverage.toml",
            "params.samples=1",
            &[
                "alpha_to_coverage/technique.toml:46:45",
                "`scene`",
                "1 sample(s)",
                "cannot be resolved into `scene_resolved`",
            ],
        ),
    ];
    for (pipeline, set, expected) in cases {
        let o = plait(&["check", pipeline, "--set", set]);
        assert_fails(
            &format!("plait check {pipeline} --set {set}"),
            &o,
            expected,
            None,
        );
    }
}

/// Every gallery pipeline passes `plait check` at the default size, within
/// WebGPU's default limits.
#[test]
fn every_gallery_pipeline_checks() {
    for entry in std::fs::read_dir(root().join("pipelines")).expect("pipelines/") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            let o = plait(&["check", path.to_str().expect("utf-8")]);
            assert_eq!(
                o.status.code(),
                Some(0),
                "{}: {}",
                path.display(),
                text(&o.stderr)
            );
        }
    }
}

/// A visibility provider is a WGSL file the library finds by itself; one that
/// breaks the contract (`fn hair_visibility(world: vec3<f32>) -> f32`) is an
/// error naming its file, before any GPU work.
#[test]
fn a_provider_that_breaks_the_contract_names_its_file() {
    for (what, body) in [
        (
            "missing",
            "fn visibility_of(world: vec3<f32>) -> f32 { return 1.0; }",
        ),
        (
            "wrong signature",
            "fn hair_visibility(world: vec3<f32>) -> vec2<f32> { return vec2<f32>(1.0); }",
        ),
    ] {
        let dir = tempfile::tempdir().expect("tempdir");
        let folder = dir.path().join("shaders/lib/visibility");
        std::fs::create_dir_all(&folder).expect("mkdir");
        std::fs::write(
            folder.join("broken.wgsl"),
            format!("#define_import_path plait::self_shadow::broken\n\n{body}\n"),
        )
        .expect("write");
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_plait"))
            .current_dir(root())
            .env("PLAIT_PATH", dir.path())
            .args(["check", "pipelines/occupancy.toml"])
            .output()
            .expect("run plait");
        assert_fails(
            &format!("a provider with the contract function {what}"),
            &o,
            &[
                "broken.wgsl",
                "must define `fn hair_visibility(world: vec3<f32>) -> f32`",
            ],
            None,
        );
    }
}

/// The shading point's second function (`[wgsl.also]`, what `lighting =
/// "ambient"` reflects) is part of every provider's contract: a shading
/// provider defining `hair_direct` alone is refused naming its file and the
/// function it lacks.
#[test]
fn a_shading_provider_without_its_uniform_response_names_its_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let folder = dir.path().join("techniques/shading/flat");
    std::fs::create_dir_all(&folder).expect("mkdir");
    std::fs::write(
        folder.join("shading.wgsl"),
        "#define_import_path plait::shading::flat\n\n\
         fn hair_direct(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {\n    return base;\n}\n",
    )
    .expect("write");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_plait"))
        .current_dir(root())
        .env("PLAIT_PATH", dir.path())
        .args(["check", "pipelines/occupancy.toml"])
        .output()
        .expect("run plait");
    assert_fails(
        "a shading provider without hair_uniform",
        &o,
        &[
            "flat/shading.wgsl",
            "must define `fn hair_uniform(tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32>`",
        ],
        None,
    );
}

/// `plait check` and `plait graph` find a gallery pipeline by name from any
/// directory, as `plait render` does (the library search path).
#[test]
fn check_and_graph_find_gallery_names_from_anywhere() {
    let dir = tempfile::tempdir().expect("tempdir");
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_plait"))
            .current_dir(dir.path())
            .args(args)
            .output()
            .expect("run plait")
    };
    let o = run(&["check", "forward.toml", "deep_opacity.toml"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let o = run(&["graph", "reference.toml", "--format", "text"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    assert!(text(&o.stdout).contains("technique self_shadow = exact"));
}
