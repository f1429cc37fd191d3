//! Marschner's lobes against Chiang's, lobe by lobe: plait's `marschner`
//! functions (shaders/lib/marschner.wgsl: the exact `longitudinal` ×
//! `azimuthal` the `marschner_reference` technique shades with, and the
//! `marschner` technique tabulates — tests/shading.rs holds its tables to
//! them) on the GPU, R, TT and TRT alone (the fixture's right half), against
//! Chiang, Bitterli, Tappan & Burley 2016's lobes (EGSR) as Mitsuba 3's hair
//! BSDF evaluates them: tests/fixtures/marschner_mitsuba.txt, written by
//! scripts/mitsuba/marschner_lobes.py from a port of the lobes that it holds
//! to Mitsuba's sum and to Mitsuba's R (σ_a = 10⁴) point by point.
//!
//! Per light and lobe, three statistics ([`lobe_statistics`], the script's
//! `statistics`): where the lobe's energy peaks along the fibre (θo + θi,
//! 0 at the mirror direction), around it (|φo|: 0 towards the light's side,
//! 180° opposite it) and how much energy it carries (∫ f dωo). The two
//! models differ by design — Marschner et al. 2003's cuticle shifts α_R =
//! −7.5°, α_TT = 3.75°, α_TRT = 11.25° (Halén & Wester's defaults) against
//! Chiang's single tilt α = 2° (R at −2α, TT at +α, TRT at +4α: the same
//! sides, towards the root for R, the tip for TT and TRT — issue 42; the
//! fixture is Mitsuba at the export's scale_tilt −α, see
//! `every_lobe_leaves_on_its_cuticles_side`), Gaussian M_p in θh against d'Eon's, no energy
//! conservation, caustics clamped — and the test holds each difference at
//! its measured value, so a lobe that moves, swaps or vanishes fails.

use super::{ANGLES, AZIMUTHS, ChiangSphere, LIGHT_DEGREES, Sphere, theta_o};
use plait_tests::repo_root;
use std::f64::consts::PI;

/// Where a lobe goes and how much of it there is.
#[derive(Debug, Clone, Copy)]
pub struct LobeStatistics {
    /// θo + θi at the peak of cos θo Σ_φ f, degrees (parabolic refinement).
    pub shift: f64,
    /// |φo| at the peak of Σ_θ f cos θo, degrees in [0, 180].
    pub azimuth: f64,
    /// ∫ f dωo by the midpoint rule.
    pub energy: f64,
}

/// The statistics of the grid `f(j, i)` (row j: θo, column i: φo) under a
/// light at `theta_i_deg`.
pub fn lobe_statistics(f: impl Fn(usize, usize) -> f64, theta_i_deg: f64) -> LobeStatistics {
    let (d_theta, d_phi) = (PI / ANGLES as f64, 2.0 * PI / AZIMUTHS as f64);
    let lon: Vec<f64> = (0..ANGLES)
        .map(|j| theta_o(j).cos() * (0..AZIMUTHS).map(|i| f(j, i)).sum::<f64>())
        .collect();
    let azi: Vec<f64> = (0..AZIMUTHS)
        .map(|i| (0..ANGLES).map(|j| f(j, i) * theta_o(j).cos()).sum())
        .collect();
    let argmax = |v: &[f64]| (0..v.len()).fold(0, |best, k| if v[k] > v[best] { k } else { best });
    let j = argmax(&lon);
    let mut frac = 0.0;
    if j > 0 && j + 1 < ANGLES {
        let (a, b, c) = (lon[j - 1], lon[j], lon[j + 1]);
        let den = a - 2.0 * b + c;
        if den != 0.0 {
            frac = 0.5 * (a - c) / den;
        }
    }
    let i = argmax(&azi);
    let phi = (i as f64 + 0.5) * 360.0 / AZIMUTHS as f64;
    LobeStatistics {
        shift: theta_o(j).to_degrees() + frac * 180.0 / ANGLES as f64 + theta_i_deg,
        azimuth: phi.min(360.0 - phi),
        energy: azi.iter().sum::<f64>() * d_theta * d_phi,
    }
}

const LOBES: [&str; 3] = ["R", "TT", "TRT"];

/// The fixture's statistics, `[light][lobe]`.
fn chiang_lobes() -> Vec<[LobeStatistics; 3]> {
    let path = repo_root().join("tests/fixtures/marschner_mitsuba.txt");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut out = vec![
        [LobeStatistics {
            shift: f64::NAN,
            azimuth: f64::NAN,
            energy: f64::NAN
        }; 3];
        LIGHT_DEGREES.len()
    ];
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let w: Vec<&str> = line.split_whitespace().collect();
        let Some(p) = LOBES.iter().position(|l| *l == w[0]) else {
            continue;
        };
        let k: usize = w[1].parse().unwrap();
        let num = |n: usize| w[n].parse::<f64>().unwrap();
        out[k][p] = LobeStatistics {
            shift: num(3),
            azimuth: num(4),
            energy: num(5),
        };
    }
    assert!(
        out.iter().flatten().all(|s| s.energy.is_finite()),
        "{}: a (lobe, light) row is missing",
        path.display()
    );
    out
}

/// plait − Chiang, measured: `[light][lobe]` = (Δ shift °, Δ azimuth °,
/// energy ratio plait / Chiang).
/// Measured on lavapipe (Mesa 25.0.7) by this test's own table (`cargo test
/// -p plait-tests --test fibre marschner_lobes -- --nocapture`).
const HELD: [[(f64, f64, f64); 3]; 4] = [
    [
        (-10.74, 5.63, 0.945),
        (5.49, -0.00, 0.996),
        (12.03, 16.88, 0.744),
    ],
    [
        (-9.36, 5.63, 0.909),
        (5.04, -0.00, 0.984),
        (18.13, 0.00, 0.676),
    ],
    [
        (-4.76, 4.22, 1.219),
        (3.82, -0.00, 0.972),
        (10.68, 0.00, 0.616),
    ],
    [
        (-4.27, 43.59, 0.949),
        (2.59, -0.00, 0.438),
        (-0.44, 0.00, 0.376),
    ],
];

#[test]
fn marschner_lobes_against_chiang() {
    let sphere = Sphere::render();
    let chiang = chiang_lobes();
    let mut failures = Vec::new();
    println!(
        "| θi | lobe | shift plait | shift Chiang | azimuth plait | azimuth Chiang | energy plait | energy Chiang | ratio |"
    );
    println!("|---:|---|---:|---:|---:|---:|---:|---:|---:|");
    for (k, degrees) in LIGHT_DEGREES.iter().enumerate() {
        for (p, name) in LOBES.iter().enumerate() {
            let m = lobe_statistics(|j, i| sphere.at(1, k, j, i)[p] as f64, *degrees);
            let c = chiang[k][p];
            let (d_shift, d_azimuth, ratio) = (
                m.shift - c.shift,
                m.azimuth - c.azimuth,
                m.energy / c.energy,
            );
            println!(
                "| {degrees:.0}° | {name} | {:.1}° | {:.1}° | {:.1}° | {:.1}° | {:.4} | {:.4} | {ratio:.3} |",
                m.shift, c.shift, m.azimuth, c.azimuth, m.energy, c.energy
            );
            let (hs, ha, hr) = HELD[k][p];
            // One row of the grid is 1.4°, one column 1.4°. TRT at θi 0°:
            // the caustic clamp flattens its azimuthal profile's top, and
            // where on the plateau the maximum falls is no model property.
            let azimuth_margin = if *degrees == 0.0 && p == 2 { 20.0 } else { 3.0 };
            if (d_shift - hs).abs() > 1.5
                || (d_azimuth - ha).abs() > azimuth_margin
                || (ratio / hr - 1.0).abs() > 0.05
            {
                failures.push(format!(
                    "θi {degrees}° {name}: plait − Chiang shift {d_shift:.2}° (held {hs}), azimuth {d_azimuth:.2}° (held {ha}), energy ratio {ratio:.4} (held {hr})"
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Issue 42: every lobe leaves on its cuticle's side. Under a light in the
/// normal plane (θi 0) an untilted fibre's lobes are symmetric in θo (M_p,
/// the Fresnel factors and η' depend on θo through cos θo and sin² θo), so
/// the peak's side is the tilt's alone. With θ measured towards the tip
/// (plait's tangent runs root to tip) and scales pointing to the tip, R
/// leaves towards the root (θo + θi < 0: Marschner et al. 2003's α_R < 0)
/// and TT, TRT towards the tip. Held for plait's `marschner` (α_R −7.5°),
/// plait's `chiang` (the WGSL, R, TT and TRT alone, α 2°) and Chiang's lobes
/// as Mitsuba evaluates them at the export's scale_tilt (the fixture). The
/// margins are a third of the smallest expected shift (Chiang's TT, α).
#[test]
fn every_lobe_leaves_on_its_cuticles_side() {
    let (marschner, chiang_wgsl) = (Sphere::render(), ChiangSphere::render());
    let chiang = chiang_lobes();
    let mut failures = Vec::new();
    for (p, name) in LOBES.iter().enumerate() {
        let shifts = [
            (
                "marschner",
                lobe_statistics(|j, i| marschner.at(1, 0, j, i)[p] as f64, 0.0).shift,
            ),
            (
                "chiang (WGSL)",
                lobe_statistics(|j, i| chiang_wgsl.at(p + 1, 0, j, i)[3] as f64, 0.0).shift,
            ),
            ("Chiang (Mitsuba, the export's tilt)", chiang[0][p].shift),
        ];
        for (model, shift) in shifts {
            println!("θi 0° {name} {model}: θo + θi at the peak {shift:.2}°");
            let on_side = if p == 0 { shift < -0.6 } else { shift > 0.6 };
            if !on_side {
                failures.push(format!(
                    "{model} {name}: θo + θi {shift:.2}° (want {} 0.6°: towards the {})",
                    if p == 0 { "< -" } else { ">" },
                    if p == 0 { "root" } else { "tip" }
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
