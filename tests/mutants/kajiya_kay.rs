//! `shading/kajiya_kay`: the specular normalization of `shaders/lib/kajiya_kay.wgsl`.

use plait::session::{SceneData, prepare};
use plait_tests::{open_gpu, repo_root};

/// Wallis's integrals ∫_{-π/2}^{π/2} cos^p x dx in f64: π at p = 0, 2 at
/// p = 1, and I(p) = (p − 1)/p · I(p − 2).
fn wallis(p: usize) -> f64 {
    match p {
        0 => std::f64::consts::PI,
        1 => 2.0,
        _ => (p as f64 - 1.0) / p as f64 * wallis(p - 2),
    }
}

/// `cos_power_integral` (the specular cone's ∫cos^p, by four steps of
/// Γ(z+1) = zΓ(z) and an asymptotic series in 1/x, x = p/2 + 4) equals
/// Wallis's integrals within 4e-6 relative at every integer p from 0 to 47
/// (the series' next term, 399/(262144x⁵), is 1.5e-6 at p = 0). Kills, in
/// `shaders/lib/kajiya_kay.wgsl`, ±10 % on the series' coefficients 1/8,
/// 1/128 and 5/1024 (3e-3, 5e-5 and 8e-6 at p = 0) — the fibre tests read
/// the normalization only through a furnace bound and one fibre's closed
/// form at one exponent. The last coefficient, 21/32768 (2.5e-6 at p = 0),
/// is below what an f32 probe can tell apart ±10 %.
#[test]
fn kajiya_kay_cos_power_integral_matches_wallis() {
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/kk_integral.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (4, 4)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let bytes = prepared.read_buffer("integrals").expect("integrals");
    let mut failures = Vec::new();
    let mut worst = 0.0f64;
    for (p, c) in bytes.chunks_exact(4).enumerate() {
        let got = f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64;
        let error = (got / wallis(p) - 1.0).abs();
        worst = worst.max(error);
        if error > 4e-6 {
            failures.push(format!(
                "p {p}: {got}, Wallis {}, relative error {error:e}",
                wallis(p)
            ));
        }
    }
    eprintln!("worst relative error {worst:e}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
