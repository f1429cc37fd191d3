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

/// `cos_power_integral` as `shaders/lib/kajiya_kay.wgsl` computes it, step
/// by step in f32 (each operation rounded as the shader's is): x = p/2 raised
/// by four steps of Γ(z+1) = zΓ(z), then the series 1 − u/8 + u²/128 +
/// 5u³/1024 − 21u⁴/32768 in u = 1/x, Horner's order.
fn cos_power_integral_f32(p: f32) -> f32 {
    let mut x = 0.5 * p.max(0.0);
    let mut scale = 1.0f32;
    for _ in 0..4 {
        scale *= (x + 1.0) / (x + 0.5);
        x += 1.0;
    }
    let u = 1.0 / x;
    let series =
        1.0 + u * (-1.0 / 8.0 + u * (1.0 / 128.0 + u * (5.0 / 1024.0 - u * 21.0 / 32768.0)));
    std::f32::consts::PI.sqrt() * scale * series * (1.0 / x.sqrt())
}

/// The f32 values of `cos_power_integral` (the fixture of the test above,
/// p = 0 … 47) are its formula's own f32 arithmetic
/// ([`cos_power_integral_f32`]) within 2 units in the last place (measured
/// on lavapipe: 0 at p = 0, at most 2, at p = 15, 27, 28 and 31 — the
/// GPU's division and inverseSqrt are not all correctly rounded). The
/// series' last term, 21u⁴/32768, is below the series' truncation error
/// (the next term, 1.5e-6 at p = 0), so no comparison with the true
/// integral can see it; the f32 arithmetic can: at p = 0 (u = ¼) it is
/// 2.5e-6 of the series, and the coefficient ×1/1.1 moves the f32 result by
/// 3 ulps (3.1415977 → 3.1415985 in the CPU's f32; p = 1 … 4 and 6 by 1
/// ulp, none past 6), one more than the tolerance. Kills, in
/// `shaders/lib/kajiya_kay.wgsl`, 41:92 (32768 → 36044.8).
#[test]
fn kajiya_kay_cos_power_integral_is_its_f32_formula() {
    const ULPS: i32 = 2;
    let (_lock, gpu) = open_gpu();
    let scene = SceneData::load(Some(&repo_root().join("examples/scenes/small.toml")))
        .expect("the small scene loads");
    let pipeline = repo_root().join("tests/fixtures/kk_integral.toml");
    let prepared = prepare(&gpu, &pipeline, &[], &scene, (4, 4)).expect("the fixture prepares");
    prepared.render_unchecked().expect("renders");
    let bytes = prepared.read_buffer("integrals").expect("integrals");
    let mut failures = Vec::new();
    for (p, c) in bytes.chunks_exact(4).enumerate() {
        let got = f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
        let want = cos_power_integral_f32(p as f32);
        // Positive finite f32s: the bit patterns' difference counts ulps.
        let ulps = got.to_bits() as i32 - want.to_bits() as i32;
        if p < 8 {
            eprintln!("p {p}: {got} against {want}, {ulps} ulps");
        }
        if ulps.abs() > ULPS {
            failures.push(format!(
                "p {p}: {got}, its f32 formula {want} ({ulps} ulps)"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
