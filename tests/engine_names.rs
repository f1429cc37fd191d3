//! No Rust names a technique (issue 41): what the engine must know about a
//! technique is a key of its `technique.toml` (`[technique] engine`,
//! `[param_ranges]`) or its point's `point.toml` (slots, params, defaults,
//! bindings), never a string match on its folder name. This test reads the
//! engine crates' sources and fails at the file:line of a string literal
//! naming a technique of point P where that line or the two before it also
//! name P (`t.point == "geometry" && t.name == "lod"`,
//! `params.get("lighting") == … "environment_reference"`,
//! `choice("shading", "kajiya_kay", …)`): the shapes a choice on a technique
//! takes; and at a path literal into a technique's folder
//! (`"techniques/transparency/depth_peeling/peel.wgsl"`), which the
//! technique's own data should name. Comments and `#[cfg(test)]` modules are
//! not read.

use std::path::{Path, PathBuf};

use plait_tests::repo_root;

/// The crates whose `src/` is the engine (the tools — plait-compare,
/// plait-book, plait-mutate — and benches and tests are not).
const ENGINE_CRATES: &[&str] = &[
    "plait-assets",
    "plait-graph",
    "plait-gpu",
    "plait-passes",
    "plait-hair",
    "plait",
    "plait-cli",
    "plait-view",
];

/// `(file, literal, reason)`: literals that are honestly not a technique
/// choice of the engine.
const ALLOWED: &[(&str, &str, &str)] = &[(
    "crates/plait/src/ab/path_traced.rs",
    "agx",
    "a path-traced reference is displayed by the CPU twin of the agx operator (crates/plait/src/ab/agx.rs), so a --set of another operator is refused, not followed: the literal names which twin exists",
)];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The code of each line before the file's `#[cfg(test)]`, comments cut.
fn code_lines(text: &str) -> Vec<String> {
    text.lines()
        .take_while(|l| l.trim() != "#[cfg(test)]")
        .map(|l| {
            let t = l.trim_start();
            if t.starts_with("//") {
                String::new()
            } else {
                // A ` // comment` after code (a "//" inside a string is rare
                // in these crates and only hides the rest of its line).
                l.split(" // ").next().unwrap_or("").to_owned()
            }
        })
        .collect()
}

/// `(point, technique)` for every technique folder of the checkout.
fn techniques(root: &Path) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for p in std::fs::read_dir(root.join("techniques"))
        .expect("techniques/")
        .flatten()
    {
        if !p.path().is_dir() {
            continue;
        }
        let point = p.file_name().to_string_lossy().into_owned();
        for t in std::fs::read_dir(p.path())
            .expect("a point folder")
            .flatten()
        {
            if t.path().join("technique.toml").is_file() {
                out.push((point.clone(), t.file_name().to_string_lossy().into_owned()));
            }
        }
    }
    out.sort();
    out
}

/// Every `file:line: …` where a literal names a technique of a point the
/// context names, but for [`ALLOWED`].
fn violations(root: &Path, files: &[PathBuf]) -> Vec<String> {
    let techniques = techniques(root);
    let mut found = Vec::new();
    for path in files {
        let rel = path
            .strip_prefix(root)
            .unwrap_or(path)
            .to_string_lossy()
            .replace('\\', "/");
        let text = std::fs::read_to_string(path).expect("read");
        let lines = code_lines(&text);
        for (i, line) in lines.iter().enumerate() {
            let context = lines[i.saturating_sub(2)..=i].join("\n");
            for (point, name) in &techniques {
                let literal = format!("\"{name}\"");
                let names_point = context.contains(&format!("\"{point}\""))
                    || context.contains(&format!("techniques.{point}"));
                if line.contains(&literal)
                    && names_point
                    && !ALLOWED.iter().any(|(f, l, _)| *f == rel && l == name)
                {
                    found.push(format!(
                        "{rel}:{}: `{name}` (a {point} technique) decides behaviour here: {}",
                        i + 1,
                        line.trim()
                    ));
                }
                // A file of the technique's folder named from Rust: the
                // technique's data should name it (a pass's `shader = …`).
                if line.contains(&format!("\"techniques/{point}/{name}/")) {
                    found.push(format!(
                        "{rel}:{}: a file of technique {point}/{name} is named here: {}",
                        i + 1,
                        line.trim()
                    ));
                }
            }
        }
    }
    found
}

#[test]
fn no_engine_source_names_a_technique() {
    let root = repo_root();
    let mut files = Vec::new();
    for c in ENGINE_CRATES {
        rust_files(&root.join("crates").join(c).join("src"), &mut files);
    }
    files.sort();
    assert!(files.len() > 50, "engine sources not found: {files:?}");
    let found = violations(&root, &files);
    assert!(
        found.is_empty(),
        "Rust names a technique; say what the engine needs in the technique's technique.toml or its point.toml instead:\n{}",
        found.join("\n")
    );
    // Each allowance still matches something, or it is stale.
    for (file, literal, _) in ALLOWED {
        let text = std::fs::read_to_string(root.join(file)).expect("allowed file");
        assert!(
            text.contains(&format!("\"{literal}\"")),
            "{file} no longer holds \"{literal}\": drop it from ALLOWED"
        );
    }
}

/// The check sees the shapes it is for.
#[test]
fn the_check_finds_a_technique_choice() {
    let root = repo_root();
    let dir = std::env::temp_dir().join(format!("plait-engine-names-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("choice.rs");
    std::fs::write(
        &file,
        "fn f(t: &T) -> bool {\n    // t.name == \"lod\" in a comment is fine\n    t.point == \"geometry\"\n        && t.name == \"lod\"\n}\nconst S: &str = \"techniques/geometry/wisps/x.wgsl\";\n#[cfg(test)]\nmod tests { const X: (&str, &str) = (\"geometry\", \"wisps\"); }\n",
    )
    .expect("write");
    let found = violations(&root, std::slice::from_ref(&file));
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(
        found[0].ends_with(
            ":4: `lod` (a geometry technique) decides behaviour here: && t.name == \"lod\""
        ),
        "{found:?}"
    );
    assert!(
        found[1].ends_with(":6: a file of technique geometry/wisps is named here: const S: &str = \"techniques/geometry/wisps/x.wgsl\";"),
        "{found:?}"
    );
}
