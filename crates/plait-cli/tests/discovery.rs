//! The engine finds techniques, their WGSL providers and pass types in the
//! folders of the search path by itself: a folder dropped into a `PLAIT_PATH`
//! folder is used by the built binary without a rebuild, and what is wrong in
//! it is an error at its file, line and column with exit code 2.

mod common;
use common::{assert_ok, assert_refused, root, text, with_library, write};

use std::path::Path;

const HALF_TECHNIQUE: &str = r#"
[technique]
point = "self_shadow"
description = "Half the light everywhere (a test provider)"
source = "—"
memory = "0"

[technique.exports]
params = { self_shadow = "half" }
"#;

const HALF_PROVIDER: &str = "#define_import_path plait::self_shadow::half\n\n\
fn hair_visibility(world: vec3<f32>) -> f32 {\n    return 0.5;\n}\n";

/// A library folder holding the two-file technique `self_shadow/half`, its
/// provider's WGSL as given.
fn half_technique(provider: &str) -> tempfile::TempDir {
    let library = tempfile::tempdir().expect("temp dir");
    let folder = "techniques/self_shadow/half";
    write(
        library.path(),
        &format!("{folder}/technique.toml"),
        HALF_TECHNIQUE,
    );
    write(
        library.path(),
        &format!("{folder}/self_shadow.wgsl"),
        provider,
    );
    library
}

/// A self-shadowing technique that is one folder of two files on
/// `PLAIT_PATH` is listed, checks and renders; its provider is found from
/// its `#define_import_path` alone (the selector is generated).
#[test]
fn a_provider_in_a_technique_folder_on_plait_path_is_a_choice_without_a_rebuild() {
    let library = half_technique(HALF_PROVIDER);
    let o = with_library(library.path(), &["techniques"]);
    assert_ok("plait techniques", &o);
    let listed = text(&o.stdout);
    assert!(
        listed.contains("self_shadow/half/ technique.toml, self_shadow.wgsl"),
        "the new technique and its provider file are listed:\n{listed}"
    );
    let out = library.path().join("half.png");
    let out = out.to_str().expect("utf-8");
    let o = with_library(
        library.path(),
        &[
            "render",
            "pipelines/occupancy.toml",
            "--set",
            "techniques.self_shadow=half",
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            "48x36",
            "--out",
            out,
        ],
    );
    assert_ok("render with the new provider", &o);
    assert!(Path::new(out).is_file());
}

/// What is wrong in a dropped folder is an error at its place, exit 2.
#[test]
fn a_broken_provider_or_pass_type_on_plait_path_is_an_error_at_its_line() {
    // An #import no module provides.
    let library =
        half_technique(&HALF_PROVIDER.replace("\n\nfn", "\n#import plait::fram::frame\n\nfn"));
    let o = with_library(library.path(), &["check", "pipelines/forward.toml"]);
    assert_refused(
        "an unknown import",
        &o,
        &[
            "self_shadow/half/self_shadow.wgsl:2:9",
            "`#import plait::fram::frame`",
            "did you mean `plait::frame`",
        ],
    );

    // Two folders claiming one module.
    let library = tempfile::tempdir().expect("temp dir");
    write(
        library.path(),
        "shaders/lib/again.wgsl",
        "#define_import_path plait::frame\n",
    );
    let o = with_library(library.path(), &["check", "pipelines/forward.toml"]);
    assert_refused(
        "a module declared twice",
        &o,
        &[
            "again.wgsl:1:1",
            "`#define_import_path plait::frame`",
            "declares too",
        ],
    );

    // A pass-type file with a typo: found by itself, refused at the key.
    let library = tempfile::tempdir().expect("temp dir");
    write(
        library.path(),
        "shaders/passes/tint.toml",
        "[pass_type]\nname = \"tint\"\nshape = \"fullscreen\"\nsource = \"-\"\n\
         description = \"-\"\nshader = \"tint.wgsl\"\nblnd = \"over\"\n",
    );
    write(library.path(), "shaders/passes/tint.wgsl", "");
    let o = with_library(library.path(), &["check", "pipelines/forward.toml"]);
    assert_refused(
        "a broken pass-type file",
        &o,
        &["shaders/passes/tint.toml:7:1", "unknown key `blnd`"],
    );
}

/// A pass type declared by two files on `PLAIT_PATH` is usable by name from
/// a pipeline, with no line of Rust and no rebuild.
#[test]
fn a_pass_type_dropped_on_plait_path_is_usable_by_name() {
    let library = tempfile::tempdir().expect("temp dir");
    write(
        library.path(),
        "shaders/passes/tint.toml",
        r#"[pass_type]
name = "tint"
shape = "fullscreen"
source = "-"
description = "Copies the scene, tinted (a test pass type)."
shader = "tint.wgsl"

[inputs.scene]
kind = "texture"
access = "sampled"
doc = "the image to tint"

[outputs.out]
kind = "texture"
access = "color_target"
doc = "tinted"
"#,
    );
    write(
        library.path(),
        "shaders/passes/tint.wgsl",
        std::fs::read_to_string(root().join("shaders/compose_over.wgsl"))
            .expect("the compose shader")
            .as_str(),
    );
    let pipeline = library.path().join("tinted.toml");
    std::fs::write(
        &pipeline,
        r#"[pipeline]
name = "tinted"
extends = "forward.toml"
outputs = ["tinted"]

[resources.tinted]
kind = "texture"
format = "rgba8unorm"
size = "screen"

[passes.tint]
type = "tint"
reads = { scene = "scene" }
writes = { out = "tinted" }
"#,
    )
    .expect("write");
    let o = with_library(
        library.path(),
        &["check", pipeline.to_str().expect("utf-8")],
    );
    assert_ok("check a pipeline using the dropped pass type", &o);
}
