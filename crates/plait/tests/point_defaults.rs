//! A point's defaults flow from its `point.toml` (issue 41 item 2): a
//! library whose shading point file names another default technique and
//! another default fibre compiles pipelines with them and gives
//! `Fibre::standard` that fibre. Rust repeating a default would keep the
//! shipped one and fail here.

use std::path::{Path, PathBuf};

use plait::mitsuba::Fibre;
use plait_graph::{CompileOptions, Value};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("checkout")
}

/// Replaces exactly one occurrence of `from`.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "`{from}` must occur once");
    text.replace(from, to)
}

/// The forward pipeline with its hair pass taking the shading point
/// unchosen: the point's defaults decide the technique and its params.
const PIPELINE: &str = r#"
[pipeline]
name = "point_defaults"
extends = "forward.toml"

[passes.hair]
uses = ["lighting", "ambient_occlusion", "multiple_scattering"]
"#;

/// The shading pass's value of `param` in the compiled schedule.
fn compiled_param(library: &plait_gpu::PassLibrary, pipeline: &Path, param: &str) -> Value {
    let opts = CompileOptions::default();
    let schedule = plait::session::compile_checked_in(library, pipeline, &[], &opts)
        .unwrap_or_else(|e| panic!("compiles: {e}"));
    let hair = schedule
        .passes
        .iter()
        .find(|p| p.name == "hair")
        .expect("the hair pass");
    hair.params
        .get(param)
        .unwrap_or_else(|| panic!("the hair pass has no `{param}`"))
        .clone()
}

#[test]
fn a_changed_shading_point_default_reaches_the_schedule_and_the_fibre() {
    let dir = tempfile::tempdir().expect("temp dir");
    let pipeline = dir.path().join("point_defaults.toml");
    std::fs::write(&pipeline, PIPELINE).expect("write pipeline");

    // The shipped library: its point file's defaults.
    let shipped = plait_passes::read_library(&[]);
    let shipped_fibre = Fibre::standard(&shipped);
    assert_eq!(shipped_fibre.longitudinal_roughness, 0.3);
    assert_eq!(
        compiled_param(&shipped, &pipeline, "shading"),
        Value::Str("kajiya_kay".into())
    );

    // A library root before the search path whose shading point names
    // another default technique and another longitudinal roughness.
    let point =
        std::fs::read_to_string(root().join("techniques/shading/point.toml")).expect("point file");
    let point = edit(&point, "default = \"kajiya_kay\"", "default = \"chiang\"");
    let point = edit(
        &point,
        "[params.chiang_beta_m]\ntype = \"float\"\ndefault = 0.3",
        "[params.chiang_beta_m]\ntype = \"float\"\ndefault = 0.41",
    );
    let own = dir.path().join("library");
    std::fs::create_dir_all(own.join("techniques/shading")).expect("folder");
    std::fs::write(own.join("techniques/shading/point.toml"), point).expect("write point");
    let library = plait_passes::read_library(&[own]);

    let fibre = Fibre::standard(&library);
    assert_eq!(fibre.longitudinal_roughness, 0.41);
    assert_eq!(fibre.azimuthal_roughness, shipped_fibre.azimuthal_roughness);
    assert_eq!(
        compiled_param(&library, &pipeline, "shading"),
        Value::Str("chiang".into())
    );
    assert_eq!(
        compiled_param(&library, &pipeline, "chiang_beta_m"),
        Value::Float(0.41)
    );
}
