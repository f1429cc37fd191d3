//! The exporter on a hand-built two-strand scene: radii, colour groups,
//! camera, light, and the errors for what Mitsuba cannot express.

use std::path::Path;

use glam::{Vec3, Vec4};

use super::*;
use plait_hair::{Scene, Strands};

/// The standard fibre of the library on the search path.
fn standard() -> Fibre {
    Fibre::standard(&plait_passes::read_library(&[]))
}

const SCENE: &str = r#"
ambient = 0.25
[hair.procedural]
strands = 1
segments = 2
[ground]
height = -2.0
half_size = 3.0
albedo = [0.6, 0.5, 0.4]
[camera]
eye = [0.0, 1.0, 6.0]
target = [0.0, 0.0, 0.0]
fov_y_degrees = 30.0
near = 0.5
far = 50.0
[light]
type = "directional"
direction = [0.0, -1.0, -1.0]
color = [1.0, 0.5, 0.25]
intensity = 4.0
[background]
color = [0.1, 0.2, 0.3]
[material]
color = [1.0, 0.5, 1.0]
"#;

/// The scene above with two hand-built strands of different colours and
/// thickness profiles in place of its groom.
fn two_strands() -> SceneData {
    let scene = Scene::from_toml_str(SCENE, Path::new("two.toml")).expect("scene parses");
    let mut data = SceneData::new(scene).expect("scene loads");
    let mut s = Strands::new();
    let line = |x: f32| {
        [
            Vec3::new(x, 0.0, 0.0),
            Vec3::new(x, -1.0, 0.0),
            Vec3::new(x, -2.0, 0.5),
        ]
    };
    s.push_strand(
        &line(-0.5),
        |t| 0.02 * (1.0 - 0.5 * t),
        |_| 1.0,
        Vec3::new(0.5, 0.5, 0.1),
    );
    s.push_strand(&line(0.5), |_| 0.01, |_| 0.5, Vec3::new(0.8, 0.6, 0.4));
    data.strands = s;
    data
}

#[test]
fn radii_are_half_the_thickness_and_colours_make_groups() {
    let m = plan(&two_strands(), (32, 24), standard()).expect("exports");
    assert_eq!(m.hair.len(), 2, "two colours, two shapes");
    let g0 = &m.hair[0];
    // material.color (1, 0.5, 1) tints the strand's colour.
    assert_eq!(g0.color, Vec3::new(0.5, 0.25, 0.1));
    assert_eq!(g0.alpha, 1.0);
    let radii: Vec<f32> = g0.strands[0].iter().map(|p| p.1).collect();
    assert_eq!(radii, vec![0.01, 0.0075, 0.005], "radius = thickness / 2");
    assert_eq!(m.hair[1].alpha, 0.5);
    assert_eq!(m.hair[1].strands[0][2].0, Vec3::new(0.5, -2.0, 0.5));
    // Chiang et al. 2016 §4.2 at β_n = 0.3: the denominator is
    // 5.969 − 0.215·0.3 + 2.532·0.09 − 10.73·0.027 + 5.574·0.0081 + 0.245·0.00243.
    let d = 5.888_414_75_f64;
    let want = [0.5f64, 0.25, 0.1].map(|c| (c.ln() / d).powi(2));
    for (got, want) in g0.sigma_a.to_array().iter().zip(want) {
        let got = f64::from(*got);
        assert!((got - want).abs() < 1e-6 * want, "σ_a {got} vs {want}");
    }
    let xml = m.xml();
    assert!(xml.contains("<rgb name=\"sigma_a\""), "{xml}");
    assert!(
        xml.contains("<bsdf type=\"mask\">\n    <float name=\"opacity\" value=\"0.5\"/>"),
        "{xml}"
    );
    assert_eq!(
        xml.matches("<bsdf type=\"mask\">").count(),
        1,
        "only the half-opaque group is masked"
    );
}

#[test]
fn camera_light_ambient_and_background_in_plaits_units() {
    let m = plan(&two_strands(), (32, 24), standard()).expect("exports");
    let xml = m.xml();
    for want in [
        "<lookat origin=\"0, 1, 6\" target=\"0, 0, 0\" up=\"0, 1, 0\"/>",
        "<float name=\"fov\" value=\"30\"/>",
        "<string name=\"fov_axis\" value=\"y\"/>",
        "<float name=\"near_clip\" value=\"0.5\"/>",
        "<float name=\"far_clip\" value=\"50\"/>",
        "<integer name=\"width\" value=\"32\"/>",
        "<integer name=\"height\" value=\"24\"/>",
        "<rfilter type=\"box\"/>",
        // irradiance = intensity × colour
        "<rgb name=\"irradiance\" value=\"4, 2, 1\"/>",
        "<rgb name=\"radiance\" value=\"0.25, 0.25, 0.25\"/>",
        "<rgb name=\"reflectance\" value=\"0.6, 0.5, 0.4\"/>",
    ] {
        assert!(xml.contains(want), "missing {want} in\n{xml}");
    }
    let MitsubaLight::Directional { direction: d, .. } = m.light else {
        panic!("a directional light: {:?}", m.light);
    };
    assert!(
        (d - Vec3::new(0.0, -1.0, -1.0).normalize()).length() < 1e-6,
        "travel direction {d}"
    );
    assert_eq!(m.background, Vec3::new(0.1, 0.2, 0.3));
    assert!(
        m.notes.iter().any(|n| n.contains("Kajiya-Kay")),
        "{:?}",
        m.notes
    );
}

#[test]
fn the_folder_holds_every_file_the_xml_names() {
    let dir = tempfile::tempdir().expect("temp dir");
    let written = plan(&two_strands(), (32, 24), standard())
        .expect("exports")
        .write(dir.path())
        .expect("writes");
    let names: Vec<String> = written
        .files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "scene.xml",
            "hair_0.txt",
            "hair_1.txt",
            "mesh_0.obj",
            "plait.json"
        ]
    );
    // hair_0.txt: the B-spline's control points, the curve through the
    // strand's points (x y z radius) at its knots.
    let curve = std::fs::read_to_string(dir.path().join("hair_0.txt")).unwrap();
    let c = &curve_strands(&curve)[0];
    let want = [
        Vec4::new(-0.5, 0.0, 0.0, 0.01),
        Vec4::new(-0.5, -1.0, 0.0, 0.0075),
        Vec4::new(-0.5, -2.0, 0.5, 0.005),
    ];
    assert_eq!(c.len(), want.len() + 2, "{curve}");
    for (i, w) in want.iter().enumerate() {
        let at_knot = (c[i] + 4.0 * c[i + 1] + c[i + 2]) / 6.0;
        assert!(
            (at_knot - *w).abs().max_element() < 1e-6,
            "point {i}: {at_knot} != {w}"
        );
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("plait.json")).unwrap())
            .unwrap();
    assert_eq!(
        json["background"],
        serde_json::json!([0.1f32, 0.2f32, 0.3f32])
    );
    assert_eq!(json["hair_groups"][1]["strands"], 1);
}

#[test]
fn what_mitsuba_cannot_express_is_an_error() {
    let mut data = two_strands();
    data.scene.background = plait_hair::Background::Image("sky.png".into());
    let e = plan(&data, (8, 8), standard()).unwrap_err().to_string();
    assert!(e.contains("background image (sky.png)"), "{e}");

    // A spot whose cone leaves strands out of plait's shadow frustum: those
    // strands would shadow in Mitsuba and not in plait.
    let mut data = two_strands();
    data.scene.light.kind = plait_hair::LightKind::Spot {
        position: [0.0, 3.0, 0.0],
        direction: [0.0, -1.0, 0.0],
        cone_degrees: 8.0,
    };
    let e = plan(&data, (8, 8), standard()).unwrap_err().to_string();
    assert!(
        e.contains("spot light whose shadow frustum leaves out occluders")
            && e.contains("strand points"),
        "{e}"
    );

    let mut data = two_strands();
    data.scene.material.color = [1.0, 0.0, 1.0];
    let e = plan(&data, (8, 8), standard()).unwrap_err().to_string();
    assert!(e.contains("no") || e.contains("absorption"), "{e}");
}

#[test]
fn a_colour_changing_along_a_strand_is_noted() {
    let mut data = two_strands();
    data.strands.color[1] = Vec3::new(0.2, 0.2, 0.2);
    let m = plan(&data, (8, 8), standard()).expect("exports");
    assert!(
        m.notes
            .iter()
            .any(|n| n.starts_with("1 strand(s) change colour")),
        "{:?}",
        m.notes
    );
}

/// The B-spline passes through every point of a strand (at its knots) and
/// has no curvature at either end; a straight strand stays straight.
#[test]
fn the_bspline_passes_through_every_point() {
    let strand: Vec<(Vec3, f32)> = (0..7)
        .map(|i| {
            let t = i as f32;
            (Vec3::new(t, (0.7 * t).sin(), 0.1 * t * t), 0.01 + 0.001 * t)
        })
        .collect();
    let c = super::write::through_points(&strand);
    assert_eq!(c.len(), strand.len() + 2);
    for (i, (p, r)) in strand.iter().enumerate() {
        let at_knot = (c[i] + 4.0 * c[i + 1] + c[i + 2]) / 6.0;
        assert!(
            (at_knot - p.extend(*r)).abs().max_element() < 1e-5,
            "point {i}: {at_knot}"
        );
    }
    let n = c.len();
    assert!(
        (c[0] - 2.0 * c[1] + c[2]).abs().max_element() < 1e-6,
        "natural start"
    );
    assert!(
        (c[n - 1] - 2.0 * c[n - 2] + c[n - 3]).abs().max_element() < 1e-6,
        "natural end"
    );
    let line: Vec<(Vec3, f32)> = (0..5)
        .map(|i| (Vec3::new(i as f32, 0.3, 0.0), 0.1))
        .collect();
    for c in super::write::through_points(&line) {
        assert!(
            (c.y - 0.3).abs() < 1e-6 && c.z == 0.0 && (c.w - 0.1).abs() < 1e-6,
            "{c}"
        );
    }
}

/// A tip of radius 0 after thick points: the exact spline's end control
/// radius is negative; it is written as 0 and the strand is counted.
#[test]
fn a_sharp_taper_is_clamped_and_counted() {
    let strand: Vec<(Vec3, f32)> = [0.02, 0.02, 0.02, 0.0]
        .iter()
        .enumerate()
        .map(|(i, r)| (Vec3::new(i as f32, 0.0, 0.0), *r))
        .collect();
    assert!(super::write::radius_dips_below_zero(&strand));
    let c = super::write::through_points(&strand);
    assert!(c.iter().all(|c| c.w >= 0.0), "{c:?}");
    assert_eq!(c.last().unwrap().w, 0.0);
    let even: Vec<(Vec3, f32)> = strand.iter().map(|(p, _)| (*p, 0.01)).collect();
    assert!(!super::write::radius_dips_below_zero(&even));
}

/// A spot light whose cone holds every occluder is Mitsuba's point light of
/// the same radiant intensity (plait's spot has no angular falloff).
#[test]
fn a_spot_light_holding_the_hair_is_a_point_light() {
    let mut data = two_strands();
    data.scene.light.kind = plait_hair::LightKind::Spot {
        position: [0.0, 3.0, 0.0],
        direction: [0.0, -1.0, 0.0],
        cone_degrees: 40.0,
    };
    let m = plan(&data, (8, 8), standard()).expect("exports");
    assert_eq!(
        m.light,
        MitsubaLight::Point {
            position: Vec3::new(0.0, 3.0, 0.0),
            intensity: data.scene.light.radiance(),
        }
    );
    let xml = m.xml();
    assert!(xml.contains("<emitter type=\"point\">"), "{xml}");
    assert!(
        xml.contains("<point name=\"position\" value=\"0, 3, 0\"/>"),
        "{xml}"
    );
    assert!(!xml.contains("directional"), "{xml}");
}

/// A groom whose every strand has its own alpha (past 64 distinct values)
/// is exported with alphas rounded to 1/256 — a few groups, each strand
/// moved by at most half a step — and the note says so; up to 64 distinct
/// values the export is exact (the test above).
#[test]
fn a_groom_of_distinct_alphas_is_rounded_to_few_groups_and_noted() {
    let mut data = two_strands();
    let mut s = Strands::new();
    for i in 0..100 {
        let x = i as f32 * 0.01;
        let points = [Vec3::new(x, 0.0, 0.0), Vec3::new(x, -1.0, 0.0)];
        let alpha = 0.5 + 0.001 * i as f32;
        s.push_strand(&points, |_| 0.01, |_| alpha, Vec3::new(0.5, 0.5, 0.5));
    }
    data.strands = s;
    let m = plan(&data, (8, 8), standard()).expect("exports");
    // 0.5 … 0.599 spans 0.099 × 256 ≈ 25 steps.
    assert!((20..=27).contains(&m.hair.len()), "{} groups", m.hair.len());
    for (g, strand) in m
        .hair
        .iter()
        .flat_map(|g| g.strands.iter().map(move |s| (g, s)))
    {
        let i = (strand[0].0.x / 0.01).round();
        let exact = (0.5 + 0.001 * i) * data.scene.material.alpha;
        assert!(
            (g.alpha - exact).abs() <= 0.5 / 256.0 + 1e-6,
            "{} vs {exact}",
            g.alpha
        );
    }
    assert!(
        m.notes
            .iter()
            .any(|n| n.contains("rounded to a multiple of 1/256")),
        "{:?}",
        m.notes
    );
}

/// The strands of a `bsplinecurve` file: control points, blank lines between.
fn curve_strands(text: &str) -> Vec<Vec<Vec4>> {
    text.split("\n\n")
        .map(|strand| {
            strand
                .lines()
                .map(|l| {
                    let f: Vec<f32> = l.split(' ').map(|x| x.parse().unwrap()).collect();
                    Vec4::from_slice(&f)
                })
                .collect()
        })
        .collect()
}

/// Mitsuba 3.9.1 reads one segment past the end of a curve file for a hit
/// at the end of its last segment (`write::terminator`): every file the
/// export writes ends with a segment of radius 0 at the last strand's tip,
/// after the strands, whose segments keep their indices.
#[test]
fn every_curve_file_ends_with_a_segment_no_ray_can_hit() {
    let dir = tempfile::tempdir().expect("temp dir");
    let m = plan(&two_strands(), (32, 24), standard()).expect("exports");
    m.write(dir.path()).expect("writes");
    assert!(
        m.notes
            .iter()
            .any(|n| n.contains("radius 0 at its last strand's tip")),
        "{:?}",
        m.notes
    );
    for (k, g) in m.hair.iter().enumerate() {
        let text = std::fs::read_to_string(dir.path().join(format!("hair_{k}.txt"))).unwrap();
        let strands = curve_strands(&text);
        assert_eq!(strands.len(), g.strands.len() + 1, "hair_{k}.txt:\n{text}");
        let tip = *strands[strands.len() - 2].last().unwrap();
        let last = &strands[strands.len() - 1];
        assert_eq!(last.len(), 4, "hair_{k}.txt: the terminator is one segment");
        for c in last {
            assert_eq!(*c, tip.truncate().extend(0.0), "hair_{k}.txt");
        }
        // Every strand before it has a surface: its segments are the ones
        // Mitsuba's prim_index counts, in plait's order.
        for (s, points) in strands[..g.strands.len()].iter().zip(&g.strands) {
            assert_eq!(s.len(), points.len() + 2);
            assert!(s.iter().all(|c| c.w > 0.0), "hair_{k}.txt: {s:?}");
        }
    }
}

/// Issue 42: Mitsuba's `scale_tilt` is −α. Its hair BSDF moves R by +2·
/// scale_tilt towards the curve's last control point, and the export writes
/// each strand root first; plait's α > 0 (scales pointing to the tip) puts
/// R towards the root. A positive `scale_tilt` here would put Mitsuba's
/// highlight on the other side of plait's (`scripts/mitsuba/tilt_side.py`).
#[test]
fn the_cuticle_tilt_reaches_mitsuba_negated_for_curves_written_root_first() {
    let fibre = standard();
    assert!(fibre.scale_tilt_degrees > 0.0, "{fibre:?}");
    let xml = plan(&two_strands(), (8, 8), fibre).expect("exports").xml();
    let want = format!(
        "<float name=\"scale_tilt\" value=\"{}\"/>",
        -fibre.scale_tilt_degrees
    );
    assert_eq!(xml.matches(&want).count(), 2, "{want} in\n{xml}");
    // Root first: `the_folder_holds_every_file_the_xml_names` holds the
    // curve file's first knot to the strand's root.
}
