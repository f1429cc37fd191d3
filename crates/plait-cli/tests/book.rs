//! The book (`bash scripts/book.sh`): built once with this crate's `plait`,
//! it has a generated page for every technique the engine finds and every
//! gallery pipeline, no broken link, missing image or network load, and every
//! page renders in headless Chromium. The guide names only techniques that
//! exist.

mod common;

use std::collections::BTreeSet;
use std::path::Path;

use common::root;
use plait_book::{Generated, Options};

/// (point, name) of every technique `plait techniques --json` lists.
fn catalog() -> BTreeSet<(String, String)> {
    let out = common::plait(&["techniques", "--json"]);
    assert!(out.status.success(), "{}", common::text(&out.stderr));
    let list: serde_json::Value = serde_json::from_slice(&out.stdout).expect("techniques JSON");
    list.as_array()
        .expect("a list")
        .iter()
        .map(|t| {
            (
                t["point"].as_str().unwrap().to_string(),
                t["name"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

fn gallery() -> BTreeSet<String> {
    std::fs::read_dir(root().join("pipelines"))
        .expect("pipelines/")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".toml"))
        .collect()
}

/// One test, so the book (a couple of minutes of pictures on lavapipe) is
/// built once.
#[test]
fn the_book_has_a_page_per_technique_and_pipeline_and_opens_cleanly_in_chromium() {
    let dir = tempfile::tempdir().unwrap();
    let opts = Options {
        repo: root(),
        stage: dir.path().join("src"),
        out: dir.path().join("html"),
        plait: env!("CARGO_BIN_EXE_plait").into(),
        // Small pictures on one scene: the test is about pages, not images
        // (each picture is a `plait render` process, most of it start-up).
        figures: plait_book::FigureSettings {
            scenes: vec!["small.toml".into()],
            size: (96, 72),
        },
        live: None,
    };
    let built = plait_book::build(&opts).unwrap_or_else(|e| panic!("book: {e}"));

    let mut techniques = BTreeSet::new();
    let mut pipelines = BTreeSet::new();
    for g in &built.generated {
        let page = match g {
            Generated::Technique { point, name, page } => {
                techniques.insert((point.clone(), name.clone()));
                page
            }
            Generated::Pipeline { file, page } => {
                pipelines.insert(file.clone());
                page
            }
        };
        let html = built.out.join(Path::new(page).with_extension("html"));
        assert!(
            html.is_file(),
            "{} was generated but not built",
            html.display()
        );
    }
    assert_eq!(
        techniques,
        catalog(),
        "technique pages vs `plait techniques`"
    );
    assert_eq!(pipelines, gallery(), "pipeline pages vs pipelines/*.toml");

    // The default render's table is measured while the book builds.
    let first = built
        .out
        .join(Path::new(plait_book::DEFAULT_FRAME_PAGE).with_extension("html"));
    let first = std::fs::read_to_string(&first).expect("the first-render page");
    for row in [
        "$ plait render pipelines/default.toml   # what bash scripts/render.sh runs",
        "light_occupancy",
        "GPU ms",
        "frame",
    ] {
        assert!(
            first.contains(row),
            "the default frame's table lacks `{row}`"
        );
    }
    assert!(
        !first.contains("generated:default-frame"),
        "marker left in the page"
    );

    let problems = plait_book::check::check(&built.out);
    assert!(problems.is_empty(), "broken book:\n{}", join(&problems));

    let pages = plait_book::check::pages(&built.out);
    assert!(
        pages.len() > techniques.len() + pipelines.len(),
        "{} pages",
        pages.len()
    );
    let seen =
        plait_book::browser::check_pages(&built.out, &pages).unwrap_or_else(|e| panic!("{e}"));
    assert!(seen.is_empty(), "in Chromium:\n{}", join(&seen));
}

fn join<T: std::fmt::Display>(items: &[T]) -> String {
    items
        .iter()
        .map(|p| format!("  {p}"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// `techniques.POINT=NAME` (a `--set` or a sweep's `=A,B`) and
/// `POINT = "NAME"` written in the guide or the README name a technique that
/// exists: renaming or removing one fails here until the text follows.
#[test]
fn the_guide_and_readme_name_only_techniques_that_exist() {
    let known = catalog();
    let points: BTreeSet<&str> = known.iter().map(|(p, _)| p.as_str()).collect();
    let mut files = vec![root().join("README.md")];
    // The pages (a page's pictures may sit in a folder beside it).
    for e in std::fs::read_dir(root().join("book/src/guide")).unwrap() {
        let path = e.unwrap().path();
        if path.extension().is_some_and(|x| x == "md") {
            files.push(path);
        }
    }
    let mut checked = 0;
    let mut unknown = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        // A page that writes a technique out whole (`<!-- file:
        // techniques/POINT/NAME/… -->`, the worked example) may name it:
        // tests/worked_technique.rs runs those files.
        let mut known = known.clone();
        for line in text.lines() {
            let folder = line
                .strip_prefix("<!-- file: techniques/")
                .and_then(|rest| rest.split_once(" -->"))
                .map(|(path, _)| path.split('/').collect::<Vec<_>>());
            if let Some([point, name, _file]) = folder.as_deref() {
                known.insert((point.to_string(), name.to_string()));
            }
        }
        for (n, line) in text.lines().enumerate() {
            for (point, names) in mentions(line) {
                if !points.contains(point.as_str()) {
                    unknown.push(format!(
                        "{}:{}: no choice point `{point}`",
                        file.display(),
                        n + 1
                    ));
                    continue;
                }
                for name in names {
                    checked += 1;
                    // A misspelling shown with its correction on the same
                    // line (an error message quoted) is the one exception.
                    let corrected = known.iter().any(|(p, k)| {
                        *p == point && line.contains(&format!("`{k}`")) && close(k, &name)
                    });
                    if !known.contains(&(point.clone(), name.clone())) && !corrected {
                        unknown.push(format!(
                            "{}:{}: no technique `{point}.{name}`",
                            file.display(),
                            n + 1
                        ));
                    }
                }
            }
        }
    }
    assert!(unknown.is_empty(), "{}", unknown.join("\n"));
    assert!(
        checked > 10,
        "only {checked} technique names found: is the scan broken?"
    );
}

/// Within two single-character edits (a typo, not another technique).
fn close(a: &str, b: &str) -> bool {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for i in 1..=a.len() {
        let mut prev = row[0];
        row[0] = i;
        for j in 1..=b.len() {
            let cur = row[j];
            row[j] = (row[j] + 1)
                .min(row[j - 1] + 1)
                .min(prev + usize::from(a[i - 1] != b[j - 1]));
            prev = cur;
        }
    }
    row[b.len()] <= 2
}

/// `techniques.POINT=A,B` mentions in a line.
fn mentions(line: &str) -> Vec<(String, Vec<String>)> {
    let word = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(i) = rest.find("techniques.") {
        rest = &rest[i + "techniques.".len()..];
        let point: String = rest.chars().take_while(|&c| word(c)).collect();
        let after = &rest[point.len()..];
        let Some(values) = after.strip_prefix('=') else {
            continue;
        };
        let end = values
            .find(|c: char| !(word(c) || c == ','))
            .unwrap_or(values.len());
        let mut names: Vec<String> = values[..end]
            .split(',')
            .filter(|n| !n.is_empty())
            .map(str::to_string)
            .collect();
        // In a benchmark's `--variant KEY=V,KEY=V` a comma also separates
        // sets: an item followed by `.` is the next set's key (`techniques`,
        // `params`), not a technique.
        if values[end..].starts_with('.') {
            names.pop();
        }
        if !point.is_empty() && !names.is_empty() {
            out.push((point, names));
        }
    }
    out
}

#[test]
fn mentions_are_read_from_set_flags_and_sweeps() {
    assert_eq!(
        mentions(
            "--set techniques.self_shadow=exact --sweep techniques.transparency=a,b_c --out x"
        ),
        [
            ("self_shadow".to_string(), vec!["exact".to_string()]),
            (
                "transparency".to_string(),
                vec!["a".to_string(), "b_c".to_string()]
            ),
        ]
    );
    assert!(mentions("the techniques.toml file").is_empty());
    assert_eq!(
        mentions(
            "--variant techniques.transparency=compute_raster,techniques.shading_space=strand,params.tile_size=8"
        ),
        [
            (
                "transparency".to_string(),
                vec!["compute_raster".to_string()]
            ),
            ("shading_space".to_string(), vec!["strand".to_string()]),
        ]
    );
}
