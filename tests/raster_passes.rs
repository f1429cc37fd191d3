//! Data-only raster passes (`type = "raster"`): a pass declared entirely in
//! TOML + WGSL draws what the built-in passes draw, with its depth test and
//! blend state from the file, and its storage writes kept to fragments that
//! pass its depth test on both of the engine's paths.

use plait::session::{SceneData, check_pipeline, prepare};
use plait_gpu::Gpu;
use plait_graph::CompileOptions;
use plait_tests::{open_gpu, repo_root};

const SIZE: (u32, u32) = (96, 72);

/// IEEE half to f32 (normal numbers and zero: the counts are small integers).
fn half(bits: u16) -> f32 {
    let exp = ((bits >> 10) & 0x1f) as i32;
    let mantissa = (bits & 0x3ff) as f32;
    match exp {
        0 => mantissa * 2f32.powi(-24),
        _ => (1.0 + mantissa / 1024.0) * 2f32.powi(exp - 15),
    }
}

fn words(bytes: &[u8]) -> Vec<u32> {
    bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// Per-pixel hair fragment counts of `tests/fixtures/raster_counts.toml`:
/// (built-in slab pass, data-only atomics, data-only additive blending).
fn counts(gpu: &Gpu) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let pipeline = repo_root().join("tests/fixtures/raster_counts.toml");
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let prepared = prepare(gpu, &pipeline, &[], &scene, SIZE)
        .unwrap_or_else(|e| panic!("raster_counts.toml: {e}"));
    prepared.render().expect("renders");
    let read = |name: &str| prepared.read_buffer(name).expect(name);
    let blended = prepared
        .read_resource("blended_counts")
        .expect("blended_counts");
    let blended: Vec<u32> = blended
        .bytes
        .chunks_exact(8)
        .map(|px| half(u16::from_le_bytes([px[0], px[1]])) as u32)
        .collect();
    (
        words(&read("slab_counts")),
        words(&read("atomic_counts")),
        blended,
    )
}

fn assert_agree(gpu: &Gpu, path: &str) {
    let (slab, atomic, blended) = counts(gpu);
    let covered = blended.iter().filter(|&&n| n > 0).count();
    let total: u64 = blended.iter().map(|&n| n as u64).sum();
    assert!(
        covered > 100 && total > 1000,
        "{path}: too little hair to compare ({covered} pixels, {total} fragments)"
    );
    assert_eq!(slab.len(), blended.len());
    let differ = |a: &[u32], b: &[u32]| a.iter().zip(b).filter(|(x, y)| x != y).count();
    assert_eq!(
        differ(&atomic, &blended),
        0,
        "{path}: data-only atomics and additive blending count differently"
    );
    assert_eq!(
        differ(&slab, &blended),
        0,
        "{path}: the built-in slab pass and the data-only passes count differently"
    );
}

/// The same counts from the built-in slab pass, a data-only raster pass with
/// atomics and one with additive blending — with the early depth test.
#[test]
fn data_only_raster_passes_count_like_the_builtin_slab_pass() {
    let (_lock, gpu) = open_gpu();
    assert!(gpu.capabilities.early_depth_test);
    assert_agree(&gpu, "early depth test");
}

/// And where the engine tests depth in the shader instead.
#[test]
fn data_only_raster_passes_count_alike_with_the_in_shader_depth_test() {
    let (_lock, _) = open_gpu();
    let gpu = Gpu::new_without_features(&["SHADER_EARLY_DEPTH_TEST"]).expect("GPU");
    assert_agree(&gpu, "in-shader depth test");
}

/// `raster_counts.toml` with one pass's lines replaced, checked without a GPU.
fn check_with(replace: &str, with: &str) -> String {
    let path = repo_root().join("tests/fixtures/raster_counts.toml");
    let text = std::fs::read_to_string(&path).expect("fixture");
    assert!(text.contains(replace), "fixture lacks {replace:?}");
    let text = text.replace(replace, with);
    let pipeline = plait_graph::load_str(&path, &text, &[]).unwrap_or_else(|e| panic!("{e}"));
    match check_pipeline(
        &plait_passes::read_library(&[]),
        &pipeline,
        &CompileOptions::default(),
    ) {
        Ok(_) => String::new(),
        Err(e) => e.to_string(),
    }
}

/// The line (1-based) of `needle` in the fixture after the replacement.
fn line_of(replace: &str, with: &str, needle: &str) -> usize {
    let path = repo_root().join("tests/fixtures/raster_counts.toml");
    let text = std::fs::read_to_string(path)
        .expect("fixture")
        .replace(replace, with);
    text.lines()
        .position(|l| l.contains(needle))
        .expect("needle present")
        + 1
}

#[test]
fn the_fixture_checks() {
    assert_eq!(check_with("", ""), "");
}

#[test]
fn a_blend_its_target_format_cannot_do_is_an_error_at_the_blend() {
    let (from, to) = ("format = \"rgba16float\"", "format = \"r32uint\"");
    // The shader's vec4<f32> output does not fit r32uint either; the blend is
    // what this test is about, so the shader is swapped for a uint one.
    let path = repo_root().join("tests/fixtures/raster_counts.toml");
    let text = std::fs::read_to_string(&path)
        .expect("fixture")
        .replace(from, to);
    let pipeline = plait_graph::load_str(&path, &text, &[]).expect("loads");
    let err = check_pipeline(
        &plait_passes::read_library(&[]),
        &pipeline,
        &CompileOptions::default(),
    )
    .expect_err("r32uint cannot blend")
    .to_string();
    let line = line_of(from, to, "blend = { count");
    assert!(
        err.contains(&format!("raster_counts.toml:{line}:")),
        "not at the blend line {line}: {err}"
    );
    assert!(err.contains("cannot be blended"), "{err}");
}

#[test]
fn a_depth_test_without_a_depth_input_is_an_error() {
    let (from, to) = (
        "reads = { depth = \"depth\" }\nwrites = { count = \"blended_counts\" }",
        "writes = { count = \"blended_counts\" }",
    );
    let err = check_with(from, to);
    let line = line_of(from, to, "[passes.blended_counts]") + 6;
    assert!(
        err.contains(&format!("raster_counts.toml:{line}:")),
        "not at the depth line {line}: {err}"
    );
    assert!(err.contains("a depth test needs a depth input"), "{err}");
}

#[test]
fn a_storage_write_behind_a_written_depth_target_is_an_error() {
    // The atomic pass tests and writes the depth it is given: no adapter
    // without early depth tests could keep its atomics to visible fragments.
    let (from, to) = (
        "reads = { depth = \"depth\" }\nwrites = { counts = \"atomic_counts\" }\ndepth = { compare = \"less\", write = false }",
        "writes = { counts = \"atomic_counts\", depth = \"own_depth\" }\ndepth = { compare = \"less\", write = true }\n\n[resources.own_depth]\nkind = \"texture\"\nformat = \"depth32float\"\nsize = \"screen\"",
    );
    let err = check_with(from, to);
    let line = line_of(from, to, "depth = { compare = \"less\", write = true }");
    assert!(
        err.contains(&format!("raster_counts.toml:{line}:")),
        "not at the depth line {line}: {err}"
    );
    assert!(
        err.contains("writes its depth target") && err.contains("SHADER_EARLY_DEPTH_TEST"),
        "{err}"
    );
}

#[test]
fn a_storage_write_behind_a_multisampled_depth_target_is_an_error() {
    let (from, to) = (
        "[resources.depth]\nkind = \"texture\"\nformat = \"depth32float\"\nsize = \"screen\"",
        "[resources.depth]\nkind = \"texture\"\nformat = \"depth32float\"\nsize = \"screen\"\nsamples = 4",
    );
    let err = check_with(from, to);
    assert!(
        err.contains("`depth` is multisampled") && err.contains("pass `atomic_counts`"),
        "{err}"
    );
}

/// A depth texture a data-only raster pass does not bind is its depth
/// test's target; a second such slot would be dropped without a word, so it
/// is refused at its slot (found when a pass kept a shadow map its shader no
/// longer used).
#[test]
fn a_second_unbound_depth_texture_is_an_error_at_its_slot() {
    let (from, to) = (
        "reads = { depth = \"depth\" }\nwrites = { counts = \"atomic_counts\" }",
        "reads = { depth = \"depth\", unused = \"scratch\" }\nwrites = { counts = \"atomic_counts\" }",
    );
    let err = check_with(from, to);
    assert!(
        err.contains("slot `unused` is a depth texture the shader does not bind")
            && err.contains("(`depth` is the first)"),
        "{err}"
    );
}

#[test]
fn state_keys_on_a_type_that_sets_its_state_in_rust_are_an_error() {
    let err = check_with(
        "type = \"depth_range\"",
        "type = \"depth_range\"\ncull = \"back\"",
    );
    assert!(
        err.contains("type `depth_range` sets its raster state in Rust")
            && err.contains("`cull` does not apply"),
        "{err}"
    );
}

#[test]
fn a_blend_for_a_slot_that_is_no_colour_target_suggests_one() {
    let err = check_with(
        "blend = { count = \"additive\" }",
        "blend = { cont = \"additive\" }",
    );
    assert!(
        err.contains("`cont` is not a colour target") && err.contains("did you mean `count`"),
        "{err}"
    );
}

/// A culled data-only pass is still checked against its shader, but outputs
/// the schedule dropped with it are not held against its state.
#[test]
fn a_culled_raster_pass_with_state_checks() {
    let path = repo_root().join("tests/fixtures/raster_counts.toml");
    let pipeline =
        plait_graph::load(&path, &["pipeline.outputs=[\"slab_counts\"]".into()]).expect("loads");
    let schedule = check_pipeline(
        &plait_passes::read_library(&[]),
        &pipeline,
        &CompileOptions::default(),
    )
    .unwrap_or_else(|e| panic!("culled passes with state must check: {e}"));
    let culled: Vec<&str> = schedule
        .culled
        .iter()
        .map(|c| c.pass.name.as_str())
        .collect();
    assert!(
        culled.contains(&"blended_counts") && culled.contains(&"atomic_counts"),
        "{culled:?}"
    );
}
