//! `plait check` and `plait render` on a bad data-only raster pass
//! (`type = "raster"`): exit code 2, the error at the marked line of the
//! pipeline file (file:line:column), no panic, no output file.
//! Fixtures: `tests/fixtures/bad/raster_*.toml`, `loads_unwritten*.toml`,
//! `clear_channels.toml`, `fragment_*_output.{toml,wgsl}`,
//! `storage_format.{toml,wgsl}`.

mod common;
use common::{plait, root, text};

fn bad_raster_pass(name: &str, message: &str) {
    bad_pass_marked_in(name, name, message);
}

/// `bad_raster_pass` with the `<- error` marker in fixture `marked` (the
/// pipeline file or its WGSL).
fn bad_pass_marked_in(name: &str, marked: &str, message: &str) {
    let path = root().join("tests/fixtures/bad").join(name);
    let source = std::fs::read_to_string(path.with_file_name(marked)).expect("fixture");
    let line = source
        .lines()
        .position(|l| l.contains("<- error"))
        .expect("an `<- error` marker")
        + 1;
    let at = format!("{marked}:{line}:");
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("out.png");
    let scene = root().join("examples/scenes/small.toml");
    let p = path.to_str().expect("utf-8");
    let render = [
        "render",
        p,
        "--scene",
        scene.to_str().expect("utf-8"),
        "--size",
        "64x48",
        "--out",
        png.to_str().expect("utf-8"),
    ];
    for args in [&["check", p][..], &render[..]] {
        let o = plait(args);
        let stderr = text(&o.stderr);
        let context = format!(
            "plait {} {name}: exit {:?}\n{stderr}",
            args[0],
            o.status.code()
        );
        assert_eq!(o.status.code(), Some(2), "{context}");
        assert!(!stderr.contains("panicked"), "{context}");
        assert!(stderr.contains(message), "lacks `{message}`: {context}");
        let column = stderr
            .find(&at)
            .map(|i| &stderr[i + at.len()..])
            .unwrap_or_else(|| panic!("not at `{at}`: {context}"));
        assert!(
            column.starts_with(|c: char| c.is_ascii_digit()),
            "{context}"
        );
        assert!(!png.exists(), "an image was written: {context}");
    }
}

#[test]
fn a_blend_the_target_format_cannot_do() {
    bad_raster_pass("raster_blend_uint.toml", "cannot be blended");
}

#[test]
fn a_depth_test_without_a_depth_input() {
    bad_raster_pass("raster_depth_without_input.toml", "needs a depth input");
}

#[test]
fn a_storage_output_the_depth_guarantee_cannot_honour() {
    bad_raster_pass(
        "raster_storage_written_depth.toml",
        "writes its depth target",
    );
}

#[test]
fn a_load_of_a_target_nothing_wrote_without_a_clear_value() {
    bad_raster_pass(
        "loads_unwritten.toml",
        "no earlier pass in the frame writes `revealage`",
    );
}

/// The error points at the `loads` entry at fault (its own line in a list
/// written over several lines), not at the start of the list.
#[test]
fn a_load_error_points_at_the_entry() {
    bad_raster_pass(
        "loads_unwritten_entry.toml",
        "no earlier pass in the frame writes `revealage`",
    );
}

#[test]
fn a_clear_value_with_the_wrong_number_of_channels() {
    bad_raster_pass("clear_channels.toml", "a list of 4 numbers");
}

#[test]
fn a_fragment_output_past_the_colour_targets() {
    bad_pass_marked_in(
        "fragment_extra_output.toml",
        "fragment_extra_output.wgsl",
        "@location(1) has no colour target",
    );
}

#[test]
fn a_uint_fragment_output_into_a_float_target() {
    bad_pass_marked_in(
        "fragment_uint_output.toml",
        "fragment_uint_output.wgsl",
        "is u32, but its target `out` is rgba16float",
    );
}

#[test]
fn a_colour_target_the_fragment_shader_does_not_write() {
    bad_raster_pass(
        "fragment_missing_output.toml",
        "colour target `more` (rgba16float) is at @location(1)",
    );
}

/// A storage texture whose WGSL format differs from its resource's: the
/// error is at the WGSL declaration, and names the pipeline's slot with its
/// own file:line:column.
#[test]
fn a_storage_format_the_resource_does_not_have() {
    bad_pass_marked_in(
        "storage_format.toml",
        "storage_format.wgsl",
        "storage texture `counts` is declared r32float here, but slot `counts` binds resource `counts`, which is r32uint (",
    );
}
