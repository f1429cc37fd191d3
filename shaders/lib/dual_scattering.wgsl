// plait::dual_scattering — Zinke, Yuksel, Weber & Keyser 2008, "Dual
// Scattering Approximation for Fast Multiple Scattering in Hair" (ACM TOG
// 27(3)), §4–5, on the Chiang 2016 fibre (plait::chiang).
//
// The fibre's averages (§4.1 eq. 6, §4.2 eq. 11, the shifts and variances
// of eqs. 9–10) are one table, per light inclination sin θi and absorption
// σ_a, made once by the `dual_scattering_tables` pass:
//   a = (ā_f, ā_b, α_f, α_b), b = (β_f², β_b², 0, 0)
// - ā_f, ā_b: the part of the light reaching a fibre that it sends into the
//   forward (|φ| > π/2) and backward half, ∫ (S cos θi) cos θo dθo dφ over
//   that half — the fibre's energy split in the shading point's own units
//   (docs/formats.md, "Light and units": a white Chiang fibre has
//   ∫ S cos θi dωo ≈ 1), so a white fibre has ā_f + ā_b = its furnace
//   albedo (tests/dual_scattering.rs);
// - α, β²: the mean and variance of θh = (θi + θo)/2 over that half, weighted
//   by the scattered energy — the moments of the fibre's own longitudinal
//   distribution, which the paper's energy-weighted lobe shifts and widths
//   approximate for Marschner's Gaussian lobes.
// The back-scattering of §4.2 (A_b eq. 14, Δ_b eq. 16, σ_b eq. 17) is formed
// from them where it is used (a few operations per channel).
#define_import_path plait::dual_scattering

const PI: f32 = 3.14159265358979;

// Table axes: x = sin θi over [−1, 1] at texel centres; y: row j of N
// holds v = σ_a/(1 + σ_a) = j/N, so row 0 is the clear fibre (σ_a = 0)
// and the top row σ_a = N − 1 (15 at 16 rows; black hair is 0.44). Rows
// at texel centres, v = (j + ½)/N, put the first at σ_a = 0.032: every
// lighter σ_a (blond's 0.0008 / 0.005 / 0.024) read that row's averages,
// and A_b, which grows as 1/(1 − ā_f²), came out 2–3× too small (ds43).
fn absorption_at(v: f32) -> f32 {
    return v / (1.0 - v);
}

// The texture coordinate of σ_a on the y axis of a table of `rows` rows.
// Beyond the top row (σ_a > rows − 1, a fibre that transmits nothing)
// the sampler clamps to it.
fn absorption_uv(sigma_a: f32, rows: f32) -> f32 {
    return (sigma_a / (1.0 + sigma_a) * rows + 0.5) / rows;
}

struct BackScattering {
    // A_b: average back-scattered attenuation, up to three scatterings (eq. 14).
    attenuation: f32,
    // Δ_b: its longitudinal shift (eq. 16), radians of θh.
    shift: f32,
    // σ_b²: its longitudinal variance (eq. 17 squared).
    variance: f32,
}

// §4.2 from the averages; d_b the back-scattering density factor (eq. 17's).
fn back_scattering(a: vec4<f32>, b: vec2<f32>, d_b: f32) -> BackScattering {
    let af = a.x;
    let ab = a.y;
    let af2 = af * af;
    let ab2 = ab * ab;
    let ab3 = ab2 * ab;
    let one = 1.0 - af2;
    let one3 = one * one * one;
    let attenuation = ab * af2 / one + ab3 * af2 / one3;
    let shift = a.w * (1.0 - 2.0 * ab2 / (one * one)) + a.z * (2.0 * one * one + 4.0 * af2 * ab2) / one3;
    let bf = sqrt(b.x);
    let bb = sqrt(b.y);
    let sigma = (1.0 + d_b * af2) * (ab * sqrt(2.0 * b.x + b.y) + ab3 * sqrt(2.0 * b.x + 3.0 * b.y)) / (ab + ab3 * (2.0 * bf + 3.0 * bb));
    return BackScattering(attenuation, shift, sigma * sigma);
}

// The part of A_b (eq. 14) the first m strands behind the point return:
// A_1 = ā_b Σ_{k=1..∞} ā_f^2k sums one back-scattering by the strand k deep
// (crossed k times each way), so m strands give ā_b ā_f² (1 − ā_f^2m)/(1 − ā_f²)
// = A_1 · (1 − ā_f^2m); the same factor is taken for A_3 (three
// back-scatterings: its paths reach deeper, so this keeps more of it than a
// slab of m strands would). m → ∞: Zinke's A_b; m = 0: none. The floor
// keeps pow's log finite when ā_f is 0.
fn behind_fraction(af: f32, m: f32) -> f32 {
    return 1.0 - pow(max(af * af, 1e-30), m);
}

// A unit-area Gaussian of variance v at x.
fn gaussian(x: f32, v: f32) -> f32 {
    return exp(-0.5 * x * x / v) / sqrt(2.0 * PI * v);
}

// A longitudinal lobe as a density over θo for the energy measure
// cos θo dθo: the Gaussian in θh (dθo = 2 dθh) over 2 cos θo, so its energy
// is the Gaussian's mass inside |θo| < π/2 whatever its width. (Zinke's
// 1/cos²θd, in Marschner's units, loses 13 % of a σ_b-wide lobe's energy
// this way: measured by tests/dual_scattering.rs before this form.) The
// floor 0.01 on cos θo only touches an eye within 0.6° of the strand's axis.
fn lobe(theta_h: f32, shift: f32, variance: f32, cos_o: f32) -> f32 {
    return gaussian(theta_h - shift, variance) / (2.0 * max(cos_o, 0.01));
}
