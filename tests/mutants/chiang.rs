//! `shading/chiang`: the fibre constants of `shaders/lib/chiang.wgsl`.

use std::f64::consts::PI;

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

/// Chiang, Bitterli, Tappan & Burley 2016 §4.1–4.2 at β_m = β_n = β, in
/// f64: the longitudinal variance v = (0.726β + 0.812β² + 3.7β²⁰)², the
/// logistic scale s = √(π/8)(0.265β + 1.194β² + 5.372β²²), the trimmed
/// logistic's normalisation 1 / (F(π) − F(−π)) with F the logistic's CDF of
/// scale s, and σ_a = (ln c / (5.969 − 0.215β + 2.532β² − 10.73β³ + 5.574β⁴
/// + 0.245β⁵))² for a colour c.
fn closed_form(beta: f64, colour: f64) -> [f64; 4] {
    let v = (0.726 * beta + 0.812 * beta.powi(2) + 3.7 * beta.powi(20)).powi(2);
    let s = (PI / 8.0).sqrt() * (0.265 * beta + 1.194 * beta.powi(2) + 5.372 * beta.powi(22));
    let cdf = |x: f64| 1.0 / (1.0 + (-x / s).exp());
    let trim = 1.0 / (cdf(PI) - cdf(-PI));
    let denominator = 5.969 - 0.215 * beta + 2.532 * beta.powi(2) - 10.73 * beta.powi(3)
        + 5.574 * beta.powi(4)
        + 0.245 * beta.powi(5);
    let sigma_a = (colour.ln() / denominator).powi(2);
    [v, s, trim, sigma_a]
}

/// pbrt-v3's `LogI0` past 12 (Pharr 2016, *The Implementation of a Hair
/// Scattering Model*, pbrt-v3's `src/materials/hair.cpp`), which
/// `shaders/lib/chiang.wgsl` is written after, in f64: x + ½(−ln 2π +
/// ln(1/x) + 1/(8x)).
fn log_i0_asymptotic(x: f64) -> f64 {
    x + 0.5 * (-(2.0 * PI).ln() + (1.0 / x).ln() + 1.0 / (8.0 * x))
}

/// `plait::chiang::fibre` equals the paper's closed forms within 1e-4
/// relative at β = 0.1 … 0.9, where the terms in β²⁰ and β²² matter (5.372 ·
/// 0.9²² ≈ 0.53 of s's 2.7). The fibre tests stay near β 0.3, where those
/// terms are below 1e-10; and `log_bessel_i0` past 12 equals pbrt-v3's
/// form within 1e-5 (the term in 1/(8x) is 5e-3 at x = 12.5). Kills, in
/// `shaders/lib/chiang.wgsl`, `+ 5.372 · pow(β_n, 22)` → `−`, the trim's
/// `1 + exp(−π/s)` → `−` and π → 1.1π in it (s ≈ 2.7 at β 0.9, where the
/// trim is 1.6; at β 0.3 it is 1 + 2e-11), `1/(8x)` → `0.9/(8x)`, and the
/// floor 1e-6 on a colour channel before its logarithm ×0.9 / ×1.1 (66:40:
/// σ_a of a black channel 1.5 % off).
#[test]
fn chiang_fibre_constants_match_the_paper_at_high_roughness() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/chiang_fibre.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (4, 4)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let bytes = prepared.read_buffer("constants").expect("constants");
    let got: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let mut failures = Vec::new();
    for (k, beta) in [0.1, 0.3, 0.6, 0.9].into_iter().enumerate() {
        let want = closed_form(beta, 0.5);
        for (c, name) in ["v", "s", "trim", "σ_a"].into_iter().enumerate() {
            let g = got[4 * k + c] as f64;
            if (g - want[c]).abs() > 1e-4 * want[c].abs() {
                failures.push(format!("β {beta}: {name} {g}, closed form {}", want[c]));
            }
        }
    }
    for (k, x) in [12.5, 15.0, 20.0, 30.0, 50.0, 80.0, 120.0, 200.0]
        .into_iter()
        .enumerate()
    {
        let (g, w) = (got[16 + k] as f64, log_i0_asymptotic(x));
        if (g - w).abs() > 1e-5 * w.max(1.0) {
            failures.push(format!("ln I0({x}) {g}, pbrt-v3 {w}"));
        }
    }
    // σ_a of a channel outside (0, 1]: 0 and 1e-7 as 1e-6 (the floor the
    // shader's comment states), 2 as 1 (no absorption); 1.05e-6 as itself.
    for (k, colour) in [0.0f64, 1e-7, 2.0, 1.05e-6].into_iter().enumerate() {
        let (g, w) = (
            got[24 + k] as f64,
            closed_form(0.3, colour.clamp(1e-6, 1.0))[3],
        );
        if (g - w).abs() > 1e-4 * w.max(1e-9) {
            failures.push(format!(
                "σ_a of colour {colour}: {g}, the floored closed form {w}"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
