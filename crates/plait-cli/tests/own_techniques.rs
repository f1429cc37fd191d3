//! A technique folder beside a pipeline (its own `techniques/`) is a choice
//! of that pipeline, WGSL provider modules included: the shader library reads
//! the pipeline's own folder once the pipeline is loaded.

mod common;

use std::path::{Path, PathBuf};

use common::{plait, root, text};

/// Deep opacity copied as `my_dom` into `dir/techniques/` (its import path
/// and export renamed), beside a pipeline `dir/mine.toml` choosing it.
fn own_copy(dir: &Path) -> PathBuf {
    let point = dir.join("techniques/self_shadow");
    let mine = point.join("my_dom");
    std::fs::create_dir_all(&mine).expect("mkdir");
    let original = root().join("techniques/self_shadow");
    // The fragment deep opacity includes from its point's folder.
    std::fs::copy(
        original.join("light_range.toml"),
        point.join("light_range.toml"),
    )
    .expect("copy light_range.toml");
    let rename = |file: &str, from: &str, to: &str| {
        let text = std::fs::read_to_string(original.join("deep_opacity").join(file))
            .expect("the deep_opacity folder");
        assert!(text.contains(from), "{file} has no `{from}`");
        std::fs::write(mine.join(file), text.replace(from, to)).expect("write");
    };
    rename(
        "self_shadow.wgsl",
        "#define_import_path plait::self_shadow::deep_opacity",
        "#define_import_path plait::self_shadow::my_dom",
    );
    rename(
        "technique.toml",
        "self_shadow = \"deep_opacity\"",
        "self_shadow = \"my_dom\"",
    );
    let pipeline = dir.join("mine.toml");
    std::fs::write(
        &pipeline,
        "[pipeline]\nname = \"mine\"\nextends = \"occupancy.toml\"\n\n[techniques]\nself_shadow = \"my_dom\"\n",
    )
    .expect("write the pipeline");
    pipeline
}

#[test]
fn a_self_shadow_provider_beside_the_pipeline_renders_like_the_original() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pipeline = own_copy(dir.path());
    let render = |pipeline: &str, set: &str, out: &str| {
        let out = dir.path().join(out);
        let o = plait(&[
            "render",
            pipeline,
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            "48x36",
            "--set",
            "params.light_size=128",
            "--set",
            set,
            "--out",
            out.to_str().expect("utf-8"),
        ]);
        assert!(o.status.success(), "{}", text(&o.stderr));
        image::open(&out).expect("a PNG").to_rgba8()
    };
    let theirs = render(
        "pipelines/occupancy.toml",
        "techniques.self_shadow=deep_opacity",
        "theirs.png",
    );
    let mine = render(
        pipeline.to_str().expect("utf-8"),
        "techniques.transparency=occupancy_order",
        "mine.png",
    );
    assert!(mine == theirs, "the copied provider renders another image");
    // And it is not the default self-shadowing: the choice took effect.
    let default = render(
        "pipelines/occupancy.toml",
        "techniques.transparency=occupancy_order",
        "default.png",
    );
    assert!(mine != default, "the copy rendered the default technique");
}

/// The shader library is one per process: two pipelines checked together
/// whose own folders declare one module are an error naming both files.
#[test]
fn two_pipelines_whose_own_folders_declare_one_module_are_an_error() {
    let a = tempfile::tempdir().expect("tempdir");
    let b = tempfile::tempdir().expect("tempdir");
    let (pa, pb) = (own_copy(a.path()), own_copy(b.path()));
    let o = plait(&[
        "check",
        pa.to_str().expect("utf-8"),
        pb.to_str().expect("utf-8"),
    ]);
    let stderr = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("one module per import path"), "{stderr}");
    for dir in [a.path(), b.path()] {
        let file = dir.join("techniques/self_shadow/my_dom/self_shadow.wgsl");
        let file = file.canonicalize().expect("the copy");
        // At the line of its `#define_import_path`.
        let line = std::fs::read_to_string(&file)
            .expect("the copy")
            .lines()
            .position(|l| l.starts_with("#define_import_path"))
            .expect("an import path")
            + 1;
        let at = format!("{}:{line}:1", file.display());
        assert!(stderr.contains(&at), "{at} is not named: {stderr}");
    }
}
