//! `[techniques]`: one key swaps a technique; every bad choice, file or
//! contract is an error with file:line:column (or the flag) that lists the
//! valid names.

use std::path::{Path, PathBuf};

use plait_graph::{Error, Location, load};

/// A pipeline file plus technique files in a fresh folder.
struct Tree {
    dir: tempfile::TempDir,
}

impl Tree {
    fn new(files: &[(&str, &str)]) -> Tree {
        let dir = tempfile::tempdir().expect("tempdir");
        // The fixtures' `shading` point is their own, data only: its
        // techniques export what these tests need (`look`, `lut`), which the
        // library's WGSL shading point (its contract in its point.toml)
        // would refuse as undeclared.
        let own_point = ("techniques/shading/point.toml", SHADING_POINT);
        let needs_point = files
            .iter()
            .any(|(p, _)| p.starts_with("techniques/shading/"))
            && !files.iter().any(|(p, _)| *p == own_point.0);
        for (path, text) in files.iter().chain(needs_point.then_some(&own_point)) {
            let p = dir.path().join(path);
            std::fs::create_dir_all(p.parent().expect("parent")).expect("mkdir");
            std::fs::write(p, text).expect("write");
        }
        Tree { dir }
    }

    fn path(&self, p: &str) -> PathBuf {
        self.dir.path().join(p)
    }
}

const PIPELINE: &str = r#"[pipeline]
name = "p"
outputs = ["out"]

[techniques]
shading = "flat"

[resources.out]
kind = "texture"
format = "rgba8unorm"
size = [4, 4]

[passes.draw]
type = "fullscreen"
shader = "s.wgsl"
uses = ["shading"]
writes = { out = "out" }
"#;

const FLAT: &str = r#"[technique]
point = "shading"
description = "flat colour"

[technique.exports]
params = { look = "flat", strength = "${flat_strength}" }
reads = { lut = "flat_lut" }

[params]
flat_strength = 0.5

[resources.flat_lut]
kind = "texture"
format = "rgba8unorm"
size = [2, 2]

[passes.make_lut]
type = "fullscreen"
shader = "lut.wgsl"
writes = { lut = "flat_lut" }
"#;

const SHADING_POINT: &str = "# The tests' own shading point: no WGSL contract.\n";

const TOON: &str = r#"[technique]
point = "shading"
description = "bands"

[technique.exports]
params = { look = "toon" }
"#;

fn tree() -> Tree {
    Tree::new(&[
        ("pipelines/p.toml", PIPELINE),
        ("techniques/shading/flat/technique.toml", FLAT),
        ("techniques/shading/toon/technique.toml", TOON),
    ])
}

fn errors_of(path: &Path, sets: &[&str]) -> Vec<Error> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    match load(path, &sets) {
        Ok(_) => panic!("expected an error loading {}", path.display()),
        Err(e) => e.0,
    }
}

fn at(e: &Error) -> (String, u32, u32) {
    match &e.location {
        Location::File { path, line, column } => (
            path.file_name().unwrap().to_string_lossy().into_owned(),
            *line,
            *column,
        ),
        other => (format!("{other}"), 0, 0),
    }
}

#[test]
fn a_choice_brings_its_data_and_exports_to_the_passes_that_use_it() {
    let t = tree();
    let p = load(&t.path("pipelines/p.toml"), &[]).expect("loads");
    assert!(p.resources.contains_key("flat_lut"));
    assert!(p.passes.contains_key("make_lut"));
    let draw = &p.passes["draw"];
    assert_eq!(
        draw.reads.get("lut").map(|r| r.value.as_str()),
        Some("flat_lut")
    );
    assert_eq!(draw.params["look"].value.to_string(), "\"flat\"");
    // Technique params are substituted like the pipeline's own.
    assert_eq!(draw.params["strength"].value.to_string(), "0.5");
    assert_eq!(p.techniques.len(), 1);
    assert_eq!(p.techniques[0].label(), "shading/flat");
    assert!(
        p.files
            .iter()
            .any(|f| f.ends_with("techniques/shading/flat/technique.toml"))
    );
}

#[test]
fn one_key_swaps_the_technique() {
    let t = tree();
    let p = load(
        &t.path("pipelines/p.toml"),
        &["techniques.shading=toon".into()],
    )
    .expect("loads");
    assert!(!p.resources.contains_key("flat_lut"), "flat's data is gone");
    assert_eq!(
        p.passes["draw"].params["look"].value.to_string(),
        "\"toon\""
    );
    assert!(!p.passes["draw"].reads.contains_key("lut"));
}

#[test]
fn the_pipeline_and_set_tune_a_techniques_params() {
    let t = tree();
    let p = load(
        &t.path("pipelines/p.toml"),
        &["params.flat_strength=0.9".into()],
    )
    .expect("a technique's param can be set");
    assert_eq!(p.passes["draw"].params["strength"].value.to_string(), "0.9");
}

#[test]
fn an_unknown_choice_lists_the_choices() {
    let t = tree();
    let e = errors_of(&t.path("pipelines/p.toml"), &["techniques.shading=ton"]);
    let text = e[0].to_string();
    assert!(matches!(&e[0].location, Location::Flag { flag } if flag == "techniques.shading=ton"));
    assert!(text.contains("did you mean `toon`"), "{text}");
    assert!(text.contains("toon | flat"), "{text}");

    let bad = PIPELINE.replace("shading = \"flat\"", "shading = \"flta\"");
    let t = Tree::new(&[
        ("pipelines/p.toml", &bad),
        ("techniques/shading/flat/technique.toml", FLAT),
    ]);
    let e = errors_of(&t.path("pipelines/p.toml"), &[]);
    assert_eq!(at(&e[0]), ("p.toml".into(), 6, 11), "{}", e[0]);
    assert!(e[0].to_string().contains("did you mean `flat`"));
}

#[test]
fn an_unknown_choice_point_lists_the_points() {
    let bad = PIPELINE.replace("shading = \"flat\"", "shadnig = \"flat\"");
    let t = Tree::new(&[
        ("pipelines/p.toml", &bad),
        ("techniques/shading/flat/technique.toml", FLAT),
    ]);
    let e = errors_of(&t.path("pipelines/p.toml"), &[]);
    assert_eq!(at(&e[0]), ("p.toml".into(), 6, 1), "{}", e[0]);
    assert!(
        e[0].to_string().contains("did you mean `shading`"),
        "{}",
        e[0]
    );
}

#[test]
fn using_a_point_nobody_chose_is_an_error() {
    let bad = PIPELINE.replace("uses = [\"shading\"]", "uses = [\"shadow\"]");
    let t = Tree::new(&[
        ("pipelines/p.toml", &bad),
        ("techniques/shading/flat/technique.toml", FLAT),
    ]);
    let e = errors_of(&t.path("pipelines/p.toml"), &[]);
    assert_eq!(at(&e[0]), ("p.toml".into(), 16, 9), "{}", e[0]);
    assert!(e[0].to_string().contains("chosen: shading"), "{}", e[0]);
}

/// The errors of choosing `flat` for shading beside a lighting technique
/// `sky` whose file ends with `sky_data`, and their text joined.
fn beside_a_sky(sky_data: &str) -> (Vec<Error>, String) {
    let pipeline = PIPELINE.replace(
        "shading = \"flat\"",
        "shading = \"flat\"\nlighting = \"sky\"",
    );
    let sky = format!("[technique]\npoint = \"lighting\"\ndescription = \"sky\"\n\n{sky_data}");
    let t = Tree::new(&[
        ("pipelines/p.toml", &pipeline),
        ("techniques/shading/flat/technique.toml", FLAT),
        ("techniques/lighting/sky/technique.toml", &sky),
    ]);
    let e = errors_of(&t.path("pipelines/p.toml"), &[]);
    let text = e
        .iter()
        .map(|e| e.to_string())
        .collect::<Vec<_>>()
        .join("\n");
    (e, text)
}

#[test]
fn two_techniques_defining_one_name_is_an_error() {
    let (e, text) = beside_a_sky(
        "[resources.flat_lut]\nkind = \"texture\"\nformat = \"rgba8unorm\"\nsize = [2, 2]\n",
    );
    assert!(
        text.contains("resources.flat_lut is defined by technique `shading/flat` too"),
        "{text}"
    );
    assert!(
        e.iter().any(|e| at(e) == ("technique.toml".into(), 5, 12)),
        "{text}"
    );
}

/// Technique params share the pipeline's one `[params]` table: a second
/// technique defining `flat_strength` would silently retune the first
/// (issue 41: a new technique's `slabs = 9` changed occupancy's slab count,
/// exit 0). Refused at the second definition, naming the first technique.
#[test]
fn two_techniques_defining_one_param_is_an_error() {
    let (e, text) = beside_a_sky("[params]\nflat_strength = 9\n");
    assert!(
        text.contains("params.flat_strength is defined by technique `shading/flat` too")
            && text.contains("give this one a name of its own (e.g. `sky_flat_strength`)"),
        "{text}"
    );
    assert!(
        e.iter().any(|e| at(e) == ("technique.toml".into(), 6, 1)),
        "{text}"
    );
    // The pipeline's own [params] still tunes a technique's param.
    let tuned = PIPELINE.replace(
        "[resources.out]",
        "[params]\nflat_strength = 0.25\n\n[resources.out]",
    );
    let t = Tree::new(&[
        ("pipelines/p.toml", &tuned),
        ("techniques/shading/flat/technique.toml", FLAT),
    ]);
    let p = load(&t.path("pipelines/p.toml"), &[]).expect("loads");
    assert_eq!(
        p.passes["draw"].params["strength"].value.to_string(),
        "0.25"
    );
}

#[test]
fn a_technique_in_the_wrong_folder_or_with_unknown_keys_is_an_error() {
    let wrong_point = FLAT.replace("point = \"shading\"", "point = \"lighting\"");
    let t = Tree::new(&[
        ("pipelines/p.toml", PIPELINE),
        ("techniques/shading/flat/technique.toml", &wrong_point),
    ]);
    let e = errors_of(&t.path("pipelines/p.toml"), &[]);
    assert_eq!(at(&e[0]), ("technique.toml".into(), 2, 9), "{}", e[0]);

    let typo = FLAT.replace("description =", "descripton =");
    let t = Tree::new(&[
        ("pipelines/p.toml", PIPELINE),
        ("techniques/shading/flat/technique.toml", &typo),
    ]);
    let e = errors_of(&t.path("pipelines/p.toml"), &[]);
    assert_eq!(at(&e[0]), ("technique.toml".into(), 3, 1), "{}", e[0]);
    assert!(
        e[0].to_string().contains("did you mean `description`"),
        "{}",
        e[0]
    );
}

#[test]
fn includes_share_a_fragment_and_a_missing_one_names_itself() {
    let with_include = FLAT.replace(
        "description = \"flat colour\"",
        "description = \"flat colour\"\nincludes = [\"../common.toml\"]",
    );
    let common = "[resources.shared]\nkind = \"buffer\"\nsize = 16\n";
    let t = Tree::new(&[
        ("pipelines/p.toml", PIPELINE),
        ("techniques/shading/flat/technique.toml", &with_include),
        ("techniques/shading/common.toml", common),
    ]);
    let p = load(&t.path("pipelines/p.toml"), &[]).expect("loads");
    assert!(p.resources.contains_key("shared"));
    // A fragment is not a choice.
    let choices =
        plait_graph::techniques::TechniqueRoots::at(t.path("techniques")).choices("shading");
    assert_eq!(choices, vec!["flat".to_string()]);

    let t = Tree::new(&[
        ("pipelines/p.toml", PIPELINE),
        ("techniques/shading/flat/technique.toml", &with_include),
    ]);
    let e = errors_of(&t.path("pipelines/p.toml"), &[]);
    assert_eq!(at(&e[0]), ("technique.toml".into(), 4, 13), "{}", e[0]);
    assert!(e[0].to_string().contains("common.toml"), "{}", e[0]);
}

/// A technique is a folder holding `technique.toml`: a folder without one is
/// an error at the choice that names it, naming the folder; `plait
/// techniques` (the catalog) reports it too.
#[test]
fn a_technique_folder_without_its_file_is_an_error() {
    let t = Tree::new(&[
        ("pipelines/p.toml", PIPELINE),
        ("techniques/shading/flat/flat.toml", FLAT),
    ]);
    let e = errors_of(&t.path("pipelines/p.toml"), &[]);
    let text = e
        .iter()
        .map(|e| e.to_string())
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        text.contains("techniques/shading/flat has no technique.toml") && at(&e[0]).0 == "p.toml",
        "{text}"
    );
    let roots = plait_graph::techniques::TechniqueRoots::at(t.path("techniques"));
    let listed = plait_graph::techniques::catalog(&roots).expect_err("refused");
    assert!(
        listed[0].to_string().contains("has no technique.toml"),
        "{}",
        listed[0]
    );
}

/// Two folders of the search path claiming one `<point>/<name>` is an error
/// naming both; the pipeline's own folder shadows the search path instead.
#[test]
fn two_search_path_folders_claiming_one_technique_is_an_error() {
    use plait_graph::techniques::{Located, TechniqueRoots};
    let a = Tree::new(&[("techniques/shading/flat/technique.toml", FLAT)]);
    let b = Tree::new(&[
        ("techniques/shading/flat/technique.toml", FLAT),
        ("techniques/shading/toon/technique.toml", TOON),
    ]);
    let roots = TechniqueRoots::new(None, vec![a.path("techniques"), b.path("techniques")]);
    match roots.locate("shading", "flat") {
        Located::Twice(x, y) => {
            assert!(x.starts_with(a.path("techniques")) && y.starts_with(b.path("techniques")))
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        roots.locate("shading", "toon"),
        Located::Found(b.path("techniques/shading/toon/technique.toml"))
    );
    assert_eq!(roots.choices("shading"), ["flat", "toon"]);
    let own = TechniqueRoots::new(Some(a.path("techniques")), vec![b.path("techniques")]);
    assert_eq!(
        own.locate("shading", "flat"),
        Located::Found(a.path("techniques/shading/flat/technique.toml"))
    );
}

/// A point file's promise (`[point] writes`) is held against every technique
/// chosen for the point: one that writes none of it is refused at its
/// `[technique]` table, naming the promise.
#[test]
fn a_technique_that_does_not_write_what_its_point_promises_is_an_error() {
    let promise = "[point]\nwrites = [\"flat_lut\"]\n";
    let t = Tree::new(&[
        ("pipelines/p.toml", PIPELINE),
        ("techniques/shading/point.toml", promise),
        ("techniques/shading/flat/technique.toml", FLAT),
        ("techniques/shading/toon/technique.toml", TOON),
    ]);
    // flat writes flat_lut: accepted.
    load(&t.path("pipelines/p.toml"), &[]).expect("flat keeps the promise");
    // toon writes nothing.
    let e = errors_of(
        &t.path("pipelines/p.toml"),
        &["techniques.shading=\"toon\""],
    );
    assert_eq!(at(&e[0]), ("technique.toml".into(), 1, 2), "{}", e[0]);
    let text = e[0].to_string();
    assert!(
        text.contains("shading technique `toon`: no pass writes `flat_lut`")
            && text.contains("point.toml:2:11"),
        "{text}"
    );
}

/// One fragment included by two chosen techniques (the density volume that
/// self_shadow and ambient_occlusion both read, issue 43) defines its names
/// once: the same keys at the same place are one definition, not a clash
/// (the same name written in each technique's own file still is one:
/// `two_techniques_defining_one_name_is_an_error`).
#[test]
fn one_fragment_included_by_two_techniques_is_defined_once() {
    let shared =
        "[resources.shared_map]\nkind = \"texture\"\nformat = \"rgba8unorm\"\nsize = [2, 2]\n";
    let flat = FLAT.replace(
        "description = \"flat colour\"",
        "description = \"flat colour\"\nincludes = [\"../../shared.toml\"]",
    );
    let sky = "[technique]\npoint = \"lighting\"\ndescription = \"sky\"\nincludes = [\"../../shared.toml\"]\n";
    let pipeline = PIPELINE.replace(
        "shading = \"flat\"",
        "shading = \"flat\"\nlighting = \"sky\"",
    );
    let t = Tree::new(&[
        ("pipelines/p.toml", &pipeline),
        ("techniques/shading/flat/technique.toml", &flat),
        ("techniques/lighting/sky/technique.toml", sky),
        ("techniques/shared.toml", shared),
    ]);
    if let Err(e) = load(&t.path("pipelines/p.toml"), &[]) {
        panic!("{:?}", e.0);
    }
}
