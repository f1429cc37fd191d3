//! A technique folder beside a pipeline (its own `techniques/`) is a choice
//! of that pipeline, WGSL provider modules included: the shader library reads
//! the pipeline's own folder once the pipeline is loaded.

mod common;

use common::{plait, root, text};

#[test]
fn a_self_shadow_provider_beside_the_pipeline_renders_like_the_original() {
    let dir = tempfile::tempdir().expect("tempdir");
    let point = dir.path().join("techniques/self_shadow");
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
    let pipeline = dir.path().join("mine.toml");
    std::fs::write(
        &pipeline,
        "[pipeline]\nname = \"mine\"\nextends = \"occupancy.toml\"\n\n[techniques]\nself_shadow = \"my_dom\"\n",
    )
    .expect("write the pipeline");
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
