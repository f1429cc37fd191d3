//! A choice point's contract is its `point.toml` (issue 41): the slots,
//! params and binding range its providers may use are data, checked against
//! every technique and provider at load (file:line:col, exit 2), and a slot
//! name new to the library reaches the Rust pass types too.

mod common;
use common::{assert_ok, assert_refused, plait, root, with_library, write};

use std::path::Path;
use std::process::Output;

const HALFMAP_TECHNIQUE: &str = r#"
[technique]
point = "self_shadow"
description = "Half the light, read from a map a pass fills (a test provider)"
source = "—"
memory = "4 B"

[technique.exports]
reads = { vis_half = "light_half" }
params = { self_shadow = "halfmap" }

[resources.light_half]
kind = "buffer"
size = "4"

[passes.half_fill]
type = "compute"
shader = "half_fill.wgsl"
writes = { half = "light_half" }
"#;

const HALF_FILL: &str = "@group(1) @binding(0) var<storage, read_write> half: array<f32>;\n\n\
@compute @workgroup_size(64)\nfn main(@builtin(global_invocation_id) id: vec3<u32>) {\n    \
if id.x == 0u {\n        half[0] = 0.5;\n    }\n}\n";

/// The provider reads the new slot at `binding`.
fn halfmap_provider(binding: u32) -> String {
    format!(
        "#define_import_path plait::self_shadow::halfmap\n\n\
         @group(1) @binding({binding}) var<storage, read> vis_half: array<f32>;\n\n\
         fn hair_visibility(world: vec3<f32>) -> f32 {{\n    return vis_half[0];\n}}\n"
    )
}

/// The built-in self_shadow point file, with `extra` appended.
fn self_shadow_point(extra: &str) -> String {
    let built_in = std::fs::read_to_string(root().join("techniques/self_shadow/point.toml"))
        .expect("the self_shadow point file");
    format!("{built_in}{extra}")
}

const VIS_HALF: &str = "\n[inputs.vis_half]\nkind = \"buffer\"\naccess = \"storage_read\"\n\
doc = \"halfmap: the fraction of light, one f32\"\n";

/// A library with the technique `self_shadow/halfmap` (its provider at
/// `binding`) and, when `declare`, the self_shadow point file declaring its
/// slot `vis_half`.
fn halfmap_library(binding: u32, declare: bool) -> tempfile::TempDir {
    let library = tempfile::tempdir().expect("temp dir");
    let folder = "techniques/self_shadow/halfmap";
    write(
        library.path(),
        &format!("{folder}/technique.toml"),
        HALFMAP_TECHNIQUE,
    );
    write(
        library.path(),
        &format!("{folder}/half_fill.wgsl"),
        HALF_FILL,
    );
    write(
        library.path(),
        &format!("{folder}/self_shadow.wgsl"),
        &halfmap_provider(binding),
    );
    if declare {
        write(
            library.path(),
            "techniques/self_shadow/point.toml",
            &self_shadow_point(VIS_HALF),
        );
    }
    library
}

/// The default pipeline, copied into `library` so that the library's
/// `techniques/` is its own (a pipeline's own folder comes before the search
/// path's, and the checkout's would otherwise win): its path.
fn own_pipeline(library: &Path) -> String {
    let text = std::fs::read_to_string(root().join("pipelines/occupancy.toml")).expect("occupancy");
    write(library, "pipelines/occupancy.toml", &text);
    library
        .join("pipelines/occupancy.toml")
        .to_str()
        .expect("utf-8")
        .to_owned()
}

fn render(library: &Path, technique: &str, out: &Path) -> Output {
    with_library(
        library,
        &[
            "render",
            &own_pipeline(library),
            "--set",
            &format!("techniques.self_shadow={technique}"),
            "--scene",
            "examples/scenes/small.toml",
            "--size",
            "48x36",
            "--out",
            out.to_str().expect("utf-8"),
        ],
    )
}

/// A slot name no Rust knows (`vis_half`), declared by a line of the point
/// file and bound by a data-only technique, reaches the Rust pass type
/// `opaque_shade` (the head's shading, which takes the self_shadow slots) as
/// well as the data-only hair passes: the picture equals the one a provider
/// returning the constant 0.5 draws.
#[test]
fn a_new_slot_name_in_the_point_file_works_for_every_pass_type() {
    let library = halfmap_library(12, true);
    let mapped = library.path().join("mapped.png");
    assert_ok(
        "render with vis_half",
        &render(library.path(), "halfmap", &mapped),
    );
    // The same technique reading no map: its provider returns the 0.5.
    let constant = halfmap_library(12, true);
    write(
        constant.path(),
        "techniques/self_shadow/halfmap/technique.toml",
        &HALFMAP_TECHNIQUE.replace("reads = { vis_half = \"light_half\" }\n", ""),
    );
    write(
        constant.path(),
        "techniques/self_shadow/halfmap/self_shadow.wgsl",
        "#define_import_path plait::self_shadow::halfmap\n\n\
         fn hair_visibility(world: vec3<f32>) -> f32 {\n    return 0.5;\n}\n",
    );
    let reference = constant.path().join("constant.png");
    assert_ok(
        "render with 0.5",
        &render(constant.path(), "halfmap", &reference),
    );
    let a = std::fs::read(&mapped).expect("mapped.png");
    let b = std::fs::read(&reference).expect("constant.png");
    assert!(
        a == b,
        "the map's 0.5 and the constant 0.5 differ: vis_half was not bound as declared"
    );
}

/// Without the point file's line the technique's export is refused at its
/// place, naming the point file.
#[test]
fn a_read_the_point_does_not_declare_is_refused_at_the_export() {
    let library = halfmap_library(12, false);
    let o = with_library(
        library.path(),
        &[
            "check",
            &own_pipeline(library.path()),
            "--set",
            "techniques.self_shadow=halfmap",
        ],
    );
    assert_refused(
        "undeclared slot",
        &o,
        &[
            "self_shadow/halfmap/technique.toml:9:11:",
            "exports a read of slot `vis_half`, which",
            "techniques/self_shadow/point.toml does not declare",
        ],
    );
}

/// A provider binding outside its point's range is refused at the binding.
#[test]
fn a_provider_binding_outside_its_range_is_refused_at_its_line() {
    let library = halfmap_library(16, true);
    let o = with_library(library.path(), &["check", &own_pipeline(library.path())]);
    assert_refused(
        "binding 16",
        &o,
        &[
            "self_shadow/halfmap/self_shadow.wgsl:3:11:",
            "declares @group(1) @binding(16), outside the point's bindings 8–15",
            "techniques/self_shadow/point.toml:",
        ],
    );
}

/// A technique tuning a point param away from the point's default, or
/// exporting a param the point lacks, is refused at its line.
#[test]
fn a_technique_param_must_be_the_points() {
    let library = tempfile::tempdir().expect("temp dir");
    let chiang = std::fs::read_to_string(root().join("techniques/shading/chiang/technique.toml"))
        .expect("chiang");
    let changed = chiang
        .replace("chiang_beta_n = 0.3\n", "chiang_beta_n = 0.4\n")
        .replace(
            "chiang_eta = \"${chiang_eta}\"",
            "chiang_etta = \"${chiang_eta}\"",
        );
    assert_ne!(chiang, changed);
    write(
        library.path(),
        "techniques/shading/chiang/technique.toml",
        &changed,
    );
    let o = with_library(
        library.path(),
        &[
            "check",
            &own_pipeline(library.path()),
            "--set",
            "techniques.shading=chiang",
        ],
    );
    // The point's `[params.chiang_beta_n]` (at its name), by search: the
    // point file's other entries move it.
    let point = std::fs::read_to_string(root().join("techniques/shading/point.toml"))
        .expect("the shading point");
    let line = 1 + point
        .lines()
        .position(|l| l == "[params.chiang_beta_n]")
        .expect("[params.chiang_beta_n]");
    let at = format!("techniques/shading/point.toml:{line}:9)");
    assert_refused(
        "default and export",
        &o,
        &[
            "`chiang_beta_n = 0.4` differs from the point's default 0.3 (",
            &at,
            "exports param `chiang_etta`, which ",
            "techniques/shading/point.toml does not declare; did you mean `chiang_eta`?",
        ],
    );
}

/// A technique's own range is checked against the value the pipeline ends
/// with: at the flag, or at the pipeline's line.
#[test]
fn a_technique_param_range_names_the_flag_or_the_line() {
    let o = plait(&[
        "check",
        "pipelines/occupancy.toml",
        "--set",
        "techniques.shading=chiang",
        "--set",
        "params.chiang_beta_n=0.1",
    ]);
    assert_refused(
        "β_n 0.1",
        &o,
        &[
            "--set params.chiang_beta_n=0.1: param `chiang_beta_n` = 0.1 is out of shading technique chiang's range 0.15…1 (techniques/shading/chiang/technique.toml:",
        ],
    );
    let dir = tempfile::tempdir().expect("temp dir");
    let pipeline = dir.path().join("p.toml");
    std::fs::write(
        &pipeline,
        format!(
            "[pipeline]\nextends = \"{}\"\n\n[techniques]\nshading = \"chiang\"\n\n[params]\nchiang_tilt = 12.0\n",
            root().join("pipelines/occupancy.toml").display()
        ),
    )
    .expect("write");
    let o = plait(&["check", pipeline.to_str().expect("utf-8")]);
    assert_refused(
        "tilt 12",
        &o,
        &[
            "p.toml:8:15: param `chiang_tilt` = 12 is out of shading technique chiang's range -10…10",
        ],
    );
    let o = plait(&[
        "check",
        "pipelines/occupancy.toml",
        "--set",
        "techniques.shading=chiang",
        "--set",
        "params.chiang_beta_n=0.15",
    ]);
    assert_ok("β_n at its bound", &o);
}

/// `[technique] engine` and `[param_ranges]` are checked where written.
#[test]
fn engine_needs_and_ranges_are_checked_in_the_technique_file() {
    let library = tempfile::tempdir().expect("temp dir");
    let wisps = std::fs::read_to_string(root().join("techniques/geometry/wisps/technique.toml"))
        .expect("wisps");
    let bad = wisps.replace("engine = [\"wisp_mesh\"]", "engine = [\"wisp_mesch\"]");
    assert_ne!(wisps, bad);
    write(
        library.path(),
        "techniques/geometry/wisps/technique.toml",
        &bad,
    );
    let chiang = std::fs::read_to_string(root().join("techniques/shading/chiang/technique.toml"))
        .expect("chiang");
    let bad = chiang.replace("chiang_tilt = { min = -10.0", "chiang_tlt = { min = -10.0");
    assert_ne!(chiang, bad);
    write(
        library.path(),
        "techniques/shading/chiang/technique.toml",
        &bad,
    );
    let o = with_library(
        library.path(),
        &[
            "check",
            &own_pipeline(library.path()),
            "--set",
            "techniques.geometry=wisps",
            "--set",
            "techniques.shading=chiang",
        ],
    );
    assert_refused(
        "engine and range",
        &o,
        &[
            "technique.engine: no engine need `wisp_mesch`; did you mean `wisp_mesh`?",
            "param_ranges.chiang_tlt: the technique has no param `chiang_tlt`; did you mean `chiang_tilt`?",
        ],
    );
}
