//! State across frames: `history = N` (`NAME.previous` … `NAME.previous.N`)
//! and `persistent = true`, checked at load time at the place that is wrong.

mod common;

use common::*;
use plait_graph::*;

/// `step` integrates from last frame's positions and adds into a persistent
/// total; `show` draws both. Line numbers matter: tests point at them.
const HISTORY: &str = r#"[pipeline]
name = "history"
outputs = ["final"]

[resources.positions]
kind = "buffer"
size = 64
history = 1

[resources.total]
kind = "buffer"
size = 16
persistent = true

[resources.final]
kind = "texture"
format = "rgba16float"
size = "screen"

[passes.step]
type = "fullscreen"
shader = "step.wgsl"
reads = { prev = "positions.previous" }
writes = { positions = "positions", total = "total" }

[passes.show]
type = "fullscreen"
shader = "show.wgsl"
reads = { positions = "positions", total = "total" }
writes = { final = "final" }
"#;

fn only_error(text: &str) -> Error {
    let errors = errors_of(text, &[]);
    assert_eq!(errors.len(), 1, "{}", Errors(errors.clone()));
    errors.into_iter().next().unwrap()
}

fn id(schedule: &Schedule, name: &str) -> ResourceId {
    schedule
        .resource(name)
        .unwrap_or_else(|| panic!("no resource `{name}`"))
}

#[test]
fn a_history_adds_last_frames_version_and_one_copy_per_frame() {
    let s = compile_text(HISTORY, &[]).unwrap();
    let (positions, previous, total) = (
        id(&s, "positions"),
        id(&s, "positions.previous"),
        id(&s, "total"),
    );
    assert_eq!(
        s.resources[positions].lifetime,
        Lifetime::History { frames: 1 }
    );
    assert_eq!(
        s.resources[previous].lifetime,
        Lifetime::Previous {
            of: positions,
            frames_ago: 1
        }
    );
    assert_eq!(s.resources[previous].desc, s.resources[positions].desc);
    assert_eq!(s.resources[total].lifetime, Lifetime::Persistent);
    assert_eq!(
        s.history,
        [HistoryCopy {
            from: positions,
            to: previous
        }]
    );
    // Contents that outlive the frame span it and own their memory.
    let last = s.passes.len() - 1;
    for r in [positions, previous, total] {
        assert_eq!(
            (s.resources[r].first_use, s.resources[r].last_use),
            (0, last)
        );
        assert!(
            s.shares_memory_with(r).is_empty(),
            "{}",
            s.resources[r].name
        );
    }
    // The engine never clears a persistent resource: its writers load.
    let step = &s.passes[0];
    assert_eq!(step.name, "step");
    let write = |name: &str| {
        step.writes
            .iter()
            .find(|b| b.resource_name == name)
            .unwrap()
    };
    assert!(write("total").loads);
    assert!(
        !write("positions").loads,
        "a history's own version starts cleared"
    );
    let text = schedule_text(&s);
    assert!(text.contains("positions.previous: buffer 64 B"), "{text}");
    assert!(
        text.contains("previous of positions, 1 frame ago"),
        "{text}"
    );
    assert!(
        text.contains("history: positions -> positions.previous"),
        "{text}"
    );
}

#[test]
fn a_longer_history_is_aged_oldest_first() {
    let text = edit(HISTORY, "history = 1", "history = 3");
    let text = edit(&text, "\"positions.previous\"", "\"positions.previous.3\"");
    let s = compile_text(&text, &[]).unwrap();
    let name = |r: ResourceId| s.resources[r].name.as_str();
    let copies: Vec<(&str, &str)> = s
        .history
        .iter()
        .map(|c| (name(c.from), name(c.to)))
        .collect();
    assert_eq!(
        copies,
        [
            ("positions.previous.2", "positions.previous.3"),
            ("positions.previous", "positions.previous.2"),
            ("positions", "positions.previous"),
        ]
    );
}

#[test]
fn previous_of_a_resource_without_history_says_how_to_keep_one() {
    let text = edit(HISTORY, "history = 1\n", "");
    let e = only_error(&text);
    assert_eq!(e.location, at(22, 18));
    assert!(matches!(e.kind, ErrorKind::NoHistory { .. }), "{e:?}");
    let message = e.to_string();
    assert!(
        message.contains("`positions` keeps no history; add `history = 1` to [resources.positions] (pipelines/test.toml:5:"),
        "{message}"
    );
}

#[test]
fn reading_further_back_than_the_history_names_the_count_needed() {
    let text = edit(
        HISTORY,
        "\"positions.previous\"",
        "\"positions.previous.2\"",
    );
    let e = only_error(&text);
    assert_eq!(e.location, at(23, 18));
    let message = e.to_string();
    assert!(
        message.contains("`positions` keeps 1 frame of history (pipelines/test.toml:8:11); `positions.previous.2` needs `history = 2`"),
        "{message}"
    );
}

#[test]
fn a_history_nobody_writes_is_an_error_at_the_read() {
    let text = edit(
        HISTORY,
        "writes = { positions = \"positions\", total = \"total\" }",
        "writes = { total = \"total\" }",
    );
    let text = edit(
        &text,
        "reads = { positions = \"positions\", total = \"total\" }",
        "reads = { total = \"total\" }",
    );
    let e = only_error(&text);
    assert_eq!(e.location, at(23, 18));
    assert_eq!(
        e.kind,
        ErrorKind::HistoryNeverWritten {
            previous: "positions.previous".into(),
            resource: "positions".into(),
            reader: "step".into(),
        }
    );
}

#[test]
fn writing_an_earlier_frame_is_refused() {
    let text = edit(
        HISTORY,
        "writes = { final = \"final\" }",
        "writes = { final = \"final\", old = \"positions.previous\" }",
    );
    let e = only_error(&text);
    assert_eq!(e.location, at(30, 35));
    assert!(
        e.to_string()
            .contains("which is read-only: write `positions` and the engine keeps its history"),
        "{e}"
    );
}

#[test]
fn a_multisampled_texture_cannot_keep_a_history() {
    let text = edit(
        HISTORY,
        "size = \"screen\"\n",
        "size = \"screen\"\nsamples = 4\nhistory = 1\n",
    );
    let e = only_error(&text);
    assert_eq!(e.location, at(20, 11));
    assert!(e.to_string().contains("cannot be copied"), "{e}");
}

#[test]
fn history_and_persistent_values_are_checked() {
    for (value, column) in [("0", 11), ("9", 11), ("\"two\"", 11), ("1.5", 11)] {
        let text = edit(HISTORY, "history = 1", &format!("history = {value}"));
        let e = only_error(&text);
        assert_eq!(e.location, at(8, column), "{value}");
        assert!(e.to_string().contains("an integer 1 … 8"), "{e}");
    }
    let text = edit(HISTORY, "persistent = true", "persistent = \"yes\"");
    let e = errors_of(&text, &[]).remove(0);
    assert_eq!(e.location, at(13, 14));
    assert!(e.to_string().contains("must be true or false"), "{e}");
}

#[test]
fn a_misspelt_history_suggests_the_declared_one() {
    let text = edit(HISTORY, "\"positions.previous\"", "\"positons.previous\"");
    let e = only_error(&text);
    assert!(
        e.to_string().contains("did you mean `positions.previous`"),
        "{e}"
    );
}

#[test]
fn dotted_resource_names_are_kept_for_histories() {
    let text = edit(HISTORY, "[resources.total]", "[resources.\"total.sum\"]");
    let e = errors_of(&text, &[]).remove(0);
    assert_eq!(e.location, at(10, 12));
    assert!(e.to_string().contains("kept for histories"), "{e}");
}

#[test]
fn reading_last_frame_keeps_the_writer_that_runs_after_it() {
    // `show` reads only last frame's positions; `step`, which writes them,
    // has no edge to it and runs after it. Both stay.
    let text = edit(
        HISTORY,
        "reads = { positions = \"positions\", total = \"total\" }",
        "reads = { positions = \"positions.previous\" }",
    );
    let text = edit(&text, "reads = { prev = \"positions.previous\" }\n", "");
    let s = compile_text(&text, &[]).unwrap();
    let names: Vec<_> = s.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["step", "show"]);
    assert!(s.culled.is_empty());
    // Declared first, `show` runs first: the walk that culls must come back
    // for `step` once `show` needs `positions` through its history.
    let (head, passes) = text.split_at(text.find("[passes.step]").unwrap());
    let (step, show) = passes.split_at(passes.find("[passes.show]").unwrap());
    let s = compile_text(&format!("{head}{show}\n{step}"), &[]).unwrap();
    let names: Vec<_> = s.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["show", "step"]);
    assert!(s.culled.is_empty());
}
