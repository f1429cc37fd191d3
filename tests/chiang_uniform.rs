//! `shading = "chiang"` under a uniform environment: what `lighting =
//! "ambient"` reflects is the shading point's `hair_uniform`, for chiang the
//! fibre's albedo seen from the eye (plait::chiang::chiang_albedo: the mean
//! over h of Σ_p A_p). Held here to the brute-force integral of the same
//! fibre's radiance over every light direction, on the GPU
//! (tests/fixtures/chiang_uniform.wgsl), for white, blond, dark brown and
//! black hair at 16 eye angles.

use plait_tests::fixture_texels;

const COLOURS: [&str; 4] = ["white", "blond", "dark brown", "black"];
const ANGLES: usize = 16;

/// The albedo within 1 % (plus 1e-4 absolute for black hair's tiny
/// values) of the integral at every eye angle and channel: the integral's
/// midpoint grid and d'Eon's normalization of M_p leave less than that
/// (measured below). Without the p ≥ 3 remainder the white fibre's albedo
/// falls far below the integral and the test fails; so does a Fresnel taken
/// at the light's angle.
#[test]
fn the_albedo_is_the_sphere_integral_of_the_fibre() {
    let texels = fixture_texels("chiang_uniform.toml", (ANGLES as u32, 8), &["fibre"]).remove(0);
    let mut worst = 0.0f64;
    let mut failures = Vec::new();
    for (c, colour) in COLOURS.iter().enumerate() {
        let integral: Vec<[f32; 4]> = texels[c * ANGLES..(c + 1) * ANGLES].to_vec();
        let albedo: Vec<[f32; 4]> = texels[(4 + c) * ANGLES..(5 + c) * ANGLES].to_vec();
        let show = |v: &[[f32; 4]]| {
            v.iter()
                .map(|t| format!("{:.4}", t[0]))
                .collect::<Vec<_>>()
                .join(" ")
        };
        println!("{colour:>10} integral (red): {}", show(&integral));
        println!("{colour:>10} albedo   (red): {}", show(&albedo));
        for i in 0..ANGLES {
            for ch in 0..3 {
                let (a, b) = (f64::from(albedo[i][ch]), f64::from(integral[i][ch]));
                let error = (a - b).abs() / b.max(1e-6);
                if (a - b).abs() > 1e-4 {
                    worst = worst.max(error);
                }
                if (a - b).abs() > 0.01 * b + 1e-4 {
                    failures.push(format!(
                        "{colour}, eye angle {i}, channel {ch}: albedo {a:.5}, integral {b:.5}"
                    ));
                }
            }
        }
    }
    println!("largest relative difference: {worst:.4}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
