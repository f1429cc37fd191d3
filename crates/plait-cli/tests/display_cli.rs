//! The display transform's bad input (issue 47): a non-finite exposure, a
//! tone mapper that does not exist, and `--out x.exr` on a pipeline with no
//! floating-point radiance are refused with the flag, exit 2, no output file
//! and no GPU work (each check runs before the device opens: `render_cmd::render`);
//! a good `--out x.exr` holds 32-bit float linear radiance.

mod common;
use common::{plait, text};

/// A path in a fresh temporary folder (kept alive by the returned guard).
fn out_path(name: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join(name).display().to_string();
    (dir, path)
}

#[test]
fn a_non_finite_exposure_is_refused_at_the_flag() {
    for value in ["nan", "inf", "-inf", "100"] {
        let (_dir, out) = out_path("x.png");
        let flag = format!("params.exposure={value}");
        let o = plait(&["render", "--size", "32x24", "--out", &out, "--set", &flag]);
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{flag}: {err}");
        assert!(
            err.starts_with(&format!("error: --set {flag}: param `exposure`")),
            "{flag}: the error does not name the flag and the param:\n{err}"
        );
        assert!(!std::path::Path::new(&out).exists(), "{flag}: wrote {out}");
    }
}

#[test]
fn an_unknown_tone_mapper_is_refused_with_the_nearest_name() {
    let o = plait(&[
        "check",
        "pipelines/occupancy.toml",
        "--set",
        "techniques.tone_mapping=agxx",
    ]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains(
            "error: --set techniques.tone_mapping=agxx: no tone_mapping technique `agxx`; \
             did you mean `agx`?"
        ),
        "{err}"
    );
    for name in ["clip", "reinhard", "aces_fitted", "agx", "pbr_neutral"] {
        assert!(err.contains(name), "choice {name} not listed:\n{err}");
    }
}

#[test]
fn exr_out_of_a_pipeline_without_float_radiance_is_refused_at_the_flag() {
    // kk.toml writes an rgba8unorm `final` and has no `radiance`; occupancy
    // with its radiance made 8-bit has one, but not floating point.
    let cases: [(&str, &[&str], &str); 2] = [
        (
            "tests/fixtures/kk.toml",
            &[],
            "has no floating-point `radiance` texture",
        ),
        (
            "pipelines/occupancy.toml",
            &["--set", "resources.radiance.format=\"rgba8unorm\""],
            "(it is rgba8unorm)",
        ),
    ];
    for (pipeline, sets, says) in cases {
        let (_dir, out) = out_path("x.exr");
        let mut args = vec!["render", pipeline, "--size", "32x24", "--out", &out];
        args.extend_from_slice(sets);
        let o = plait(&args);
        let err = text(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{pipeline}: {err}");
        assert!(
            err.starts_with(&format!("error: --out {out}: {pipeline}")) && err.contains(says),
            "{pipeline}: {err}"
        );
        assert!(!std::path::Path::new(&out).exists(), "wrote {out}");
    }
}

#[test]
fn exr_out_holds_float_linear_radiance() {
    let (_dir, out) = out_path("x.exr");
    let o = plait(&["render", "--size", "40x30", "--out", &out]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o.stderr));
    let img = image::open(&out).expect("an OpenEXR file");
    let image::DynamicImage::ImageRgba32F(img) = img else {
        panic!("not 32-bit float RGBA: {:?}", img.color());
    };
    assert_eq!(img.dimensions(), (40, 30));
    assert!(img.pixels().all(|p| p.0.iter().all(|v| v.is_finite())));
    assert!(img.pixels().any(|p| p.0[0] > 0.0), "all black");
    // Alpha is the part of the pixel anything covers (docs/formats.md): 0
    // where only the background shows, strictly between at the hair's thin
    // strands (tests/exr_alpha.rs checks the values against coverage).
    assert!(img.pixels().all(|p| (0.0..=1.0).contains(&p.0[3])));
    assert!(img.pixels().any(|p| p.0[3] == 0.0), "no background alpha 0");
    assert!(
        img.pixels().any(|p| p.0[3] > 0.0 && p.0[3] < 1.0),
        "no partly covered pixel"
    );
    // The file itself stores 32-bit floats (pixel type 2 of OpenEXR's
    // chlist), not halves widened by the decoder.
    let bytes = std::fs::read(&out).expect("reads");
    let key = b"channels\0chlist\0";
    let at = bytes
        .windows(key.len())
        .position(|w| w == key)
        .expect("a chlist")
        + key.len()
        + 4;
    let mut i = at;
    let mut channels = Vec::new();
    while bytes[i] != 0 {
        let end = i + bytes[i..].iter().position(|&b| b == 0).expect("a name");
        let kind = u32::from_le_bytes(bytes[end + 1..end + 5].try_into().unwrap());
        channels.push((String::from_utf8_lossy(&bytes[i..end]).into_owned(), kind));
        i = end + 1 + 16;
    }
    assert_eq!(channels.len(), 4, "{channels:?}");
    assert!(channels.iter().all(|(_, kind)| *kind == 2), "{channels:?}");
}
