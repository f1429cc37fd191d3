//! An installed `plait` outside the checkout (issue 13, item 4): the binary
//! copied elsewhere renders the built-in scene from `/tmp` on its built-in
//! pipelines and shaders; a pipeline copied out of the repository finds the
//! file it extends and the library's shaders; a shader on the search path
//! replaces the built-in copy without a rebuild; `--version` names the build.

mod common;
use common::{root, text};

use std::path::Path;
use std::process::{Command, Output};

/// The `plait` binary copied into `dir` (as `cargo install` would put it),
/// run from `cwd` with `PLAIT_PATH` set to `plait_path` (`None`: unset).
fn installed(dir: &Path, cwd: &Path, plait_path: Option<&str>, args: &[&str]) -> Output {
    let exe = dir.join("plait");
    if !exe.exists() {
        std::fs::copy(env!("CARGO_BIN_EXE_plait"), &exe).expect("copy the binary");
    }
    let mut cmd = Command::new(&exe);
    cmd.current_dir(cwd).args(args);
    match plait_path {
        Some(p) => cmd.env("PLAIT_PATH", p),
        None => cmd.env_remove("PLAIT_PATH"),
    };
    common::run_copied(&mut cmd)
}

fn assert_ok(what: &str, o: &Output) {
    assert!(
        o.status.success(),
        "{what}: exit {:?}\n--- stderr:\n{}\n--- stdout:\n{}",
        o.status.code(),
        text(&o.stderr),
        text(&o.stdout)
    );
}

#[test]
fn a_copied_binary_renders_the_built_in_scene_from_tmp_with_built_in_files_only() {
    let bin = tempfile::tempdir().expect("temp dir");
    let cwd = tempfile::tempdir_in("/tmp").expect("temp dir in /tmp");
    // PLAIT_PATH set but empty: no folder is searched, only the copies built in.
    let o = installed(
        bin.path(),
        cwd.path(),
        Some(""),
        &[
            "render",
            "--size",
            "48x36",
            "--set",
            "params.light_size=128",
            "--out",
            "out.png",
        ],
    );
    assert_ok("render from /tmp", &o);
    let stdout = text(&o.stdout);
    assert!(
        stdout.contains("<built-in>/pipelines/occupancy.toml"),
        "the default pipeline should come from the built-in copy: {stdout}"
    );
    let image = image::open(cwd.path().join("out.png")).expect("a PNG in the working directory");
    assert_eq!((image.width(), image.height()), (48, 36));
    // A hair render, not a blank frame: some pixels differ from the corner (background).
    let rgb = image.to_rgb8();
    let corner = *rgb.get_pixel(0, 0);
    assert!(rgb.pixels().any(|p| *p != corner), "the image is uniform");
}

const COPIED: &str = r#"
[pipeline]
name = "copied"
extends = "occupancy_no_slab.toml"   # not next to this file: found on the search path
outputs = ["tinted"]

[resources.tinted]
kind = "texture"
format = "rgba8unorm"
size = "screen"

[passes.tint]
type = "fullscreen"
shader = "../shaders/compose_over.wgsl"   # the library's data-only compose shader
reads = { scene = "scene" }
writes = { out = "tinted" }
"#;

#[test]
fn a_pipeline_copied_out_of_the_repository_finds_its_base_and_the_library_shaders() {
    let bin = tempfile::tempdir().expect("temp dir");
    let elsewhere = tempfile::tempdir().expect("temp dir");
    let file = elsewhere.path().join("copied.toml");
    std::fs::write(&file, COPIED).expect("write the pipeline");
    let file = file.to_str().expect("utf-8 path");
    // Through the build checkout (PLAIT_PATH unset) and through the built-in copies alone.
    for plait_path in [None, Some("")] {
        let o = installed(bin.path(), elsewhere.path(), plait_path, &["check", file]);
        assert_ok(&format!("check with PLAIT_PATH={plait_path:?}"), &o);
        let o = installed(
            bin.path(),
            elsewhere.path(),
            plait_path,
            &["graph", file, "--format", "text"],
        );
        assert_ok("graph", &o);
        assert!(text(&o.stdout).contains("tint"), "{}", text(&o.stdout));
    }
}

#[test]
fn a_shader_on_plait_path_replaces_the_built_in_copy_without_a_rebuild() {
    let bin = tempfile::tempdir().expect("temp dir");
    let library = tempfile::tempdir().expect("temp dir");
    let passes = library.path().join("shaders/passes");
    std::fs::create_dir_all(&passes).expect("mkdir");
    let original = std::fs::read_to_string(root().join("shaders/passes/opaque_shade.wgsl"))
        .expect("the checkout's opaque_shade shader");
    // One line broken: the error must point at the copy on PLAIT_PATH.
    let broken = format!("{original}\nfn broken() -> f32 {{ return undefined_name; }}\n");
    let line = broken.lines().count();
    std::fs::write(passes.join("opaque_shade.wgsl"), &broken).expect("write");
    std::fs::create_dir_all(library.path().join("pipelines")).expect("mkdir");
    std::fs::copy(
        root().join("pipelines/forward.toml"),
        library.path().join("pipelines/forward.toml"),
    )
    .expect("copy forward.toml");
    let path_var = library.path().to_str().expect("utf-8 path");
    let o = installed(
        bin.path(),
        library.path(),
        Some(path_var),
        &["check", "pipelines/forward.toml"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o.stderr));
    let stderr = text(&o.stderr);
    assert!(
        stderr.contains(&format!("opaque_shade.wgsl:{line}:")),
        "the error should name the edited copy at line {line}: {stderr}"
    );
    // Fixed: the same binary accepts it again.
    std::fs::write(passes.join("opaque_shade.wgsl"), &original).expect("write");
    let o = installed(
        bin.path(),
        library.path(),
        Some(path_var),
        &["check", "pipelines/forward.toml"],
    );
    assert_ok("check after the fix", &o);
}

#[test]
fn version_names_the_build() {
    let o = Command::new(env!("CARGO_BIN_EXE_plait"))
        .arg("--version")
        .output()
        .expect("run plait");
    assert_ok("--version", &o);
    let stdout = text(&o.stdout);
    assert!(
        stdout.starts_with(&format!("plait {}", env!("CARGO_PKG_VERSION"))),
        "{stdout}"
    );
    // Built from a git checkout (as here): the commit is named.
    let in_git = Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .current_dir(root())
        .output()
        .ok()
        .filter(|o| o.status.success());
    if let Some(head) = in_git {
        let head = text(&head.stdout);
        assert!(
            stdout.contains(&format!("commit {}", head.trim())),
            "{stdout} should name commit {head}"
        );
    }
}

#[test]
fn every_built_in_gallery_pipeline_checks_without_any_folder_on_the_search_path() {
    let bin = tempfile::tempdir().expect("temp dir");
    let cwd = tempfile::tempdir().expect("temp dir");
    let gallery: Vec<String> = std::fs::read_dir(root().join("pipelines"))
        .expect("pipelines/")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .map(|n| format!("<built-in>/pipelines/{n}"))
        .collect();
    assert!(gallery.len() >= 10, "{gallery:?}");
    let mut args = vec!["check"];
    args.extend(gallery.iter().map(String::as_str));
    // Their `extends` and `../shaders/…` resolve among the built-in copies.
    let o = installed(bin.path(), cwd.path(), Some(""), &args);
    assert_ok("check the built-in gallery", &o);
    assert_eq!(
        text(&o.stdout)
            .lines()
            .filter(|l| l.starts_with("ok "))
            .count(),
        gallery.len()
    );
}

/// A technique is a folder the engine finds by itself: ShortCut's folder,
/// copied under a new name into a `PLAIT_PATH` folder, is a choice for an
/// installed binary (no rebuild, no registry) and renders exactly the image
/// of the original, which comes from the copies built in.
#[test]
fn a_technique_folder_dropped_on_the_search_path_is_a_choice_without_a_rebuild() {
    let bin = tempfile::tempdir().expect("temp dir");
    let cwd = tempfile::tempdir_in("/tmp").expect("temp dir in /tmp");
    let library = tempfile::tempdir().expect("temp dir");
    let original =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../techniques/transparency/shortcut");
    let copy = library.path().join("techniques/transparency/my_shortcut");
    std::fs::create_dir_all(&copy).expect("mkdir");
    let mut copied = Vec::new();
    for entry in std::fs::read_dir(&original).expect("the shortcut folder") {
        let path = entry.expect("entry").path();
        let name = path.file_name().expect("name").to_owned();
        std::fs::copy(&path, copy.join(&name)).expect("copy");
        copied.push(name.to_string_lossy().into_owned());
    }
    assert!(copied.iter().any(|f| f == "technique.toml"), "{copied:?}");
    let plait_path = library.path().to_str().expect("utf-8 path");
    let render = |technique: &str, out: &str| {
        let set = format!("techniques.transparency={technique}");
        let o = installed(
            bin.path(),
            cwd.path(),
            Some(plait_path),
            &[
                "render",
                "--size",
                "48x36",
                "--set",
                "params.light_size=128",
                "--set",
                &set,
                "--out",
                out,
            ],
        );
        assert_ok(&format!("render {technique}"), &o);
        let stdout = text(&o.stdout);
        assert!(
            stdout.contains(&format!("transparency/{technique}")),
            "{stdout}"
        );
        image::open(cwd.path().join(out)).expect("a PNG").to_rgba8()
    };
    let mine = render("my_shortcut", "mine.png");
    let theirs = render("shortcut", "theirs.png");
    assert!(mine == theirs, "the copied technique renders another image");
    // `plait techniques` lists it with its files.
    let o = installed(bin.path(), cwd.path(), Some(plait_path), &["techniques"]);
    assert_ok("techniques", &o);
    let listing = text(&o.stdout);
    assert!(
        listing.contains("my_shortcut") && listing.contains("technique.toml, depths.wgsl"),
        "{listing}"
    );
}
