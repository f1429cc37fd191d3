//! `plait ab --shard I/N` and `plait ab merge` (issue 42 item 5): three
//! shards run as three processes at once, merged, give the report one run
//! writes — the same report.json but for timings and the list of machines,
//! the same image files byte for byte — and the merged report says where
//! each time was measured. Bad shard indices, and merging shards that are
//! missing, duplicated, half-written or of another plan, are errors naming
//! them, exit 2.

mod common;
use common::{plait, root, text};

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use serde_json::Value;

/// Two variants against the reference on the small scene, 64×48, one repeat.
const RUN: &[&str] = &[
    "ab",
    "pipelines/forward.toml",
    "pipelines/occupancy.toml",
    "--reference",
    "pipelines/reference.toml",
    "--scene",
    "examples/scenes/small.toml",
    "--size",
    "64x48",
    "--repeats",
    "1",
];

fn command(extra: &[&str], env: &[(&str, &str)]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_plait"));
    c.current_dir(root()).args(RUN).args(extra);
    for var in [
        "SLURM_ARRAY_TASK_ID",
        "SLURM_ARRAY_TASK_COUNT",
        "SLURM_ARRAY_TASK_MIN",
        "SLURM_ARRAY_TASK_STEP",
        "JOB_COMPLETION_INDEX",
        "PLAIT_SHARD_COUNT",
    ] {
        c.env_remove(var);
    }
    c.envs(env.iter().copied());
    c.stdout(Stdio::piped()).stderr(Stdio::piped());
    c
}

fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "stderr: {}\nstdout: {}",
        text(&o.stderr),
        text(&o.stdout)
    );
}

/// Exit 2 with `needles` in the message, and no panic.
fn fails_naming(o: &Output, needles: &[&str]) {
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "`{n}` not in: {err}");
    }
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// report.json without what may differ between one run and merged shards:
/// each row's timing and shard, the list of shards, the command line and
/// the time of day. Everything else — every row, in order — must be equal.
fn comparable(dir: &Path) -> Value {
    let mut r: Value =
        serde_json::from_slice(&std::fs::read(dir.join("report.json")).expect("report.json"))
            .expect("JSON");
    let o = r.as_object_mut().expect("object");
    o.remove("shards");
    let p = o["provenance"].as_object_mut().expect("provenance");
    for key in ["command", "command_line", "unix_time"] {
        p.remove(key);
    }
    for scene in o["scenes"].as_array_mut().expect("scenes") {
        for run in scene["runs"].as_array_mut().expect("runs") {
            let run = run.as_object_mut().expect("run");
            run.remove("timing");
            run.remove("shard");
        }
    }
    r
}

/// Where `a` and `b` first differ (a JSON path and both values, cut short),
/// or `None`: a failure names the field instead of printing two reports.
fn first_difference(a: &Value, b: &Value, path: &str) -> Option<String> {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let keys: std::collections::BTreeSet<&String> = x.keys().chain(y.keys()).collect();
            keys.into_iter().find_map(|k| match (x.get(k), y.get(k)) {
                (Some(u), Some(v)) => first_difference(u, v, &format!("{path}.{k}")),
                _ => Some(format!("{path}.{k}: present in only one")),
            })
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .find_map(|(i, (u, v))| first_difference(u, v, &format!("{path}[{i}]"))),
        _ if a == b => None,
        _ => {
            let cut = |v: &Value| v.to_string().chars().take(200).collect::<String>();
            Some(format!("{path}: {} vs {}", cut(a), cut(b)))
        }
    }
}

/// The rows of the first scene of a report.
fn runs(v: &mut Value) -> &mut Vec<Value> {
    v["scenes"][0]["runs"].as_array_mut().expect("runs")
}

fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".png") || n.ends_with(".exr") || n.ends_with(".svg"))
        .collect();
    names.sort();
    names
}

#[test]
fn three_shards_merged_equal_one_run() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let one = tmp.path().join("one");
    ok(&command(&["--out", s(&one)], &[]).output().expect("run"));
    // Three processes at once: shard 0 by flag, 1 as a Slurm array task
    // (ids 1..3), 2 as a Kubernetes Indexed Job pod.
    let shards: Vec<PathBuf> = (0..3).map(|i| tmp.path().join(format!("s{i}"))).collect();
    let children = [
        command(&["--shard", "0/3", "--out", s(&shards[0])], &[]).spawn(),
        command(
            &["--out", s(&shards[1])],
            &[
                ("SLURM_ARRAY_TASK_ID", "2"),
                ("SLURM_ARRAY_TASK_MIN", "1"),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
            ],
        )
        .spawn(),
        command(
            &["--shard-count", "3", "--out", s(&shards[2])],
            &[("JOB_COMPLETION_INDEX", "2")],
        )
        .spawn(),
    ];
    for child in children {
        ok(&child.expect("spawn").wait_with_output().expect("wait"));
    }
    let merged = tmp.path().join("merged");
    let mut args = vec!["ab", "merge"];
    args.extend(shards.iter().rev().map(|p| s(p)));
    args.extend(["--out", s(&merged)]);
    ok(&plait(&args));

    let expected = comparable(&one);
    let difference = first_difference(&comparable(&merged), &expected, "report");
    assert_eq!(difference, None, "merged shards ≠ one run");
    // The comparison sees a row missing or twice.
    let mut missing = expected.clone();
    runs(&mut missing).remove(1);
    assert!(first_difference(&missing, &expected, "").is_some());
    let mut twice = expected.clone();
    let row = runs(&mut twice)[1].clone();
    runs(&mut twice).push(row);
    assert!(first_difference(&twice, &expected, "").is_some());
    // The same files, byte for byte (difference maps redrawn at the scale
    // of all rows, not the shard's own).
    assert_eq!(files(&merged), files(&one));
    for name in files(&one) {
        let same = std::fs::read(one.join(&name)).ok() == std::fs::read(merged.join(&name)).ok();
        assert!(same, "{name} differs between one run and the merged shards");
    }
    // Where each time comes from: every row by its shard, said in the tables.
    let json: Value =
        serde_json::from_slice(&std::fs::read(merged.join("report.json")).expect("json"))
            .expect("JSON");
    let by_shard: Vec<u64> = json["scenes"][0]["runs"]
        .as_array()
        .expect("runs")
        .iter()
        .map(|r| r["shard"].as_u64().expect("shard"))
        .collect();
    assert_eq!(by_shard, [0, 1, 2]);
    assert_eq!(json["shards"].as_array().expect("shards").len(), 3);
    let md = std::fs::read_to_string(merged.join("report.md")).expect("md");
    assert!(
        md.contains("(shard 1 on ") && md.contains("(across shards)"),
        "{md}"
    );
    assert!(
        md.contains("not ratios measured side by side in one run"),
        "{md}"
    );
    let html = std::fs::read_to_string(merged.join("report.html")).expect("html");
    assert!(html.contains("Merged from 3 shards"));

    bad_merges(tmp.path(), &shards);
}

/// Merging what is not every shard of one plan, each once, finished.
fn bad_merges(tmp: &Path, shards: &[PathBuf]) {
    let out = tmp.join("bad");
    let merge = |dirs: &[&PathBuf]| {
        let mut args = vec!["ab", "merge"];
        args.extend(dirs.iter().map(|p| s(p)));
        args.extend(["--out", s(&out)]);
        plait(&args)
    };
    let [a, b, c] = [&shards[0], &shards[1], &shards[2]];
    fails_naming(&merge(&[a, b]), &["shard 2 of 3 is missing", s(a), s(b)]);
    fails_naming(&merge(&[a, b, c, b]), &["are both shard 1", s(b)]);
    // Another plan: the reference supersampled.
    let other = tmp.join("other");
    ok(&command(
        &["--shard", "2/3", "--supersample", "2", "--out", s(&other)],
        &[],
    )
    .output()
    .expect("run"));
    fails_naming(&merge(&[a, b, &other]), &["different plans", s(&other)]);
    // Half-written: no completion marker.
    let half = tmp.join("half");
    std::fs::create_dir(&half).expect("mkdir");
    for entry in std::fs::read_dir(c).expect("dir") {
        let entry = entry.expect("entry");
        if entry.file_name() != "shard.json" {
            std::fs::copy(entry.path(), half.join(entry.file_name())).expect("copy");
        }
    }
    fails_naming(&merge(&[a, b, &half]), &["no shard.json", s(&half)]);
    // A shard holding a row of another shard's: the row is there twice.
    let greedy = tmp.join("greedy");
    std::fs::create_dir(&greedy).expect("mkdir");
    for entry in std::fs::read_dir(c).expect("dir") {
        let entry = entry.expect("entry");
        std::fs::copy(entry.path(), greedy.join(entry.file_name())).expect("copy");
    }
    let report: Value =
        serde_json::from_slice(&std::fs::read(c.join("report.json")).expect("json")).expect("JSON");
    let first: Value =
        serde_json::from_slice(&std::fs::read(a.join("report.json")).expect("json")).expect("JSON");
    let mut report = report;
    let stolen = first["scenes"][0]["runs"][0].clone();
    report["scenes"][0]["runs"]
        .as_array_mut()
        .expect("runs")
        .insert(0, stolen);
    std::fs::write(greedy.join("report.json"), report.to_string()).expect("write");
    fails_naming(&merge(&[a, b, &greedy]), &["small/forward", "each once"]);
    // Shards whose references differ (another GPU or driver): the rows
    // would be measured against different truths.
    let elsewhere = tmp.join("elsewhere");
    std::fs::create_dir(&elsewhere).expect("mkdir");
    for entry in std::fs::read_dir(b).expect("dir") {
        let entry = entry.expect("entry");
        std::fs::copy(entry.path(), elsewhere.join(entry.file_name())).expect("copy");
    }
    let image = elsewhere.join("small-reference.exr");
    let mut bytes = std::fs::read(&image).expect("reference");
    let last = bytes.len() - 1;
    bytes[last] ^= 1;
    std::fs::write(&image, bytes).expect("write");
    fails_naming(
        &merge(&[a, &elsewhere, c]),
        &[
            "scene small",
            "small-reference.exr",
            s(&elsewhere),
            "different truths",
        ],
    );
    assert!(!out.exists(), "a failed merge left {}", out.display());
}

/// A shard index out of range or malformed, from the flag or the
/// environment, names where it came from, exit 2, before any GPU work.
#[test]
fn bad_shard_indices_name_the_flag() {
    let out = tempfile::tempdir().expect("tempdir");
    let out = out.path().join("r");
    for bad in ["3/3", "0/0", "1", "x/3"] {
        let o = command(&["--shard", bad, "--out", s(&out)], &[])
            .output()
            .expect("run");
        fails_naming(&o, &["--shard", bad]);
    }
    let o = command(
        &["--out", s(&out)],
        &[("JOB_COMPLETION_INDEX", "3"), ("PLAIT_SHARD_COUNT", "3")],
    )
    .output()
    .expect("run");
    fails_naming(&o, &["--shard", "JOB_COMPLETION_INDEX=3", "out of range"]);
    let o = command(&["--out", s(&out)], &[("JOB_COMPLETION_INDEX", "0")])
        .output()
        .expect("run");
    fails_naming(&o, &["--shard-count"]);
    let o = command(
        &["--out", s(&out)],
        &[
            ("SLURM_ARRAY_TASK_ID", "7"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ],
    )
    .output()
    .expect("run");
    fails_naming(&o, &["SLURM_ARRAY_TASK_ID=7"]);
    assert!(!out.exists());
}

/// Two scenes at two camera distances (four scenes in the report), a swept
/// variant, a supersampled reference and `--frames`: four shards, some
/// holding only a scene's reference row, merge into the one run's report.
#[test]
fn scenes_distances_and_frames_merge_too() {
    let args = [
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
        "--frames",
        "2",
        "--scene",
        "examples/scenes/small.toml",
        "--scene",
        "examples/scenes/stray.toml",
        "--size",
        "64x48",
        "--repeats",
        "1",
    ];
    let tmp = tempfile::tempdir().expect("tempdir");
    let run = |extra: &[&str]| {
        let mut all = args.to_vec();
        all.extend_from_slice(extra);
        ok(&plait(&all));
    };
    let one = tmp.path().join("one");
    run(&["--out", s(&one)]);
    let shards: Vec<PathBuf> = (0..4).map(|i| tmp.path().join(format!("s{i}"))).collect();
    for (i, dir) in shards.iter().enumerate() {
        run(&["--shard", &format!("{i}/4"), "--out", s(dir)]);
    }
    let merged = tmp.path().join("merged");
    let mut merge = vec!["ab", "merge"];
    merge.extend(shards.iter().map(|p| s(p)));
    merge.extend(["--out", s(&merged)]);
    ok(&plait(&merge));
    let difference = first_difference(&comparable(&merged), &comparable(&one), "report");
    assert_eq!(difference, None, "merged shards ≠ one run");
    assert_eq!(files(&merged), files(&one));
    for name in files(&one) {
        let same = std::fs::read(one.join(&name)).ok() == std::fs::read(merged.join(&name)).ok();
        assert!(same, "{name} differs between one run and the merged shards");
    }
}

/// The `plait ab` command of a file in examples/cluster/, as words: the
/// Slurm script's (lines joined at `\`) or the Kubernetes manifest's
/// folded `args` block (no YAML crate is a dependency; the manifest was
/// checked with Python's yaml.safe_load when written).
fn example_command(name: &str) -> (String, Vec<String>) {
    let text = std::fs::read_to_string(root().join("examples/cluster").join(name)).expect(name);
    let joined = text.replace("\\\n", " ");
    let words: Vec<String> = if name.ends_with(".sh") {
        let line = joined
            .lines()
            .find(|l| l.trim_start().starts_with("plait ab "));
        let line = line.expect("a plait ab line");
        line.split_whitespace().map(String::from).collect()
    } else {
        let block: Vec<&str> = text
            .lines()
            .skip_while(|l| l.trim() != "- >-")
            .skip(1)
            .take_while(|l| !l.trim_start().starts_with("resources:"))
            .collect();
        let block = block.join(" ");
        block.split_whitespace().map(String::from).collect()
    };
    (text, words)
}

/// The examples of the book's "Runs that outgrow one machine" run as
/// written (at 64×48, one repeat), and agree with each other: the same
/// command, and as many shards in the Slurm array as Kubernetes completions
/// and PLAIT_SHARD_COUNT.
#[test]
fn the_cluster_examples_run_as_written() {
    let (slurm_text, slurm) = example_command("slurm-ab.sh");
    let (k8s_text, k8s) = example_command("plait-ab-job.yaml");
    let without_out = |w: &[String]| -> Vec<String> {
        let at = w.iter().position(|x| x == "--out").expect("--out");
        w[..at].to_vec()
    };
    assert_eq!(without_out(&slurm), without_out(&k8s));
    let shards = 5;
    assert!(slurm_text.contains(&format!("#SBATCH --array=0-{}", shards - 1)));
    assert!(k8s_text.contains(&format!("completions: {shards}\n")));
    assert!(k8s_text.contains(&format!("value: \"{shards}\"")));
    assert!(k8s_text.contains("completionMode: Indexed"));

    let tmp = tempfile::tempdir().expect("tempdir");
    let out = tmp.path().join("shard");
    let mut args: Vec<String> = without_out(&slurm)[1..].to_vec();
    for (flag, value) in [("--size", "64x48"), ("--repeats", "1")] {
        let at = args.iter().position(|x| x == flag).expect(flag);
        args[at + 1] = value.into();
    }
    let last = format!("{}/{shards}", shards - 1);
    args.extend(["--shard".into(), last, "--out".into(), s(&out).into()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    ok(&plait(&args));
    assert!(out.join("shard.json").is_file());
}
