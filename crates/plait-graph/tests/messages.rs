//! Messages a new user met (issue 20): a broken unquoted expression, the one
//! form of an unreadable file, suggestions without stray punctuation, and
//! the technique catalog listing only the params a technique uses.

mod common;

use common::*;
use plait_graph::*;

fn texts(errors: &[Error]) -> String {
    errors
        .iter()
        .map(|e| e.to_string())
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn an_unquoted_expression_is_reported_as_an_expression() {
    let cases = [
        // An incomplete expression: what is wrong with it.
        (
            "size = 1024 +",
            "`1024 +` is not a complete expression (expression ends too early)",
        ),
        ("size = (2 * 3", "(missing `)`)"),
        // A complete one: only the quotes are missing.
        (
            "size = 1024 * 2",
            "`1024 * 2` is an expression: write it as a string, `size = \"1024 * 2\"`",
        ),
        (
            "size = ${base} * 2   # twice",
            "`${base} * 2` is an expression: write it as a string",
        ),
    ];
    for (line, want) in cases {
        let text = edit(GOOD, "size = 256", line);
        let errors = load_text(&text, &[]).expect_err("does not parse").0;
        let message = texts(&errors);
        assert!(message.contains(want), "{line}: {message}");
        assert!(!message.contains("must be quoted"), "{line}: {message}");
        // The value's line and column (line 6, after `size = `).
        assert_eq!(errors[0].location, at(6, 8), "{line}: {message}");
    }
    // Not an expression: TOML's own message stays.
    let text = edit(GOOD, "size = 256", "size = two hundred");
    let message = texts(&load_text(&text, &[]).expect_err("bad").0);
    assert!(message.contains("TOML syntax error"), "{message}");
}

#[test]
fn a_missing_base_file_is_named_with_cannot_read_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let child = dir.path().join("child.toml");
    std::fs::write(&child, "[pipeline]\nextends = \"nope.toml\"\n").expect("write");
    let e = load(&child, &[]).expect_err("no base").0.remove(0);
    let message = e.to_string();
    let base = dir.path().join("nope.toml");
    assert!(
        message.starts_with(&format!(
            "{}:2:11: {}: cannot read file: ",
            child.display(),
            base.display()
        )),
        "{message}"
    );
}

#[test]
fn a_suggestion_ends_its_clause_before_the_list() {
    let text = edit(GOOD, "view = \"light\"", "view = \"lihgt\"");
    let message = texts(&errors_of(&text, &[]));
    assert!(
        message.contains("is `lihgt`; did you mean `light`? (accepted: light, camera)"),
        "{message}"
    );
    let text = edit(
        GOOD,
        "kind = \"texture\"\nformat = \"rg32float\"",
        "kind = \"textre\"\nformat = \"rg32float\"",
    );
    let message = texts(&errors_of(&text, &[]));
    assert!(
        message.contains(
            "did you mean `texture`? (accepted: texture, buffer, acceleration_structure)"
        ),
        "{message}"
    );
}

/// `occupancy_no_slab` includes `occupancy.toml` and replaces its slab
/// buffer by one counter per texel: the included `slabs` param then tunes
/// nothing and is not listed; `occupancy` itself lists it.
#[test]
fn the_catalog_lists_only_params_a_technique_uses() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../techniques");
    let catalog =
        techniques::catalog(&techniques::TechniqueRoots::at(root)).expect("the techniques parse");
    let params = |name: &str| -> Vec<String> {
        catalog
            .iter()
            .find(|t| t.point == "self_shadow" && t.name == name)
            .unwrap_or_else(|| panic!("no self_shadow/{name}"))
            .params
            .iter()
            .map(|(k, _)| k.clone())
            .collect()
    };
    assert_eq!(params("occupancy"), ["slices", "slabs"]);
    assert_eq!(params("occupancy_no_slab"), ["slices"]);
}
