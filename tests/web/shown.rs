//! What the page shows beside the picture (issue 44): the GPU time of every
//! pass, as `plait render` prints it, and the compiled schedule drawn as
//! `plait graph --format svg` draws it.

use plait::session::{SceneData, compile_checked_in, prepare};
use plait_graph::CompileOptions;
use plait_tests::{open_gpu, repo_root};

use crate::page::{Outcome, run_page};
use crate::{SIZE, small_scene};

/// `plait graph --format svg --size 96x72 [--set …]`'s picture: the CLI's
/// compile (no adapter, no scene) of the built-in library.
fn native_svg(pipeline: &str, sets: &[String]) -> String {
    let library = plait_passes::library_for(&[]);
    let path = repo_root().join("pipelines").join(pipeline);
    let opts = CompileOptions {
        screen: SIZE,
        ..CompileOptions::default()
    };
    let schedule = compile_checked_in(&library, &path, sets, &opts)
        .unwrap_or_else(|e| panic!("{pipeline}: {e}"));
    plait_graph::to_svg(&schedule)
}

/// `name.toml;a=b;c=d` → (`name.toml`, [`a=b`, `c=d`]).
fn split(entry: &str) -> (&str, Vec<String>) {
    let mut parts = entry.split(';');
    let name = parts.next().unwrap_or_default();
    (name, parts.map(str::to_owned).collect())
}

/// The pass names `plait render` lists for the entry, in schedule order: the
/// live passes, then the culled ones, then `frame`.
fn native_rows(entry: &str, gpu: &plait_gpu::Gpu, scene: &SceneData) -> Vec<String> {
    let (name, sets) = split(entry);
    let path = repo_root().join("pipelines").join(name);
    let prepared = prepare(gpu, &path, &sets, scene, SIZE).unwrap_or_else(|e| panic!("{e}"));
    let s = prepared.schedule();
    let live = s.passes.iter().map(|p| p.name.clone());
    let culled = s.culled.iter().map(|c| c.pass.name.clone());
    live.chain(culled).chain(["frame".to_owned()]).collect()
}

/// The shown table's problems: a pass missing or out of order, a time that
/// is not a positive number of milliseconds, a missing-feature line.
fn table_problems(outcome: &Outcome, expected: &[String]) -> Vec<String> {
    let name = &outcome.pipeline;
    let mut problems = Vec::new();
    let shown: Vec<&str> = outcome.table.iter().map(|r| r[0].as_str()).collect();
    if shown != expected {
        problems.push(format!(
            "{name}: the table lists {shown:?}, the schedule {expected:?}"
        ));
    }
    for row in &outcome.table {
        let time = row.get(3).map(String::as_str).unwrap_or("");
        let ok = time == "culled" || time.parse::<f64>().is_ok_and(|ms| ms > 0.0);
        if !ok {
            problems.push(format!(
                "{name}: `{}` shows `{time}`, not a positive time",
                row[0]
            ));
        }
    }
    if let Some(missing) = &outcome.missing {
        problems.push(format!(
            "{name}: the page says `{missing}` on SwiftShader, which has timestamp queries"
        ));
    }
    problems
}

/// On SwiftShader (timestamp queries, none inside encoders): each pipeline's
/// table lists every pass in schedule order with a positive time, and its
/// graph is `plait graph`'s SVG for the same pipeline and choices — redrawn
/// when a choice changes (the two occupancy entries differ in their
/// shading technique).
#[test]
fn the_page_shows_pass_times_and_the_schedule() {
    let entries = [
        "depth_peeling.toml",
        "occupancy.toml",
        "occupancy.toml;techniques.shading=marschner",
    ];
    let (posted, console, _) = run_page(&entries);
    if let Some(fatal) = &posted.fatal {
        panic!("the page failed: {fatal}");
    }
    assert_eq!(posted.results.len(), entries.len(), "{posted:?}");
    let scene = small_scene();
    let (_lock, gpu) = open_gpu();
    let mut problems = Vec::new();
    for (entry, outcome) in entries.iter().zip(&posted.results) {
        assert_eq!(outcome.error, None, "{entry}");
        eprintln!("{entry}: the page's table:");
        for row in &outcome.table {
            eprintln!("  {}", row.join(" | "));
        }
        problems.extend(table_problems(outcome, &native_rows(entry, &gpu, &scene)));
        let (name, sets) = split(entry);
        let native = native_svg(name, &sets);
        match &outcome.graph {
            Some(svg) if *svg == native && outcome.graph_drawn => {}
            Some(svg) => problems.push(format!(
                "{entry}: the page's SVG ({} bytes, drawn: {}) is not `plait graph`'s ({} bytes); first difference at byte {:?}",
                svg.len(),
                outcome.graph_drawn,
                native.len(),
                svg.bytes().zip(native.bytes()).position(|(a, b)| a != b)
            )),
            None => problems.push(format!("{entry}: no graph shown")),
        }
    }
    if posted.results[1].graph == posted.results[2].graph {
        problems.push("the graph did not change with the shading technique".into());
    }
    assert!(
        console.is_empty(),
        "console errors:\n{}",
        console.join("\n")
    );
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// Without timestamp queries (lavapipe opened without TIMESTAMP_QUERY) the
/// table the page shows has `n/a`, never a zero, and names the missing
/// feature, as `plait render` does.
#[test]
fn without_timestamps_the_table_names_the_feature() {
    let (_lock, usual) = open_gpu();
    drop(usual);
    let gpu = plait_gpu::Gpu::new_without_features(&["TIMESTAMP_QUERY"]).expect("lavapipe");
    assert_eq!(gpu.timestamp_way(), None);
    let path = repo_root().join("pipelines/occupancy.toml");
    let prepared = prepare(&gpu, &path, &[], &small_scene(), SIZE).expect("occupancy");
    let report = prepared.render().expect("frame").report;
    let timed = gpu.timestamp_way().is_some();
    let table = plait_web::timings::Timings::of(prepared.schedule(), &report, timed);
    let times: Vec<&str> = table.rows.iter().map(|r| r.gpu_ms.as_str()).collect();
    assert!(
        times.iter().all(|t| *t == "n/a" || *t == "culled"),
        "{times:?}"
    );
    let missing = table.missing.unwrap_or_default();
    assert!(missing.contains("TIMESTAMP_QUERY"), "{missing}");
}
