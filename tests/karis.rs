//! Karis 2016's multiple-scattering term (techniques/multiple_scattering/
//! karis/): the provider's value on a sphere of eye directions against the
//! formula, evaluated here in f64 —
//!   v · √base · (1/π) · mix(sat((N'·L + 1)/4), 1 − |T·L|, 0.33) · scatter
//!     · (base / luma)^(1 − v),
//! N' the eye direction projected normal to the strand, luma with Unreal's
//! weights (0.3, 0.59, 0.11), v the self-shadow visibility.

use std::f64::consts::PI;

use plait_tests::fixture_texels;

const AZIMUTHS: usize = 64;
const ANGLES: usize = 32;

fn direction(theta: f64, phi: f64) -> [f64; 3] {
    [
        theta.sin(),
        theta.cos() * phi.cos(),
        theta.cos() * phi.sin(),
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The formula at the fixture's light, base, visibility and scatter.
fn karis(e: [f64; 3], base: [f64; 3]) -> [f64; 3] {
    let (t, l) = ([1.0, 0.0, 0.0], direction(PI / 6.0, 0.0));
    let (v, scatter) = (0.5, 0.8);
    let kajiya = 1.0 - dot(t, l).abs();
    let p = [e[0] - dot(e, t), e[1], e[2]];
    let norm = dot(p, p).sqrt();
    let n = p.map(|c| c / norm);
    let wrap = ((dot(n, l) + 1.0) / 4.0).clamp(0.0, 1.0);
    let diffuse = (1.0 / PI) * (wrap + (kajiya - wrap) * 0.33) * scatter;
    let luma = 0.3 * base[0] + 0.59 * base[1] + 0.11 * base[2];
    base.map(|b: f64| v * b.sqrt() * diffuse * (b / luma).powf(1.0 - v))
}

#[test]
fn karis_adds_exactly_its_formula() {
    let size = (AZIMUTHS as u32, ANGLES as u32);
    let texels: Vec<[f64; 4]> = fixture_texels("karis_cases.toml", size, &["cases"])
        .remove(0)
        .into_iter()
        .map(|t| t.map(f64::from))
        .collect();
    let mut worst = 0.0_f64;
    for j in 0..ANGLES {
        let theta = -0.5 * PI + (j as f64 + 0.5) * PI / ANGLES as f64;
        for i in 0..AZIMUTHS {
            let phi = (i as f64 + 0.5) * 2.0 * PI / AZIMUTHS as f64;
            // The right half of the columns: the blond base 10⁷ times
            // darker, where the formula must still hold (relative to the
            // value itself: every value here is positive).
            let blond = [0.85, 0.65, 0.40];
            let base = if i >= AZIMUTHS / 2 {
                blond.map(|b| b * 1e-7)
            } else {
                blond
            };
            let want = karis(direction(theta, phi), base);
            let got = texels[j * AZIMUTHS + i];
            for c in 0..3 {
                worst = worst.max((got[c] - want[c]).abs() / want[c].abs().max(1e-30));
            }
        }
    }
    println!("largest relative difference from the formula: {worst:e}");
    assert!(
        worst < 1e-4,
        "karis differs from its formula by {worst} (relative)"
    );
}
