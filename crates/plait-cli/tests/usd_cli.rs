//! `plait hair info` / `plait hair convert` and scenes on USD grooms
//! (issue 24): BasisCurves written here as `.usda` text, and `.usdc` /
//! `.usdz` written by `plait hair convert` itself.

use std::path::{Path, PathBuf};

mod common;
use common::{plait, text};
use plait_hair::{Asset, Strands};

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write");
    path
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// A Z-up centimetre stage: `curves` B-spline curves of 6 vertices, 20 cm
/// tall along +Z, with constant widths and per-curve colours.
fn groom_usda(curves: usize) -> String {
    let mut points = Vec::new();
    let mut colors = Vec::new();
    for c in 0..curves {
        let (x, y) = ((c % 5) as f32 * 2.0, (c / 5) as f32 * 2.0);
        for k in 0..6 {
            points.push(format!(
                "({}, {y}, {})",
                x + k as f32 * 0.5,
                20.0 - 4.0 * k as f32
            ));
        }
        colors.push(format!("({}, 0.3, 0.2)", c as f32 / curves as f32));
    }
    format!(
        "#usda 1.0\n(\n    metersPerUnit = 0.01\n    upAxis = \"Z\"\n)\ndef Xform \"Groom\"\n{{\n    def BasisCurves \"Hair\"\n    {{\n        uniform token type = \"cubic\"\n        uniform token basis = \"bspline\"\n        uniform token wrap = \"pinned\"\n        int[] curveVertexCounts = [{}]\n        point3f[] points = [{}]\n        float[] widths = [0.1] (interpolation = \"constant\")\n        color3f[] primvars:displayColor = [{}] (interpolation = \"uniform\")\n    }}\n}}\n",
        vec!["6"; curves].join(", "),
        points.join(", "),
        colors.join(", ")
    )
}

#[test]
fn info_reads_a_usd_groom() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = write(dir.path(), "g.usda", groom_usda(3).as_bytes());
    let o = plait(&[
        "hair",
        "info",
        "--json",
        "--segments-per-span",
        "4",
        s(&file),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(v["format"], "usd");
    assert_eq!(v["container"], "usda");
    assert_eq!(v["up_axis"], "Z");
    assert_eq!(v["meters_per_unit"], 0.01);
    assert_eq!(v["strands"], 3);
    // Pinned B-spline, 6 vertices: 5 spans of 4 segments, 21 points a curve.
    assert_eq!(v["points"], 63);
    assert_eq!(v["prims"][0]["path"], "/Groom/Hair");
    assert_eq!(v["prims"][0]["curves"], "cubic bspline, pinned");
    assert_eq!(v["prims"][0]["display_color"], "uniform");
    // 20 cm along +Z is 0.2 m along +Y; pinned curves reach their roots.
    let top = v["bounds"]["max"][1].as_f64().expect("number");
    assert!((top - 0.2).abs() < 1e-6, "{top}");
    let o = plait(&["hair", "info", s(&file)]);
    assert!(
        text(&o.stdout).contains("USD (usda), BasisCurves"),
        "{}",
        text(&o.stdout)
    );
}

/// `.hair` → USD → `.hair` in every container keeps the strands exactly.
#[test]
fn convert_round_trips_hair_through_usd() {
    let dir = tempfile::tempdir().expect("tempdir");
    let hair = dir.path().join("g.hair");
    let o = plait(&[
        "hair",
        "generate",
        "--strands",
        "20",
        "--segments",
        "6",
        "--out",
        s(&hair),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let (original, _) = Asset::read(&hair).expect("hair");
    let original: Strands = original.strands();
    for name in ["out.usda", "out.usdc", "out.usdz"] {
        let usd = dir.path().join(name);
        let o = plait(&["hair", "convert", s(&hair), s(&usd)]);
        assert!(o.status.success(), "{name}: {}", text(&o.stderr));
        let (read, _) = Asset::read(&usd).expect("usd");
        assert_eq!(read.strands(), original, "{name}");
        let back = dir.path().join(format!("{name}.hair"));
        let o = plait(&["hair", "convert", s(&usd), s(&back)]);
        assert!(o.status.success(), "{name}: {}", text(&o.stderr));
        let (again, _) = Asset::read(&back).expect("hair");
        assert_eq!(again.strands(), original, "{name} → .hair");
    }
    let text_out = std::fs::read_to_string(dir.path().join("out.usda")).expect("usda");
    assert!(text_out.starts_with("#usda 1.0"));
    assert!(text_out.contains("def BasisCurves \"Strands\""));
}

#[test]
fn bad_usd_input_exits_2_naming_the_file_and_prim_and_writes_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let curves = |attrs: &str| {
        format!(
            "#usda 1.0\ndef Xform \"G\"\n{{\n    def BasisCurves \"H\"\n    {{\n{attrs}\n    }}\n}}\n"
        )
    };
    let lin = "uniform token type = \"linear\"";
    let two = "point3f[] points = [(0,0,0), (0,1,0)]";
    let four = "point3f[] points = [(0,0,0), (0,1,0), (0,2,0), (0,3,0)]";
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "garbage.usda",
            "not USD at all {{{".into(),
            "not a readable USD file",
        ),
        (
            "zip.usdz",
            "PK\u{3}\u{4} truncated".into(),
            "not a readable USD file",
        ),
        (
            "crate.usdc",
            "PXR-USDC\0\0\0\0 truncated".into(),
            "not a readable USD file",
        ),
        (
            "empty.usda",
            "#usda 1.0\ndef Xform \"G\"\n{\n}\n".into(),
            "no BasisCurves prim under `/`",
        ),
        (
            "counts.usda",
            curves(&format!("{lin}\nint[] curveVertexCounts = [3]\n{two}")),
            "prim `/G/H`, field `curveVertexCounts`: sums to 3 vertices but `points` has 2",
        ),
        (
            "widths.usda",
            curves(&format!(
                "{lin}\nint[] curveVertexCounts = [2]\n{two}\nfloat[] widths = [1, 2, 3]"
            )),
            "prim `/G/H`, field `widths`: has 3 values",
        ),
        (
            "nan.usda",
            curves(&format!(
                "{lin}\nint[] curveVertexCounts = [2]\npoint3f[] points = [(0,0,0), (nan,1,0)]"
            )),
            "prim `/G/H`, field `points`: point 1 is not finite",
        ),
        (
            "hermite.usda",
            curves(&format!(
                "uniform token type = \"cubic\"\nuniform token basis = \"hermite\"\nint[] curveVertexCounts = [4]\n{four}"
            )),
            "prim `/G/H`, field `basis`: `hermite` is not supported",
        ),
        (
            "periodic.usda",
            curves(&format!(
                "{lin}\nuniform token wrap = \"periodic\"\nint[] curveVertexCounts = [4]\n{four}"
            )),
            "prim `/G/H`, field `wrap`: `periodic` is not supported",
        ),
    ];
    for (name, body, want) in &cases {
        let input = write(dir.path(), name, body.as_bytes());
        let out = dir.path().join(format!("{name}.hair"));
        for args in [
            vec!["hair", "info", s(&input)],
            vec!["hair", "convert", s(&input), s(&out)],
        ] {
            let o = plait(&args);
            let err = text(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
            assert!(err.contains(name) && err.contains(want), "{name}: {err}");
            assert!(!err.contains("panicked"), "{err}");
        }
        assert!(!out.exists(), "no output for a bad input");
    }
    // A prim that is not there, with the nearest suggested.
    let ok = write(dir.path(), "ok.usda", groom_usda(2).as_bytes());
    let o = plait(&["hair", "info", "--prim", "/Grom", s(&ok)]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("ok.usda: prim `/Grom` is not on the stage (did you mean `/Groom`?)"),
        "{err}"
    );
    let o = plait(&["hair", "info", "--segments-per-span", "0", s(&ok)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o.stderr).contains("--segments-per-span must be in 1..=256"));
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .expect("list")
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with(".plait-"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
}

/// A scene naming a Z-up centimetre USD groom renders it framed, upright.
#[test]
fn a_usd_scene_renders_framed() {
    let dir = tempfile::tempdir().expect("tempdir");
    write(dir.path(), "g.usda", groom_usda(20).as_bytes());
    let scene = write(
        dir.path(),
        "s.toml",
        b"camera = \"fit\"\nlight = \"fit\"\n[hair]\nfile = \"g.usda\"\nprim = \"/Groom\"\nsegments_per_span = 4\n",
    );
    let out = dir.path().join("g.png");
    let o = plait(&[
        "render",
        "--scene",
        s(&scene),
        "--size",
        "64x48",
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", text(&o.stderr));
    let img = image::open(&out).expect("png").to_rgba8();
    let background = *img.get_pixel(0, 0);
    let (mut lo, mut hi) = ((u32::MAX, u32::MAX), (0, 0));
    for (x, y, p) in img.enumerate_pixels() {
        if *p != background {
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
        }
    }
    // Upright (Z up became Y up): taller than wide in the frame.
    assert!(
        hi.1 > lo.1 && hi.1 - lo.1 >= 30,
        "hair spans rows {lo:?}..{hi:?}"
    );
    assert!(
        hi.0 - lo.0 < hi.1 - lo.1,
        "hair spans {lo:?}..{hi:?}: lying down"
    );
}

/// A binary `.usdc` whose points array claims 2^40 points (12 TiB) is an
/// error naming the file, the attribute and the field, exit 2, read as a
/// groom and as a scene's mesh — never an abort on the allocation.
#[test]
fn a_usdc_claiming_a_huge_array_is_an_error() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut strands = Strands::new();
    let points = [glam::Vec3::ZERO, glam::Vec3::new(0.0, -0.1, 0.01)];
    strands.push_strand(&points, |_| 0.002, |_| 1.0, glam::Vec3::ONE);
    let mut bytes =
        plait_hair::usd::write(&strands, plait_hair::usd::WriteFormat::Usdc).expect("writes");
    let first: Vec<u8> = [0.0f32, 0.0, 0.0, 0.0, -0.1, 0.01]
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let at = bytes
        .windows(24)
        .position(|w| w == first)
        .expect("the points")
        - 8;
    bytes[at..at + 8].copy_from_slice(&(1u64 << 40).to_le_bytes());
    let file = write(dir.path(), "huge.usdc", &bytes);
    let o = plait(&["hair", "info", s(&file)]);
    let err = text(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("huge.usdc")
            && err.contains("attribute `/Groom/Strands.points`, field `default`")
            && err.contains("1099511627776 elements of 12 bytes"),
        "{err}"
    );
}
