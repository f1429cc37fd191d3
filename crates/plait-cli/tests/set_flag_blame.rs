//! A `--set` value that makes a size check fail is named first, even when
//! the technique uses it inside a longer expression
//! (`"${light_size} * ${light_size} * ${slices} / 8"`) or a list
//! (`size = ["${light_size}", "${light_size}"]`), not the technique line.

mod common;
use common::{plait, text};

#[test]
fn a_zero_size_from_a_flag_names_the_flag() {
    for (flag, resource) in [
        (
            "params.slices=0",
            "resource `light_bits`: buffer size is 0 bytes",
        ),
        ("params.light_size=0", "texture `opaque_shadow` is 0x0"),
    ] {
        let o = plait(&["check", "pipelines/occupancy.toml", "--set", flag]);
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{flag}: {err}");
        assert!(
            err.contains(&format!("error: --set {flag}: {resource}")),
            "{flag}: the error does not start with the flag:\n{err}"
        );
        assert!(
            err.lines()
                .all(|l| l.starts_with(&format!("error: --set {flag}: "))),
            "{flag}: an error blames a file line instead of the flag:\n{err}"
        );
    }
}
