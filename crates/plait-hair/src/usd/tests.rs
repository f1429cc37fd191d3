//! USD reading and writing, on stages written here as text (and as crate and
//! package files through `openusd`'s writers).

use std::path::Path;

use glam::Vec3;

use super::*;
use crate::strands::Strands;

/// A stage in metres, Y up, holding `body` at the root.
fn stage(body: &str) -> String {
    format!("#usda 1.0\n(\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n\n{body}\n")
}

fn curves(attrs: &str) -> String {
    stage(&format!("def BasisCurves \"C\"\n{{\n{attrs}\n}}"))
}

fn read_text(text: &str, options: &UsdOptions) -> Result<(UsdGroom, Vec<String>), UsdError> {
    UsdGroom::from_bytes(
        Path::new("t.usda"),
        text.as_bytes().to_vec(),
        options,
        false,
    )
}

fn read_ok(text: &str, segments: u32) -> Strands {
    let options = UsdOptions {
        segments_per_span: segments,
        ..UsdOptions::default()
    };
    match read_text(text, &options) {
        Ok((g, _)) => g.strands,
        Err(e) => panic!("{e}\n{text}"),
    }
}

fn read_err(text: &str) -> String {
    match read_text(text, &UsdOptions::default()) {
        Ok(_) => panic!("read, but should not have:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn close(a: Vec3, b: Vec3) {
    assert!((a - b).length() < 1e-5, "{a} != {b}");
}

const P: [Vec3; 4] = [
    Vec3::new(0.0, 0.0, 0.0),
    Vec3::new(1.0, 2.0, 0.0),
    Vec3::new(3.0, 2.0, 1.0),
    Vec3::new(4.0, 0.0, -1.0),
];
const FOUR: &str = "point3f[] points = [(0, 0, 0), (1, 2, 0), (3, 2, 1), (4, 0, -1)]";

fn cubic(basis: &str, wrap: &str) -> String {
    curves(&format!(
        "uniform token type = \"cubic\"\nuniform token basis = \"{basis}\"\nuniform token wrap = \"{wrap}\"\nint[] curveVertexCounts = [4]\n{FOUR}"
    ))
}

#[test]
fn linear_curves_are_read_as_they_are() {
    let s = read_ok(
        &curves(
            "uniform token type = \"linear\"\nint[] curveVertexCounts = [3, 2]\npoint3f[] points = [(0, 0, 0), (0, 1, 0), (0, 2, 0), (5, 0, 0), (5, 1, 0)]",
        ),
        8,
    );
    assert_eq!(s.offsets, vec![0, 3, 5]);
    assert_eq!(s.points[2], Vec3::new(0.0, 2.0, 0.0));
    assert_eq!(s.points[4], Vec3::new(5.0, 1.0, 0.0));
    // No widths or colours: width 1, white, opaque.
    assert!(s.thickness.iter().all(|&t| t == 1.0));
    assert!(s.color.iter().all(|&c| c == Vec3::ONE));
}

#[test]
fn bspline_is_evaluated_at_the_basis() {
    let s = read_ok(&cubic("bspline", "nonperiodic"), 2);
    // One span, 2 segments: t = 0, 0.5, 1.
    assert_eq!(s.offsets, vec![0, 3]);
    close(s.points[0], (P[0] + 4.0 * P[1] + P[2]) / 6.0);
    close(
        s.points[1],
        (P[0] + 23.0 * P[1] + 23.0 * P[2] + P[3]) / 48.0,
    );
    close(s.points[2], (P[1] + 4.0 * P[2] + P[3]) / 6.0);
}

#[test]
fn bezier_is_evaluated_at_the_basis() {
    let s = read_ok(&cubic("bezier", "nonperiodic"), 2);
    close(s.points[0], P[0]);
    close(s.points[1], (P[0] + 3.0 * P[1] + 3.0 * P[2] + P[3]) / 8.0);
    close(s.points[2], P[3]);
    // The default basis is Bézier.
    let s = read_ok(
        &curves(&format!(
            "uniform token type = \"cubic\"\nint[] curveVertexCounts = [4]\n{FOUR}"
        )),
        2,
    );
    close(s.points[1], (P[0] + 3.0 * P[1] + 3.0 * P[2] + P[3]) / 8.0);
}

#[test]
fn catmull_rom_passes_through_its_inner_vertices() {
    let s = read_ok(&cubic("catmullRom", "nonperiodic"), 2);
    close(s.points[0], P[1]);
    close(s.points[1], (-P[0] + 9.0 * P[1] + 9.0 * P[2] - P[3]) / 16.0);
    close(s.points[2], P[2]);
}

#[test]
fn pinned_curves_reach_their_end_vertices() {
    for basis in ["bspline", "catmullRom"] {
        let s = read_ok(&cubic(basis, "pinned"), 4);
        // Pinned: 3 spans of 4 segments.
        assert_eq!(s.offsets, vec![0, 13], "{basis}");
        close(s.points[0], P[0]);
        close(s.points[12], P[3]);
    }
    // Catmull-Rom also passes through the inner vertices.
    let s = read_ok(&cubic("catmullRom", "pinned"), 4);
    close(s.points[4], P[1]);
    close(s.points[8], P[2]);
}

#[test]
fn segments_per_span_sets_the_point_count() {
    // Bézier, 7 vertices = 2 spans.
    let text = curves(
        "uniform token type = \"cubic\"\nint[] curveVertexCounts = [7]\npoint3f[] points = [(0,0,0),(1,0,0),(2,0,0),(3,0,0),(4,0,0),(5,0,0),(6,0,0)]",
    );
    assert_eq!(read_ok(&text, 1).point_count(), 3);
    assert_eq!(read_ok(&text, 5).point_count(), 11);
    let s = read_ok(&text, 5);
    close(s.points[5], Vec3::new(3.0, 0.0, 0.0));
}

#[test]
fn widths_in_every_interpolation() {
    let base = "uniform token type = \"linear\"\nint[] curveVertexCounts = [2, 2]\npoint3f[] points = [(0,0,0),(0,1,0),(1,0,0),(1,1,0)]";
    let with = |w: &str| read_ok(&curves(&format!("{base}\n{w}")), 8).thickness;
    assert_eq!(
        with("float[] widths = [1, 2, 3, 4] (interpolation = \"vertex\")"),
        vec![1.0, 2.0, 3.0, 4.0]
    );
    // vertex is the default
    assert_eq!(
        with("float[] widths = [1, 2, 3, 4]"),
        vec![1.0, 2.0, 3.0, 4.0]
    );
    assert_eq!(
        with("float[] widths = [0.5, 0.25] (interpolation = \"uniform\")"),
        vec![0.5, 0.5, 0.25, 0.25]
    );
    assert_eq!(
        with("float[] widths = [0.1] (interpolation = \"constant\")"),
        vec![0.1; 4]
    );
    // One value and no interpolation: constant.
    assert_eq!(with("float[] widths = [0.2]"), vec![0.2; 4]);
}

#[test]
fn varying_widths_on_a_cubic_curve_are_linear_per_span() {
    // B-spline, 5 vertices: 2 spans, 3 span ends.
    let s = read_ok(
        &curves(
            "uniform token type = \"cubic\"\nuniform token basis = \"bspline\"\nint[] curveVertexCounts = [5]\npoint3f[] points = [(0,0,0),(1,0,0),(2,0,0),(3,0,0),(4,0,0)]\nfloat[] widths = [1, 3, 7] (interpolation = \"varying\")",
        ),
        2,
    );
    assert_eq!(s.thickness, vec![1.0, 2.0, 3.0, 5.0, 7.0]);
}

#[test]
fn vertex_widths_on_a_cubic_curve_follow_the_basis() {
    let s = read_ok(
        &curves(&format!(
            "uniform token type = \"cubic\"\nuniform token basis = \"bspline\"\nint[] curveVertexCounts = [4]\n{FOUR}\nfloat[] widths = [6, 12, 0, 6]"
        )),
        2,
    );
    // (6 + 4·12 + 0) / 6 = 9 at the start, (12 + 0 + 6) / 6 = 3 at the end.
    assert!((s.thickness[0] - 9.0).abs() < 1e-5);
    assert!((s.thickness[2] - 3.0).abs() < 1e-5);
}

#[test]
fn display_color_per_vertex_and_per_curve() {
    let base = "uniform token type = \"linear\"\nint[] curveVertexCounts = [2, 2]\npoint3f[] points = [(0,0,0),(0,1,0),(1,0,0),(1,1,0)]";
    let s = read_ok(
        &curves(&format!(
            "{base}\ncolor3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (interpolation = \"uniform\")"
        )),
        8,
    );
    assert_eq!(s.color, vec![Vec3::X, Vec3::X, Vec3::Y, Vec3::Y]);
    let s = read_ok(
        &curves(&format!(
            "{base}\ncolor3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0)] (interpolation = \"vertex\")\nfloat[] primvars:displayOpacity = [0.5] (interpolation = \"constant\")"
        )),
        8,
    );
    assert_eq!(
        s.color,
        vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(1.0, 1.0, 0.0)]
    );
    assert_eq!(s.alpha, vec![0.5; 4]);
}

#[test]
fn units_and_z_up_become_metres_and_y_up() {
    let text = "#usda 1.0\n(\n    metersPerUnit = 0.01\n    upAxis = \"Z\"\n)\ndef BasisCurves \"C\"\n{\nuniform token type = \"linear\"\nint[] curveVertexCounts = [2]\npoint3f[] points = [(0, 0, 0), (1, 2, 3)]\nfloat[] widths = [2] (interpolation = \"constant\")\n}\n";
    let (g, _) = read_text(text, &UsdOptions::default()).unwrap();
    // Z up → Y up: (x, y, z) → (x, z, −y), in metres.
    close(g.strands.points[1], Vec3::new(0.01, 0.03, -0.02));
    assert!((g.strands.thickness[0] - 0.02).abs() < 1e-7);
    assert!(g.units.z_up && g.units.meters_authored);
    // Not authored: USD's fallback, centimetres.
    let text = "#usda 1.0\ndef BasisCurves \"C\"\n{\nuniform token type = \"linear\"\nint[] curveVertexCounts = [2]\npoint3f[] points = [(0, 0, 0), (100, 0, 0)]\n}\n";
    let (g, _) = read_text(text, &UsdOptions::default()).unwrap();
    close(g.strands.points[1], Vec3::new(1.0, 0.0, 0.0));
    assert!(!g.units.meters_authored);
}

#[test]
fn nested_transforms_apply_innermost_first() {
    let text = stage(
        "def Xform \"Head\"\n{\n    double3 xformOp:translate = (10, 0, 0)\n    float3 xformOp:scale = (2, 2, 2)\n    uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:scale\"]\n    def BasisCurves \"C\"\n    {\n        float xformOp:rotateZ = 90\n        uniform token[] xformOpOrder = [\"xformOp:rotateZ\"]\n        uniform token type = \"linear\"\n        int[] curveVertexCounts = [2]\n        point3f[] points = [(0, 0, 0), (1, 0, 0)]\n        float[] widths = [0.5] (interpolation = \"constant\")\n    }\n}",
    );
    let s = read_ok(&text, 8);
    // (1,0,0) rotated 90° about Z is (0,1,0); scaled by 2, (0,2,0); then +10 in x.
    close(s.points[0], Vec3::new(10.0, 0.0, 0.0));
    close(s.points[1], Vec3::new(10.0, 2.0, 0.0));
    // Widths scale with the transform.
    assert!((s.thickness[0] - 1.0).abs() < 1e-6);
}

fn two_grooms() -> String {
    let c = |x: i32| {
        format!(
            "    def BasisCurves \"C\"\n    {{\n        uniform token type = \"linear\"\n        int[] curveVertexCounts = [2]\n        point3f[] points = [({x}, 0, 0), ({x}, 1, 0)]\n    }}"
        )
    };
    stage(&format!(
        "def Xform \"Left\"\n{{\n{}\n}}\ndef Xform \"Right\"\n{{\n{}\n}}\ndef Xform \"Empty\"\n{{\n}}",
        c(-1),
        c(1)
    ))
}

#[test]
fn a_prim_path_selects_a_subtree() {
    let text = two_grooms();
    assert_eq!(read_ok(&text, 8).strand_count(), 2);
    let only = |prim: &str| {
        let options = UsdOptions {
            prim: Some(prim.into()),
            ..UsdOptions::default()
        };
        read_text(&text, &options)
    };
    let (g, _) = only("/Right").unwrap();
    assert_eq!(g.strands.strand_count(), 1);
    assert_eq!(g.strands.points[0].x, 1.0);
    assert_eq!(g.prims[0].path, "/Right/C");
    // The curves prim itself.
    assert_eq!(only("/Left/C").unwrap().0.strands.points[0].x, -1.0);
    let e = only("/Rigth").unwrap_err().to_string();
    assert!(
        e.contains("t.usda") && e.contains("`/Rigth`") && e.contains("`/Right`"),
        "{e}"
    );
    let e = only("/Empty").unwrap_err().to_string();
    assert!(
        e.contains("t.usda: no BasisCurves prim under `/Empty`"),
        "{e}"
    );
}

#[test]
fn bad_input_names_the_file_and_the_prim_or_field() {
    let not_usd = read_err("this is not USD at all");
    assert!(
        not_usd.starts_with("t.usda: not a readable USD file"),
        "{not_usd}"
    );
    let e = read_err(&stage("def Xform \"Nothing\"\n{\n}"));
    assert!(e.contains("t.usda: no BasisCurves prim under `/`"), "{e}");
    let bad = |attrs: &str, field: &str, says: &str| {
        let e = read_err(&curves(attrs));
        assert!(
            e.starts_with("t.usda: prim `/C`, field `")
                && e.contains(&format!("field `{field}`"))
                && e.contains(says),
            "{e}"
        );
    };
    let lin = "uniform token type = \"linear\"";
    bad(
        &format!("{lin}\nint[] curveVertexCounts = [3]\npoint3f[] points = [(0,0,0),(0,1,0)]"),
        "curveVertexCounts",
        "sums to 3 vertices but `points` has 2",
    );
    bad(
        &format!("{lin}\nint[] curveVertexCounts = [-1, 3]\npoint3f[] points = [(0,0,0),(0,1,0)]"),
        "curveVertexCounts",
        "curve 0 has -1 vertices",
    );
    bad(
        &format!(
            "{lin}\nint[] curveVertexCounts = [2]\npoint3f[] points = [(0,0,0),(0,1,0)]\nfloat[] widths = [1, 2, 3]"
        ),
        "widths",
        "has 3 values, but interpolation `vertex` needs 2",
    );
    bad(
        &format!(
            "{lin}\nint[] curveVertexCounts = [2]\npoint3f[] points = [(0,0,0),(0,1,0)]\nfloat[] widths = [1, 2] (interpolation = \"uniform\")"
        ),
        "widths",
        "interpolation `uniform` needs 1",
    );
    bad(
        &format!("{lin}\nint[] curveVertexCounts = [2]\npoint3f[] points = [(0,0,0),(0,nan,0)]"),
        "points",
        "point 1 is not finite",
    );
    bad(
        &format!("{lin}\nint[] curveVertexCounts = [2]\npoint3f[] points = [(0,0,0),(0,inf,0)]"),
        "points",
        "point 1 is not finite",
    );
    bad(
        &format!(
            "uniform token type = \"cubic\"\nuniform token basis = \"hermite\"\nint[] curveVertexCounts = [4]\n{FOUR}"
        ),
        "basis",
        "`hermite` is not supported",
    );
    bad(
        &format!("{lin}\nuniform token wrap = \"periodic\"\nint[] curveVertexCounts = [4]\n{FOUR}"),
        "wrap",
        "`periodic` is not supported",
    );
    bad(
        "uniform token type = \"cubic\"\nint[] curveVertexCounts = [5]\npoint3f[] points = [(0,0,0),(1,0,0),(2,0,0),(3,0,0),(4,0,0)]",
        "curveVertexCounts",
        "a Bézier curve needs 4 + 3k",
    );
    bad(
        "uniform token type = \"linear\"\nint[] curveVertexCounts = [2]",
        "points",
        "is missing",
    );
    // A count claiming billions of vertices fails on the sum, allocating nothing.
    bad(
        &format!(
            "{lin}\nint[] curveVertexCounts = [2147483647, 2147483647]\npoint3f[] points = [(0,0,0),(0,1,0)]"
        ),
        "curveVertexCounts",
        "sums to 4294967294 vertices",
    );
}

#[test]
fn too_many_segments_per_span_is_refused() {
    let options = UsdOptions {
        segments_per_span: 0,
        ..UsdOptions::default()
    };
    let e = read_text(&cubic("bspline", "nonperiodic"), &options)
        .unwrap_err()
        .to_string();
    assert!(e.contains("segments_per_span must be in 1..=256"), "{e}");
}

fn sample_strands() -> Strands {
    let mut s = Strands::new();
    s.push_strand(
        &[
            Vec3::ZERO,
            Vec3::new(0.0, -0.1, 0.01),
            Vec3::new(0.0, -0.2, 0.03),
        ],
        |t| 0.002 * (1.0 - 0.5 * t),
        |t| 1.0 - 0.25 * t,
        Vec3::new(0.3, 0.2, 0.1),
    );
    s.push_strand(
        &[Vec3::new(0.05, 0.0, 0.0), Vec3::new(0.05, -0.15, 0.0)],
        |_| 0.001,
        |_| 0.75,
        Vec3::new(0.9, 0.8, 0.1),
    );
    s
}

#[test]
fn written_files_read_back_to_the_same_strands_in_every_container() {
    let s = sample_strands();
    for (format, name, magic) in [
        (WriteFormat::Usda, "w.usda", &b"#usda"[..]),
        (WriteFormat::Usdc, "w.usdc", &b"PXR-USDC"[..]),
        (WriteFormat::Usdz, "w.usdz", &b"PK\x03\x04"[..]),
    ] {
        let bytes = write(&s, format).unwrap();
        assert!(bytes.starts_with(magic), "{name}");
        let (g, warnings) =
            UsdGroom::from_bytes(Path::new(name), bytes, &UsdOptions::default(), false)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(warnings.is_empty(), "{name}: {warnings:?}");
        assert_eq!(g.strands, s, "{name}");
        assert_eq!(g.container, &name[2..], "{name}");
    }
}

#[test]
fn unwritable_strands_are_refused() {
    assert!(write(&Strands::new(), WriteFormat::Usda).is_err());
    let mut s = Strands::new();
    s.push_strand(&[Vec3::ZERO], |_| 1.0, |_| 1.0, Vec3::ONE);
    let e = write(&s, WriteFormat::Usda).unwrap_err().to_string();
    assert!(e.contains("strand 0 has 1 point(s)"), "{e}");
}

#[test]
fn overshooting_widths_are_zero_and_said() {
    // Catmull-Rom overshoots below 0 between widths 1, 0, 0, 1.
    let text = curves(&format!(
        "uniform token type = \"cubic\"\nuniform token basis = \"catmullRom\"\nint[] curveVertexCounts = [4]\n{FOUR}\nfloat[] widths = [4, 0, 0, 4]"
    ));
    let (g, warnings) = read_text(&text, &UsdOptions::default()).unwrap();
    assert!(g.strands.thickness.iter().all(|&w| w >= 0.0));
    assert!(g.strands.thickness.contains(&0.0));
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("/C: ") && w.contains("overshoot below 0")),
        "{warnings:?}"
    );
}

#[test]
fn a_transform_that_overflows_is_an_error() {
    let text = stage(
        "def BasisCurves \"C\"\n{\n    float3 xformOp:scale = (1e30, 1e30, 1e30)\n    uniform token[] xformOpOrder = [\"xformOp:scale\"]\n    uniform token type = \"linear\"\n    int[] curveVertexCounts = [2]\n    point3f[] points = [(0, 0, 0), (1e30, 0, 0)]\n}",
    );
    let e = read_err(&text);
    assert!(
        e.contains("prim `/C`, field `xformOpOrder`") && e.contains("not finite"),
        "{e}"
    );
}

/// Found by fuzzing: openusd 0.6 loops forever evaluating an xformOpOrder
/// entry that is not an attribute name; plait refuses it first.
#[test]
fn a_malformed_xform_op_order_is_an_error_not_a_hang() {
    let text = stage(
        "def Xform \"G\"\n{\n    double3 xformOp:translate = (1, 0, 0)\n    uniform token[] xformOpOrder = [\"xformOp:trty = [0.5]\n    }\n}\nanslate\"]\n    def BasisCurves \"H\"\n    {\n        uniform token type = \"linear\"\n        int[] curveVertexCounts = [2]\n        point3f[] points = [(0,0,0),(0,1,0)]\n    }\n}",
    );
    let e = read_err(&text);
    assert!(
        e.contains("prim `/G/H`, field `xformOpOrder`: on /G: ")
            && e.contains("is not an xformOp: attribute name"),
        "{e}"
    );
}

/// Found by fuzzing: openusd 0.6's traversal recurses without end on a
/// prim named by a string that is not an identifier; plait refuses it first.
#[test]
fn a_prim_name_that_is_not_an_identifier_is_an_error() {
    let e = read_err(&stage("def BasisCurves \"0,0),(1\n}\nB\"\n{\n}"));
    assert!(
        e.contains(
            "t.usda: not a readable USD file: prim name \"0,0),(1\\n}\\nB\" is not an identifier"
        ),
        "{e}"
    );
}

/// Layers a file names resolve beside it on disk; one that is missing or
/// not a regular file is a warning (the composition error), not a hang.
#[test]
fn layers_beside_the_file_compose_and_devices_are_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(
        dir.path().join("curves.usda"),
        curves("uniform token type = \"linear\"\nint[] curveVertexCounts = [2]\npoint3f[] points = [(0,0,0),(0,3,0)]"),
    )
    .expect("write");
    let root = stage(
        "def \"G\" (\n    prepend references = @./curves.usda@</C>\n)\n{\n}\ndef \"Z\" (\n    prepend references = @/dev/zero@</C>\n)\n{\n}",
    );
    let path = dir.path().join("root.usda");
    std::fs::write(&path, &root).expect("write");
    let (asset, warnings) =
        crate::Asset::read_with(&path, &UsdOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let strands = asset.strands();
    assert_eq!(strands.strand_count(), 1);
    assert_eq!(strands.points[1], Vec3::new(0.0, 3.0, 0.0));
    assert!(
        warnings.iter().any(|w| w.contains("/dev/zero")),
        "{warnings:?}"
    );
}
