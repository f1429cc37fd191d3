//! `clear = …` on a texture and the check that a `loads` entry keeps what an
//! earlier pass wrote or the declared clear value (issue 41): errors at the
//! `loads` entry or the `clear` value, the legitimate cases accepted.

mod common;

use common::*;
use plait_graph::*;

/// `accum` is loaded by `blend_in`, the first pass to touch it (line 19).
const LOADS_FIRST: &str = r#"[pipeline]
name = "loads_first"
outputs = ["final"]

[resources.accum]
kind = "texture"
format = "rgba16float"
size = "screen"

[resources.final]
kind = "texture"
format = "rgba16float"
size = "screen"

[passes.blend_in]
type = "fullscreen"
shader = "blend_in.wgsl"
writes = { out = "accum" }
loads = ["out"]

[passes.show]
type = "fullscreen"
shader = "show.wgsl"
reads = { src = "accum" }
writes = { out = "final" }
"#;

fn with_clear(clear: &str) -> String {
    with_format_and_clear("rgba16float", clear)
}

/// `accum` with `format` and the `clear` line (line 9) added.
fn with_format_and_clear(format: &str, clear: &str) -> String {
    edit(
        LOADS_FIRST,
        "format = \"rgba16float\"\nsize = \"screen\"\n\n[resources.final]",
        &format!("format = \"{format}\"\nsize = \"screen\"\n{clear}\n\n[resources.final]"),
    )
}

#[test]
fn a_load_before_any_write_is_an_error_at_the_loads_entry() {
    let errors = errors_of(LOADS_FIRST, &[]);
    assert_eq!(errors.len(), 1, "{}", Errors(errors.clone()));
    let e = &errors[0];
    // The entry `"out"` of the `loads` list on line 19 (the list starts at
    // column 9, the entry at 10).
    assert_eq!(e.location, at(19, 10), "{e}");
    let message = e.to_string();
    for part in ["pass `blend_in`", "`accum`", "earlier pass", "clear = "] {
        assert!(message.contains(part), "lacks {part}: {message}");
    }
}

#[test]
fn a_declared_clear_makes_the_load_start_from_it() {
    let schedule = compile_text(&with_clear("clear = [1, 1, 1, 1]"), &[]).unwrap();
    let accum = schedule.resource("accum").unwrap();
    assert_eq!(schedule.resources[accum].clear, Some([1.0; 4]));
    // The first pass clears (to the declared value): nothing to load yet.
    let b = &schedule.passes[0].writes[0];
    assert!(!b.loads, "the first writer must clear");
}

#[test]
fn a_load_after_an_earlier_writer_is_fine() {
    let text = edit(
        LOADS_FIRST,
        "[passes.blend_in]",
        "[passes.first]\ntype = \"fullscreen\"\nshader = \"first.wgsl\"\nwrites = { out = \"accum\" }\n\n[passes.blend_in]",
    );
    // Two writers of one resource must be ordered: the loading one runs last.
    let schedule = compile_text(&text, &[]).unwrap();
    let names: Vec<_> = schedule.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["first", "blend_in", "show"]);
    assert!(schedule.passes[1].writes[0].loads);
}

#[test]
fn a_persistent_target_loads_what_the_last_frame_left() {
    let text = with_clear("persistent = true");
    let schedule = compile_text(&text, &[]).unwrap();
    assert!(schedule.passes[0].writes[0].loads);
}

#[test]
fn an_accumulating_slot_of_a_pass_type_still_clears_first() {
    // `accumulate`'s slot loads by its type: "clear, then accumulate".
    let text = edit(
        LOADS_FIRST,
        "type = \"fullscreen\"\nshader = \"blend_in.wgsl\"\nwrites = { out = \"accum\" }\nloads = [\"out\"]",
        "type = \"accumulate\"\nreads = { src = \"final\" }\nwrites = { acc = \"accum\" }",
    );
    let text = edit(
        &text,
        "reads = { src = \"accum\" }\nwrites = { out = \"final\" }",
        "writes = { out = \"final\" }",
    );
    compile_text(&text, &[]).unwrap();
}

#[test]
fn clear_values_are_checked_against_the_format() {
    let cases: &[(&str, &str)] = &[
        ("clear = [1, 1, 1]", "a list of 4 numbers"),
        ("clear = 1", "a list of 4 numbers"),
        ("clear = [1, 1, nan, 1]", "channel 2 is not a finite number"),
        ("clear = [1, inf, 1, 1]", "channel 1 is not a finite number"),
        (
            "clear = [1, \"one\", 1, 1]",
            "channel 1 is not a finite number",
        ),
        ("clear = [1, 1, 1, 1]\npersistent = true", "never cleared"),
    ];
    for (clear, expected) in cases {
        let errors = errors_of(&with_clear(clear), &[]);
        let message = Errors(errors.clone()).to_string();
        assert_eq!(errors.len(), 1, "{clear}: {message}");
        assert!(message.contains(expected), "{clear}: {message}");
        assert!(message.contains("resources.accum"), "{clear}: {message}");
        // The value, after `clear = ` on line 9.
        assert_eq!(errors[0].location, at(9, 9), "{clear}: {message}");
    }
}

#[test]
fn clear_values_must_fit_integer_unorm_and_depth_formats() {
    let cases: &[(&str, &str, &str)] = &[
        ("r32uint", "clear = -1", "unsigned integers"),
        ("r32uint", "clear = 0.5", "unsigned integers"),
        ("rgba8unorm", "clear = [2, 0, 0, 1]", "values 0 … 1"),
        ("depth32float", "clear = 1.5", "depths 0 … 1"),
    ];
    for (format, clear, expected) in cases {
        let text = with_format_and_clear(format, clear);
        let message = Errors(errors_of(&text, &[])).to_string();
        assert!(message.contains(expected), "{format} {clear}: {message}");
    }
    for (format, clear) in [("r32uint", "clear = 7"), ("depth32float", "clear = 0")] {
        let text = with_format_and_clear(format, clear);
        let pipeline = load_text(&text, &[]).unwrap_or_else(|e| panic!("{format} {clear}: {e}"));
        assert!(
            pipeline.resources["accum"].clear.is_some(),
            "{format} {clear}"
        );
    }
}
