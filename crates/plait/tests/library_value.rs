//! The library is a value (issue 41 items 1 and 4): a session reads its
//! shaders once, when it compiles, and builds with the text it compiled; a
//! new value reads the files as they are then.

use std::path::{Path, PathBuf};

use plait::session::{SceneData, prepare_compiled};
use plait::source::PipelineSource;
use plait_gpu::Gpu;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("checkout")
}

/// The gallery's forward pipeline with its compose shader read from the
/// pipeline's folder: the file the test edits.
const PIPELINE: &str = r#"
[pipeline]
name = "edited"
extends = "forward.toml"

[passes.compose]
shader = "compose.wgsl"
"#;

#[test]
fn a_build_composes_the_text_its_compile_read_and_a_new_library_reads_the_edit() {
    let dir = tempfile::tempdir().expect("temp dir");
    let original =
        std::fs::read_to_string(root().join("shaders/compose_over.wgsl")).expect("compose_over");
    let shader = dir.path().join("compose.wgsl");
    std::fs::write(&shader, &original).expect("write shader");
    let pipeline = dir.path().join("edited.toml");
    std::fs::write(&pipeline, PIPELINE).expect("write pipeline");
    let sets = vec!["params.light_size=64".to_owned()];
    let size = (32, 24);

    let gpu = Gpu::new().expect("an adapter");
    let scene = SceneData::load(Some(&root().join("examples/scenes/small.toml"))).expect("scene");
    let source = PipelineSource::new(&pipeline, &sets);
    let loaded = source.load(&[]).expect("loads");
    let schedule = plait::adapter::compile_on(&gpu, &loaded, &source, size).expect("compiles");
    let reads = source.library.shaders.file_reads();
    assert!(reads > 0, "compile read the shaders");

    // Broken after compile, before build: the build uses what compile read.
    let broken = format!("{original}\nfn broken( {{\n");
    std::fs::write(&shader, &broken).expect("break shader");
    let prepared = prepare_compiled(&gpu, schedule, &source, &scene, size)
        .unwrap_or_else(|e| panic!("the build re-read the edited shader: {e}"));
    prepared.image().expect("renders");
    assert_eq!(
        source.library.shaders.file_reads(),
        reads,
        "the build read a shader file again"
    );

    // A new library value (the viewer's and --watch's reload) sees the edit.
    let again = PipelineSource::new(&pipeline, &sets);
    let loaded = again.load(&[]).expect("loads");
    let Err(err) = plait::adapter::compile_on(&gpu, &loaded, &again, size) else {
        panic!("the broken shader should be refused by a new library value");
    };
    assert!(err.to_string().contains("compose.wgsl"), "{err}");
}

/// Pass types are resolved once, at compile, into a handle on each pass
/// (issue 41 item 4): the library hands the build the type the handle names,
/// and a handle that names another type (a schedule compiled with another
/// library) is refused rather than looked up again by name.
#[test]
fn a_compiled_pass_carries_its_type_as_a_handle() {
    let source = PipelineSource::new(&root().join("pipelines/occupancy.toml"), &[]);
    let opts = plait_graph::CompileOptions::default();
    let schedule = source.compile(&[], &opts).expect("compiles");
    assert!(!schedule.passes.is_empty());
    for pass in &schedule.passes {
        let id = pass.type_id.expect("resolved at compile");
        let (name, _) = source
            .library
            .types
            .get_index(id.index())
            .expect("in the library");
        assert_eq!(*name, pass.type_name, "pass `{}`", pass.name);
        assert!(source.library.pass_type(pass).is_some());
    }
    // Another type's handle: refused, not looked up again by name.
    let mut pass = schedule.passes[0].clone();
    let other = (0..source.library.types.len())
        .find(|&i| source.library.types.get_index(i).map(|(n, _)| n) != Some(&pass.type_name))
        .expect("a library of more than one type");
    pass.type_id = Some(plait_graph::PassTypeId::new(other));
    assert!(source.library.pass_type(&pass).is_none());
}
