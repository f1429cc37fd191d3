use super::interpolate::{blend, guide_grid, locate};
use super::*;

fn spec(style: Style) -> GroomSpec {
    GroomSpec {
        style,
        strands: 200,
        segments: 12,
        seed: 7,
        ..GroomSpec::default()
    }
}

fn head_level(spec: &GroomSpec, p: Vec3) -> f32 {
    ((p - Vec3::from(spec.head.center)) / Vec3::from(spec.head.radii)).length()
}

#[test]
fn deterministic_by_seed_and_counts() {
    for style in [Style::Straight, Style::Wavy, Style::Curly] {
        let s = spec(style);
        let a = generate(&s);
        let b = generate(&s);
        assert_eq!(a, b);
        assert_eq!(a.strand_count(), 200);
        assert_eq!(a.point_count(), 200 * 13);
        assert_eq!(a.segment_count(), 200 * 12);
        let c = generate(&GroomSpec {
            seed: 8,
            ..s.clone()
        });
        assert_ne!(a.points, c.points);
        assert!(a.points.iter().all(|p| p.is_finite()));
    }
}

#[test]
fn roots_on_scalp_hair_drapes_outside_head() {
    let s = spec(Style::Straight);
    let h = generate(&s);
    for r in h.ranges() {
        let pts = &h.points[r];
        assert!(
            (head_level(&s, pts[0]) - 1.0).abs() < 1e-3,
            "root on the head surface"
        );
        assert!(pts[0].z < 0.95 || pts[0].y > 0.3, "no roots on the face");
        for p in &pts[1..] {
            assert!(head_level(&s, *p) > 0.999, "hair stays outside the head");
        }
        // it drapes: the tip is lower than the root
        assert!(pts[pts.len() - 1].y < pts[0].y);
    }
    // variation: strands differ in thickness, alpha and color
    assert!(
        h.thickness
            .iter()
            .any(|&t| (t - h.thickness[0]).abs() > 1e-6)
    );
    assert!(h.alpha.iter().any(|&a| a != h.alpha[0]));
    assert!(h.color.iter().any(|&c| c != h.color[0]));
    assert!(h.alpha.iter().all(|a| (0.0..=1.0).contains(a)));
}

fn mean_deviation_from_chord(h: &Strands) -> f32 {
    let mut sum = 0.0;
    let mut n = 0;
    for r in h.ranges() {
        let p = &h.points[r];
        for k in 1..p.len() - 1 {
            // second difference magnitude ~ local wiggle
            sum += (p[k - 1] + p[k + 1] - 2.0 * p[k]).length();
            n += 1;
        }
    }
    sum / n as f32
}

#[test]
fn wavy_and_curly_wiggle_more_than_straight() {
    // enough segments to resolve the curl period
    let fine = |style| GroomSpec {
        segments: 64,
        ..spec(style)
    };
    let st = mean_deviation_from_chord(&generate(&fine(Style::Straight)));
    let wv = mean_deviation_from_chord(&generate(&fine(Style::Wavy)));
    let cu = mean_deviation_from_chord(&generate(&fine(Style::Curly)));
    assert!(wv > st * 1.2, "wavy {wv} vs straight {st}");
    assert!(cu > wv, "curly {cu} vs wavy {wv}");
}

#[test]
fn stray_strands_stand_off_the_volume() {
    let s = GroomSpec {
        stray_strands: 5,
        ..spec(Style::Straight)
    };
    let h = generate(&s);
    assert_eq!(h.strand_count(), 205);
    let main = &h.points[..200 * 13];
    for i in 200..205 {
        // the farthest point of the stray from the main volume
        let off = h
            .strand(i)
            .iter()
            .map(|p| {
                main.iter()
                    .map(|q| (*p - *q).length())
                    .fold(f32::INFINITY, f32::min)
            })
            .fold(0.0f32, f32::max);
        assert!(off > 0.2, "stray {i} only {off} away from the main volume");
        assert!(
            (head_level(&s, h.strand(i)[0]) - 1.0).abs() < 1e-3,
            "stray roots on the scalp"
        );
    }
}

#[test]
fn guide_interpolation_is_barycentric() {
    let s = GroomSpec {
        guides: Some(60),
        style: Style::Wavy,
        ..spec(Style::Straight)
    };
    let h = generate(&s);
    assert_eq!(h.strand_count(), 200);
    assert_eq!(h.point_count(), 200 * 13);
    assert_eq!(h, generate(&s));
    // every rendered strand starts on the scalp and follows the guides'
    // overall shape (drapes down)
    for r in h.ranges() {
        let p = &h.points[r];
        assert!((head_level(&s, p[0]) - 1.0).abs() < 1e-3);
        assert!(p[p.len() - 1].y < p[0].y);
    }
    let (rows, cols) = guide_grid(60);
    assert!(rows * cols >= 40 && rows >= 2 && cols >= 3);
}

#[test]
fn scalp_triangulation_gives_true_barycentric_coordinates() {
    let (rows, cols) = (5, 8);
    let mut rng = SplitMix64::new(3);
    for _ in 0..1000 {
        let (u, v) = (rng.next_f32(), rng.next_f32());
        let (corners, w) = locate(u, v, rows, cols);
        assert!(w.iter().all(|&x| x >= -1e-6), "{w:?}");
        assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-5);
        // the weighted corner parameters reproduce (u, v)
        let mut pu = 0.0;
        let mut pv = 0.0;
        for ((i, j), wt) in corners.iter().zip(w) {
            pu += wt * *i as f32 / (rows - 1) as f32;
            pv += wt * *j as f32 / cols as f32;
        }
        assert!(
            (pu - u).abs() < 1e-4 && (pv - v).abs() < 1e-4,
            "({u},{v}) -> ({pu},{pv})"
        );
    }
}

#[test]
fn blend_reproduces_guides_and_averages() {
    let g0 = vec![
        Vec3::ZERO,
        Vec3::new(0.0, -1.0, 0.0),
        Vec3::new(0.5, -2.0, 0.0),
    ];
    let g1 = vec![
        Vec3::X,
        Vec3::new(1.0, -1.0, 1.0),
        Vec3::new(1.0, -2.0, 2.0),
    ];
    let g2 = vec![
        Vec3::Z,
        Vec3::new(0.0, -1.0, 1.0),
        Vec3::new(0.0, -3.0, 1.0),
    ];
    // weight 1 on a guide: that guide, moved to the new root
    let b = blend([&g0, &g1, &g2], [0.0, 1.0, 0.0], Vec3::X, 1.0);
    assert_eq!(b, g1);
    let b = blend([&g0, &g1, &g2], [1.0, 0.0, 0.0], Vec3::Y, 1.0);
    assert_eq!(b, g0.iter().map(|p| *p + Vec3::Y).collect::<Vec<_>>());
    // equal weights: the average shape
    let w = 1.0 / 3.0;
    let b = blend([&g0, &g1, &g2], [w, w, w], Vec3::ZERO, 1.0);
    let avg_tip = (g0[2] + g1[2] + g2[2]) * w - (g0[0] + g1[0] + g2[0]) * w;
    assert!((b[2] - avg_tip).length() < 1e-5);
}

#[test]
fn validate_names_fields() {
    assert!(GroomSpec::default().validate().is_ok());
    let e = GroomSpec {
        segments: 0,
        ..GroomSpec::default()
    }
    .validate()
    .unwrap_err();
    assert!(e.contains("segments"));
    let e = GroomSpec {
        segments: 70000,
        ..GroomSpec::default()
    }
    .validate()
    .unwrap_err();
    assert!(e.contains("segments"));
    let e = GroomSpec {
        length: f32::NAN,
        ..GroomSpec::default()
    }
    .validate()
    .unwrap_err();
    assert!(e.contains("length"));
    let e = GroomSpec {
        strands: u32::MAX,
        segments: 65535,
        ..GroomSpec::default()
    }
    .validate()
    .unwrap_err();
    assert!(e.contains("points"));
}

#[test]
fn spec_parses_from_toml_and_rejects_unknown_fields() {
    let s: GroomSpec =
        toml::from_str("style = \"curly\"\nstrands = 10\nguides = 30\n").expect("parse");
    assert_eq!(s.style, Style::Curly);
    assert_eq!(s.guides, Some(30));
    assert_eq!(s.segments, GroomSpec::default().segments);
    assert!(toml::from_str::<GroomSpec>("strandz = 3").is_err());
}
