//! The book's worked example (`book/src/guide/writing-a-technique.md`,
//! "A worked example: Weighted Blended OIT"): the technique's files are
//! copied out of the page itself (each fenced block after a
//! `<!-- file: PATH -->` line) into a `PLAIT_PATH` folder, and the page's
//! commands run with the built binary. So the guide cannot drift from what
//! plait accepts, and the three mistakes it warns about are refused at their
//! file, line and column.

mod common;
use common::{root, text, with_library};

use std::process::Output;

const PAGE: &str = "book/src/guide/writing-a-technique.md";
const FOLDER: &str = "techniques/transparency/wboit";

/// The page's files: (relative path, contents), in page order.
fn page_files() -> Vec<(String, String)> {
    let page = std::fs::read_to_string(root().join(PAGE)).expect("read the guide");
    let mut files = Vec::new();
    let mut lines = page.lines();
    while let Some(line) = lines.next() {
        let Some(path) = line
            .strip_prefix("<!-- file: ")
            .and_then(|rest| rest.strip_suffix(" -->"))
        else {
            continue;
        };
        let fence = lines.next().expect("a fenced block after the file marker");
        assert!(
            fence.starts_with("```"),
            "{path}: no fence after its marker"
        );
        let body: Vec<&str> = lines.by_ref().take_while(|l| *l != "```").collect();
        files.push((path.to_string(), body.join("\n") + "\n"));
    }
    files
}

/// A library folder holding the page's files, each passed through `edit`.
fn library(edit: impl Fn(&str, &str) -> String) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    for (path, body) in page_files() {
        let file = dir.path().join(&path);
        std::fs::create_dir_all(file.parent().expect("a parent")).expect("mkdir");
        std::fs::write(file, edit(&path, &body)).expect("write");
    }
    dir
}

const CHOOSE: [&str; 4] = [
    "check",
    "pipelines/occupancy.toml",
    "--set",
    "techniques.transparency=wboit",
];

fn refused(what: &str, o: &Output, wanted: &[&str]) {
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{what}: {stderr}");
    for w in wanted {
        assert!(stderr.contains(w), "{what}: no `{w}` in\n{stderr}");
    }
    assert!(!stderr.contains("panicked"), "{what}: {stderr}");
}

/// The page holds exactly the technique's three files, and a pipeline that
/// chooses it checks.
#[test]
fn the_pages_files_are_a_technique_that_checks() {
    let names: Vec<String> = page_files().into_iter().map(|(p, _)| p).collect();
    assert_eq!(
        names,
        [
            format!("{FOLDER}/technique.toml"),
            format!("{FOLDER}/sums.wgsl"),
            format!("{FOLDER}/resolve.wgsl"),
        ]
    );
    let lib = library(|_, body| body.to_string());
    let o = with_library(lib.path(), &CHOOSE);
    assert!(o.status.success(), "{}", text(&o.stderr));
}

/// The page's `plait ab`: the technique renders, and its error against depth
/// peeling sits where the page says — far below opaque lines', within a
/// factor 2 of weighted average's. A revealage that never starts at 1, a
/// coverage taken from the sums, or a missing colour would leave that band.
#[test]
fn the_pages_ab_puts_it_beside_weighted_average() {
    let lib = library(|_, body| body.to_string());
    let out = tempfile::tempdir().expect("temp dir");
    let report = out.path().join("ab");
    let o = with_library(
        lib.path(),
        &[
            "ab",
            "pipelines/occupancy.toml",
            "--reference",
            "pipelines/depth_peeling.toml",
            "--sweep",
            "techniques.transparency=wboit,weighted_average,opaque",
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            "64x48",
            "--repeats",
            "1",
            "--out",
            report.to_str().expect("utf-8 path"),
        ],
    );
    assert!(o.status.success(), "{}", text(&o.stderr));
    let json: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(report.join("report.json")).expect("report.json"),
    )
    .expect("json");
    let rmse = |variant: &str| {
        json["scenes"][0]["runs"]
            .as_array()
            .expect("runs")
            .iter()
            .find(|r| r["variant"] == format!("occupancy@{variant}"))
            .and_then(|r| r["metrics"]["rmse"].as_f64())
            .unwrap_or_else(|| panic!("no rmse for {variant}"))
    };
    let (wboit, average, opaque) = (rmse("wboit"), rmse("weighted_average"), rmse("opaque"));
    eprintln!(
        "RMSE against depth peeling: wboit {wboit:.5}, weighted_average {average:.5}, opaque {opaque:.5}"
    );
    assert!(
        wboit > 0.0 && wboit * 10.0 < opaque,
        "wboit {wboit}, opaque {opaque}"
    );
    assert!(
        wboit < 2.0 * average && average < 2.0 * wboit,
        "wboit {wboit}, weighted average {average}"
    );
}

/// The three mistakes the page warns about, each planted in the page's own
/// files, are refused at load with the file and line.
#[test]
fn the_pages_three_warnings_are_refused_at_their_line() {
    // No clear value: the `loads` of a target nothing wrote earlier.
    let lib = library(|path, body| {
        if path.ends_with("technique.toml") {
            body.replace("clear = 1\n", "")
        } else {
            body.to_string()
        }
    });
    refused(
        "no clear",
        &with_library(lib.path(), &CHOOSE),
        &["wboit/technique.toml:", "revealage", "clear"],
    );
    // A param another chosen technique defines.
    let lib = library(|_, body| body.replace("wboit_depth_unit", "slabs"));
    refused(
        "param clash",
        &with_library(lib.path(), &CHOOSE),
        &["wboit/technique.toml:", "slabs", "self_shadow/occupancy"],
    );
    // An output past the pass's two targets.
    let lib = library(|path, body| {
        if path.ends_with("sums.wgsl") {
            body.replace("@location(1) revealage", "@location(2) revealage")
        } else {
            body.to_string()
        }
    });
    refused(
        "output location",
        &with_library(lib.path(), &CHOOSE),
        &["sums.wgsl:", "location"],
    );
}
