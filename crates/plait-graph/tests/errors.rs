//! Every class of bad input gives the expected error kind at the exact
//! `file:line:column` (or `--set` flag) that caused it.

mod common;

use common::*;
use plait_graph::*;

/// The single error of a failing pipeline.
fn only_error(text: &str, sets: &[&str]) -> Error {
    let errors = errors_of(text, sets);
    assert_eq!(
        errors.len(),
        1,
        "expected one error, got:\n{}",
        Errors(errors.clone())
    );
    errors.into_iter().next().unwrap()
}

#[test]
fn the_reference_pipeline_compiles() {
    let schedule = compile_text(GOOD, &[]).unwrap();
    let names: Vec<_> = schedule.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["light_range", "shade"]);
}

#[test]
fn toml_syntax_error_points_at_the_bad_token() {
    let text = edit(GOOD, "name = \"good\"", "name = good");
    let e = load_text(&text, &[]).unwrap_err().0.remove(0);
    assert!(matches!(e.kind, ErrorKind::Syntax(_)), "{e}");
    assert_eq!(e.location, at(2, 8));
    assert!(
        e.to_string()
            .starts_with("pipelines/test.toml:2:8: TOML syntax error"),
        "{e}"
    );
}

#[test]
fn unknown_pass_type_lists_the_known_ones() {
    let text = edit(GOOD, "type = \"shade\"", "type = \"shdae\"");
    let e = only_error(&text, &[]);
    assert_eq!(e.location, at(25, 8));
    match &e.kind {
        ErrorKind::UnknownPassType { name, known } => {
            assert_eq!(name, "shdae");
            assert!(
                known.contains("shade") && known.contains("depth_range"),
                "{known}"
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn unknown_param_lists_the_params_of_the_type() {
    let text = edit(
        GOOD,
        "writes = { color = \"final\" }",
        "writes = { color = \"final\" }\nparams = { strength = 2.0, glow = 1 }",
    );
    let e = only_error(&text, &[]);
    assert_eq!(e.location, at(28, 35));
    match &e.kind {
        ErrorKind::UnknownParam {
            pass,
            pass_type,
            param,
            known,
        } => {
            assert_eq!(
                (pass.as_str(), pass_type.as_str(), param.as_str()),
                ("shade", "shade", "glow")
            );
            assert_eq!(known, "color, mode, strength, slices");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_param_values_are_reported_at_the_value() {
    let text = edit(
        GOOD,
        "writes = { color = \"final\" }",
        "writes = { color = \"final\" }\nparams = { strength = 20.0, mode = \"phong\" }",
    );
    let errors = errors_of(&text, &[]);
    assert_eq!(errors.len(), 2);
    assert!(matches!(&errors[0].kind, ErrorKind::BadParam { param, .. } if param == "strength"));
    assert_eq!(errors[0].location, at(28, 23));
    assert!(
        matches!(&errors[1].kind, ErrorKind::BadParam { param, reason, .. } if param == "mode" && reason.contains("kajiya"))
    );
    assert_eq!(errors[1].location, at(28, 36));
}

#[test]
fn read_but_never_written_points_at_the_read() {
    // Disabling the only writer leaves `depth` unwritten.
    let e = only_error(GOOD, &["passes.light_range.enabled=false"]);
    assert_eq!(e.location, at(26, 20));
    assert_eq!(
        e.kind,
        ErrorKind::NeverWritten {
            resource: "depth".into(),
            reader: "shade".into()
        }
    );
}

#[test]
fn two_unordered_writers_are_named() {
    let text = format!(
        "{GOOD}\n[passes.other_range]\ntype = \"depth_range\"\nview = \"camera\"\ndraw = \"hair\"\nwrites = {{ range = \"depth\" }}\n"
    );
    let e = only_error(&text, &[]);
    assert_eq!(e.location, at(33, 20));
    assert_eq!(
        e.kind,
        ErrorKind::UnorderedWriters {
            resource: "depth".into(),
            first: "light_range".into(),
            second: "other_range".into()
        }
    );
}

const CYCLE: &str = r#"[pipeline]
name = "cycle"
outputs = ["y"]

[resources.x]
kind = "texture"
format = "rgba16float"
size = [64, 64]

[resources.y]
kind = "texture"
format = "rgba16float"
size = [64, 64]

[passes.a]
type = "blur"
reads = { src = "x" }
writes = { dst = "y" }
params = { radius = 2 }

[passes.b]
type = "blur"
reads = { src = "y" }
writes = { dst = "x" }
params = { radius = 2 }
"#;

#[test]
fn cycle_names_the_passes_around_it() {
    let e = only_error(CYCLE, &[]);
    assert_eq!(
        e.kind,
        ErrorKind::Cycle(vec!["a".into(), "b".into(), "a".into()])
    );
    assert_eq!(e.location, at(15, 9));
    assert!(
        e.to_string().ends_with("cycle between passes: a -> b -> a"),
        "{e}"
    );
}

#[test]
fn format_mismatch_names_resource_pass_slot_and_accepted_formats() {
    let text = edit(GOOD, "format = \"rg32float\"", "format = \"rgba8unorm\"");
    let errors = errors_of(&text, &[]);
    assert_eq!(errors.len(), 2, "the writer and the reader both reject it");
    assert_eq!(errors[0].location, at(22, 20));
    assert_eq!(
        errors[0].kind,
        ErrorKind::FormatMismatch {
            resource: "depth".into(),
            declared: "rgba8unorm".into(),
            pass: "light_range".into(),
            slot: "range".into(),
            accepted: "rg32float | rg16float".into(),
        }
    );
    assert_eq!(errors[1].location, at(26, 20));
}

#[test]
fn undefined_param_points_at_the_string_using_it() {
    let text = edit(
        GOOD,
        "size = [\"${size}\", \"${size}\"]",
        "size = [\"${size}\", \"${sise}\"]",
    );
    let e = load_text(&text, &[]).unwrap_err().0.remove(0);
    assert_eq!(e.location, at(11, 20));
    assert_eq!(e.kind, ErrorKind::UndefinedParam("sise".into()));
}

#[test]
fn params_referring_to_each_other_in_a_loop_are_an_error() {
    let text = edit(
        GOOD,
        "size = 256",
        "size = \"${other}\"\nother = \"${size}\"",
    );
    let e = load_text(&text, &[]).unwrap_err().0.remove(0);
    assert!(
        matches!(&e.kind, ErrorKind::ParamCycle(names) if names.len() == 3),
        "{e}"
    );
}

#[test]
fn malformed_set_flags_are_reported_on_the_flag() {
    for flag in [
        "params.size",
        "=3",
        "params..size=3",
        "params.size.x=3",
        " = 1",
    ] {
        let e = load_text(GOOD, &[flag]).unwrap_err().0.remove(0);
        assert_eq!(e.location, Location::Flag { flag: flag.into() });
        assert!(
            matches!(&e.kind, ErrorKind::MalformedSet { flag: f, .. } if f == flag),
            "{e}"
        );
    }
}

#[test]
fn texture_too_large_names_the_limit_at_the_size() {
    // The size list is made of the flag's value: the flag is what to fix
    // (plait issue 41), as for a value used alone.
    let e = only_error(GOOD, &["params.size=10000"]);
    assert_eq!(
        e.location,
        Location::Flag {
            flag: "params.size=10000".into()
        }
    );
    assert_eq!(
        e.kind,
        ErrorKind::TextureSize {
            resource: "depth".into(),
            width: 10000,
            height: 10000,
            limit: 8192
        }
    );
    assert!(e.to_string().contains("8192"));
}

#[test]
fn unknown_keys_list_the_accepted_ones() {
    let text = edit(GOOD, "draw = \"hair\"", "draw = \"hair\"\nveiw = \"light\"");
    let e = load_text(&text, &[]).unwrap_err().0.remove(0);
    assert_eq!(e.location, at(22, 1));
    match &e.kind {
        ErrorKind::Schema(message) => {
            assert!(
                message.contains("`veiw`") && message.contains("view, draw"),
                "{message}"
            )
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn several_errors_are_reported_at_once_in_file_order() {
    let text = edit(GOOD, "type = \"shade\"", "type = \"shdae\"");
    let text = edit(&text, "format = \"rg32float\"", "format = \"rgba8unorm\"");
    let errors = errors_of(&text, &[]);
    let locations: Vec<_> = errors.iter().map(|e| e.location.clone()).collect();
    assert_eq!(locations, [at(22, 20), at(25, 8)]);
}

#[test]
fn raster_and_shader_requirements_are_checked() {
    let text = edit(GOOD, "draw = \"hair\"\n", "");
    let e = only_error(&text, &[]);
    assert!(
        matches!(&e.kind, ErrorKind::Pass { pass, message } if pass == "light_range" && message.contains("draw")),
        "{e}"
    );
    assert_eq!(e.location, at(18, 9));

    let text = edit(
        GOOD,
        "reads = { shadow = \"depth\" }",
        "view = \"camera\"\nreads = { shadow = \"depth\" }",
    );
    let e = only_error(&text, &[]);
    assert!(
        matches!(&e.kind, ErrorKind::Pass { message, .. } if message.contains("`view`")),
        "{e}"
    );
}

#[test]
fn missing_required_param_and_slot() {
    let text =
        format!("{GOOD}\n[passes.blurred]\ntype = \"blur\"\nwrites = {{ dst = \"final\" }}\n");
    let errors = errors_of(&text, &[]);
    let kinds: Vec<_> = errors.iter().map(|e| e.kind.clone()).collect();
    assert!(
        kinds.contains(&ErrorKind::MissingParam {
            pass: "blurred".into(),
            param: "radius".into()
        }),
        "{kinds:?}"
    );
    assert!(
        kinds.contains(&ErrorKind::MissingSlot {
            pass: "blurred".into(),
            direction: "input",
            slot: "src".into()
        }),
        "{kinds:?}"
    );
}

#[test]
fn undeclared_resources_and_outputs() {
    let text = edit(
        GOOD,
        "outputs = [\"final\"]",
        "outputs = [\"final\", \"missing\"]",
    );
    let text = edit(
        &text,
        "reads = { shadow = \"depth\" }",
        "reads = { shadow = \"dpeth\" }",
    );
    let errors = errors_of(&text, &[]);
    assert_eq!(
        errors[0].kind,
        ErrorKind::UnknownOutput {
            name: "missing".into(),
            hint: String::new()
        }
    );
    assert_eq!(errors[0].location, at(3, 21));
    // A typo of a declared resource suggests it.
    assert_eq!(
        errors[1].kind,
        ErrorKind::UndeclaredResource {
            name: "dpeth".into(),
            hint: "; did you mean `depth`?".into()
        }
    );
}

#[test]
fn extends_cycle_is_detected() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("extends_cycle");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("a.toml"),
        "[pipeline]\nname = \"a\"\nextends = \"b.toml\"\noutputs = []\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("b.toml"),
        "[pipeline]\nname = \"b\"\nextends = \"a.toml\"\noutputs = []\n",
    )
    .unwrap();
    let e = load(&dir.join("a.toml"), &[]).unwrap_err().0.remove(0);
    assert!(matches!(e.kind, ErrorKind::ExtendsCycle(_)), "{e}");
    assert_eq!(
        e.location,
        Location::File {
            path: dir.join("b.toml"),
            line: 3,
            column: 11
        }
    );
}

#[test]
fn missing_file_is_an_io_error_not_a_panic() {
    let e = load(std::path::Path::new("does/not/exist.toml"), &[])
        .unwrap_err()
        .0
        .remove(0);
    assert!(matches!(e.kind, ErrorKind::Io(_)));
    // The file is named without a line: it has none to point at.
    assert_eq!(
        e.location,
        Location::Path {
            path: "does/not/exist.toml".into()
        }
    );
    assert!(
        e.to_string()
            .starts_with("does/not/exist.toml: cannot read file:"),
        "{e}"
    );
}

/// A `--set` key that names nothing is an error on the flag that suggests the
/// nearest name, instead of a new key nothing reads.
#[test]
fn set_keys_that_match_nothing_suggest_the_nearest_name() {
    let cases: [(&str, &str); 7] = [
        (
            "params.sise=64",
            "there is no param `sise`; did you mean `size`?",
        ),
        (
            "passes.shaed.type=blur",
            "there is no pass `shaed`; did you mean `shade`?",
        ),
        (
            "passes.shade.prams.strength=2",
            "there is no key in [passes.shade] `prams`; did you mean `params`?",
        ),
        (
            "resources.finl.size=\"screen/2\"",
            "there is no resource `finl`; did you mean `final`?",
        ),
        ("resources.final.formt=rgba8unorm", "did you mean `format`?"),
        (
            "pipline.name=x",
            "there is no section `pipline`; did you mean `pipeline`?",
        ),
        ("pipeline.outptus=[]", "did you mean `outputs`?"),
    ];
    for (flag, message) in cases {
        let e = only_error(GOOD, &[flag]);
        assert_eq!(e.location, Location::Flag { flag: flag.into() }, "{e}");
        assert!(
            matches!(&e.kind, ErrorKind::UnknownSetKey { .. }),
            "{flag}: {e:?}"
        );
        assert!(e.to_string().contains(message), "{flag}: {e}");
    }
    // A name far from every candidate lists them without a guess.
    let e = only_error(GOOD, &["params.zzz=1"]);
    assert!(
        e.to_string()
            .ends_with("there is no param `zzz` (known: size)"),
        "{e}"
    );
}

/// What `--set` may still do: set a param the pass type has but the file
/// leaves at its default, and a param of the file.
#[test]
fn set_keys_the_pipeline_has_are_accepted() {
    compile_text(GOOD, &["passes.shade.params.strength=2", "params.size=64"])
        .expect("existing keys");
}

#[test]
fn misspelt_names_in_a_file_suggest_the_nearest() {
    let cases: [(&str, &str, &str); 5] = [
        (
            "type = \"shade\"",
            "type = \"shdae\"",
            "unknown pass type `shdae`; did you mean `shade`?",
        ),
        (
            "reads = { shadow = \"depth\" }",
            "reads = { shadwo = \"depth\" }",
            "has no input slot `shadwo`; did you mean `shadow`?",
        ),
        (
            "writes = { color = \"final\" }",
            "writes = { color = \"final\" }\nparams = { strenght = 2.0 }",
            "has no param `strenght`; did you mean `strength`?",
        ),
        (
            "writes = { color = \"final\" }",
            "writes = { color = \"final\" }\nparams = { mode = \"marchner\" }",
            "did you mean `marschner`?",
        ),
        (
            "draw = \"hair\"",
            "draw = \"hiar\"",
            "passes.light_range.draw is `hiar`; did you mean `hair`?",
        ),
    ];
    for (from, to, message) in cases {
        let text = edit(GOOD, from, to);
        let errors = errors_of(&text, &[]);
        assert!(
            errors.iter().any(|e| e.to_string().contains(message)),
            "{to}: expected `{message}` in:\n{}",
            Errors(errors.clone())
        );
    }
    let text = edit(
        GOOD,
        "kind = \"texture\"\nformat = \"rg32float\"",
        "kind = \"texture\"\nfromat = \"rg32float\"",
    );
    let errors = errors_of(&text, &[]);
    assert!(
        errors
            .iter()
            .any(|e| e.to_string().contains("unknown key `fromat`")
                && e.to_string().contains("did you mean `format`?")),
        "{}",
        Errors(errors.clone())
    );
}

/// A flag's value used inside a longer expression keeps the flag's
/// location (plait issue 41: `--set params.slices=0` blamed the technique
/// line); the same value written in the file keeps the file's; a string
/// that is no expression (a path) keeps its file, against which it resolves.
#[test]
fn a_flag_used_inside_an_expression_is_named_by_its_error() {
    let text = edit(
        GOOD,
        r#"size = ["${size}", "${size}"]"#,
        r#"size = ["${size} * 2", "${size} * 2"]"#,
    );
    let e = only_error(&text, &["params.size=0"]);
    assert_eq!(
        e.location,
        Location::Flag {
            flag: "params.size=0".into()
        },
        "{e}"
    );
    let in_file = edit(&text, "size = 256", "size = 0");
    assert_eq!(only_error(&in_file, &[]).location, at(11, 8));

    let path = edit(GOOD, "size = 256", "size = 256\ndir = \"a\"");
    let path = edit(
        &path,
        "type = \"shade\"",
        "type = \"shade\"\nshader = \"${dir}/s.wgsl\"",
    );
    let pipeline = load_text(&path, &["params.dir=b"]).expect("loads");
    let shade = &pipeline.passes["shade"];
    assert!(
        matches!(
            shade.shader.as_ref().map(|s| &s.location),
            Some(Location::File { .. })
        ),
        "{:?}",
        shade.shader
    );
}
