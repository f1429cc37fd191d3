// plait::chiang — the fibre model of Chiang, Bitterli, Tappan & Burley 2016
// ("A Practical and Controllable Hair and Fur Model for Production Path
// Tracing", EGSR / CGF 35(2)), §3–4, in the form pbrt-v3 and Mitsuba 3's
// `hair` BSDF evaluate it, the cuticle tilt's sign turned for plait's
// root-to-tip tangent (tests/fibre.rs holds this file to Mitsuba's values at
// scale_tilt −α, as plait's export writes it).
//
// For an eye ray entering the fibre at offset h (sin γo = h):
//   S·cos θi = Σ_{p=0..2} M_p(θi, θo^p) A_p(h) N_p(φ − Φ(p, h)) + M_3 A_3 / 2π
// - M_p: d'Eon et al. 2011's longitudinal lobe with variance v_p from β_m
//   (§4.1: v = (0.726 β_m + 0.812 β_m² + 3.7 β_m²⁰)², v_1 = v/4, v_2 = v_3 = 4v),
//   θo rotated by the cuticle tilt α (+2α for R, −α for TT, −4α for TRT,
//   pbrt-v3's rotation by 2^k α with its sign turned: see `longitudinal_lobes`);
// - A_p: Fresnel at entry f, A_0 = f, A_1 = (1 − f)² T, A_2 = A_1 f T, and the
//   p ≥ 3 remainder A_3 = A_2 f T / (1 − f T), with T = exp(−σ_a · 2 cos γt
//   / cos θt) (§4);
// - N_p: the logistic of scale s = √(π/8)(0.265 β_n + 1.194 β_n² + 5.372 β_n²²)
//   trimmed to [−π, π] (§4.1), around Φ(p, h) = 2p γt − 2γo + pπ.
// This is M A N per unit irradiance: d'Eon's M_p is normalized over
// cos θo dθo, so a white fibre gives ∫ (S·cos θi) dωo = 1 (pbrt's furnace).
//
// A pixel sees a sub-pixel strand across its whole width, so the shading
// point returns the mean over h ∈ [−1, 1]: ½∫ S dh, by the midpoint rule in
// γo = asin h (dh = cos γo dγo), `samples` points. M_p does not depend on h
// and is evaluated once. The mean is even in φ (A_p is even in h, Φ odd, the
// logistic even), so φ ∈ [0, π] from cos φ suffices.
#define_import_path plait::chiang

#import plait::marschner::hair_angles

const PI: f32 = 3.14159265358979;
const DEGREES: f32 = 0.0174532925199433;
// The mean over h: midpoint points in γo. 64 points differ from 512 by at
// most 1.3 % at β_n 0.3 and 6.4 % at β_n 0.15 (the param's lower bound),
// wherever the lobe is above 1 % of its peak (tests/fibre.rs measures it);
// the logistic's width in γ shrinks with β_n, the points' spacing does not.
const CHIANG_SAMPLES: i32 = 64;

struct Fibre {
    // Longitudinal variance v of R (d'Eon's M_p), from β_m.
    v: f32,
    // Logistic scale s of N_p, from β_n.
    s: f32,
    // 1 / (CDF(π) − CDF(−π)): the logistic's trim to [−π, π], once per fibre.
    trim: f32,
    // Cuticle tilt α, radians.
    alpha: f32,
    // Index of refraction η.
    eta: f32,
    // σ_a per unit fibre radius, per channel.
    sigma_a: vec3<f32>,
}

// β_n's polynomial of Chiang 2016 §4.2 (the denominator of σ_a's mapping).
fn colour_denominator(beta_n: f32) -> f32 {
    let b = beta_n;
    let b2 = b * b;
    return 5.969 - 0.215 * b + 2.532 * b2 - 10.73 * b2 * b + 5.574 * b2 * b2 + 0.245 * b2 * b2 * b;
}

// σ_a from the hair colour by Chiang 2016 §4.2: (ln c / denominator(β_n))²,
// the same formula as plait::mitsuba::sigma_a_from_color. That mapping is
// defined for c ∈ (0, 1]: a channel of 0 is taken as 1e-6 (σ_a 5.3 at β_n
// 0.3: a TT of 1e-5 of white's) and one above 1 as 1 (no absorption; more
// light than a clear fibre has no σ_a). Scenes keep hair colours in [0, 1].
fn sigma_a_from_color(color: vec3<f32>, beta_n: f32) -> vec3<f32> {
    let d = log(clamp(color, vec3<f32>(1e-6), vec3<f32>(1.0))) / colour_denominator(beta_n);
    return d * d;
}

// The model's constants from the user's params (§4.1, §4.2).
fn fibre(beta_m: f32, beta_n: f32, tilt_degrees: f32, eta: f32, color: vec3<f32>) -> Fibre {
    let b2 = beta_m * beta_m;
    let b20 = pow(beta_m, 20.0);
    let v_root = 0.726 * beta_m + 0.812 * b2 + 3.7 * b20;
    let s = sqrt(PI / 8.0) * (0.265 * beta_n + 1.194 * beta_n * beta_n + 5.372 * pow(beta_n, 22.0));
    let trim = 1.0 / (1.0 / (1.0 + exp(-PI / s)) - 1.0 / (1.0 + exp(PI / s)));
    return Fibre(v_root * v_root, s, trim, tilt_degrees * DEGREES, eta, sigma_a_from_color(color, beta_n));
}

// I0(x), the modified Bessel function, by its series (pbrt-v3's 10 terms).
fn bessel_i0(x: f32) -> f32 {
    var value = 0.0;
    var x2i = 1.0;
    var factorial = 1.0;
    var four_i = 1.0;
    for (var i = 0; i < 10; i++) {
        if (i > 1) {
            factorial *= f32(i);
        }
        value += x2i / (four_i * factorial * factorial);
        x2i *= x * x;
        four_i *= 4.0;
    }
    return value;
}

// ln I0(x); the asymptotic form above 12, where the series loses terms.
fn log_bessel_i0(x: f32) -> f32 {
    if (x > 12.0) {
        return x + 0.5 * (-log(2.0 * PI) + log(1.0 / x) + 1.0 / (8.0 * x));
    }
    return log(bessel_i0(x));
}

// d'Eon et al. 2011's M_p of variance v; the log form for small v, where
// sinh(1/v) and I0 overflow f32.
fn longitudinal(cos_i: f32, cos_o: f32, sin_i: f32, sin_o: f32, v: f32) -> f32 {
    let a = cos_i * cos_o / v;
    let b = sin_i * sin_o / v;
    if (v <= 0.1) {
        return exp(log_bessel_i0(a) - b - 1.0 / v + 0.6931 + log(1.0 / (2.0 * v)));
    }
    return exp(-b) * bessel_i0(a) / (sinh(1.0 / v) * 2.0 * v);
}

// Unpolarized Fresnel reflectance entering a dielectric of index η from air.
fn fresnel_dielectric(cos_i_in: f32, eta: f32) -> f32 {
    let cos_i = clamp(cos_i_in, 0.0, 1.0);
    let sin_t = sqrt(max(0.0, 1.0 - cos_i * cos_i)) / eta;
    let cos_t = sqrt(max(0.0, 1.0 - sin_t * sin_t));
    let r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (r_par * r_par + r_perp * r_perp);
}

// The logistic of scale s trimmed to [−π, π], at x wrapped into [−π, π].
fn trimmed_logistic(f: Fibre, x_in: f32) -> f32 {
    let x = abs(x_in - 2.0 * PI * round(x_in / (2.0 * PI)));
    let e = exp(-x / f.s);
    return f.trim * e / (f.s * (1.0 + e) * (1.0 + e));
}

// M_0..M_3 at (θi, θo): θo rotated by +2α (R), −α (TT), −4α (TRT), not for
// p ≥ 3. M_p peaks where the rotated θo is −θi, so R peaks at θo + θi = −2α:
// towards the root, with θ measured towards the tip along plait's tangent
// (root to tip). α > 0 is a cuticle whose scales point to the tip, whose
// surface leans towards the root: Marschner et al. 2003's shift, and plait's
// `marschner` (α_R < 0). pbrt-v3/v4 and Mitsuba 3 rotate by −2α, α, 4α about
// their fibre axis, the curve's parametric direction: for curves written
// root first that is the other side, so plait's export hands Mitsuba −α
// (crates/plait/src/mitsuba/write.rs, scripts/mitsuba/tilt_side.py).
fn longitudinal_lobes(f: Fibre, sin_i: f32, sin_o: f32) -> vec4<f32> {
    let cos_i = sqrt(max(0.0, 1.0 - sin_i * sin_i));
    let cos_o = sqrt(max(0.0, 1.0 - sin_o * sin_o));
    let tilt = vec3<f32>(2.0, -1.0, -4.0) * f.alpha;
    let sin_op = sin_o * cos(tilt) + cos_o * sin(tilt);
    let cos_op = abs(cos_o * cos(tilt) - sin_o * sin(tilt));
    return vec4<f32>(
        longitudinal(cos_i, cos_op.x, sin_i, sin_op.x, f.v),
        longitudinal(cos_i, cos_op.y, sin_i, sin_op.y, 0.25 * f.v),
        longitudinal(cos_i, cos_op.z, sin_i, sin_op.z, 4.0 * f.v),
        longitudinal(cos_i, cos_o, sin_i, sin_o, 4.0 * f.v),
    );
}

// Σ_p A_p(h) N_p at one offset h = sin γo, each lobe weighted by its M_p;
// `lobes` switches lobes off for the tests (1 on, 0 off, per p).
fn offset_term(f: Fibre, m: vec4<f32>, lobes: vec4<f32>, sin_o: f32, phi: f32, gamma_o: f32) -> vec3<f32> {
    let h = sin(gamma_o);
    let cos_o = sqrt(max(0.0, 1.0 - sin_o * sin_o));
    let sin_t = sin_o / f.eta;
    let cos_t = sqrt(max(0.0, 1.0 - sin_t * sin_t));
    // The slice's effective index (Bravais), as Chiang §4 and pbrt-v3 take it.
    let eta_p = sqrt(f.eta * f.eta - sin_o * sin_o) / cos_o;
    let sin_gt = clamp(h / eta_p, -1.0, 1.0);
    let cos_gt = sqrt(max(0.0, 1.0 - sin_gt * sin_gt));
    let gamma_t = asin(sin_gt);
    let t = exp(-f.sigma_a * (2.0 * cos_gt / cos_t));
    let fr = fresnel_dielectric(cos_o * cos(gamma_o), f.eta);
    let a1 = (1.0 - fr) * (1.0 - fr) * t;
    let a2 = a1 * fr * t;
    let a3 = a2 * fr * t / (vec3<f32>(1.0) - t * fr);
    var sum = vec3<f32>(lobes.x * m.x * fr * trimmed_logistic(f, phi + 2.0 * gamma_o));
    sum += lobes.y * m.y * a1 * trimmed_logistic(f, phi - (2.0 * gamma_t - 2.0 * gamma_o + PI));
    sum += lobes.z * m.z * a2 * trimmed_logistic(f, phi - (4.0 * gamma_t - 2.0 * gamma_o + 2.0 * PI));
    sum += lobes.w * m.w * a3 / (2.0 * PI);
    return sum;
}

// The h-averaged S·cos θi of the fibre along `tangent` (unit), from the light
// to the eye: radiance towards the eye per unit irradiance, `samples` points.
fn chiang_lobes(f: Fibre, tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, lobes: vec4<f32>, samples: i32) -> vec3<f32> {
    let a = hair_angles(tangent, to_light, to_eye);
    return chiang_at(f, a.x, a.y, acos(a.z), lobes, samples);
}

// The same at the angles themselves: sin θi, sin θo and φ ∈ [0, π] (the
// dual-scattering tables integrate over them; plait::dual_scattering).
fn chiang_at(f: Fibre, sin_i: f32, sin_o: f32, phi: f32, lobes: vec4<f32>, samples: i32) -> vec3<f32> {
    let m = longitudinal_lobes(f, sin_i, sin_o);
    let step = PI / f32(samples);
    var sum = vec3<f32>(0.0);
    for (var k = 0; k < samples; k++) {
        let gamma_o = -0.5 * PI + (f32(k) + 0.5) * step;
        sum += cos(gamma_o) * offset_term(f, m, lobes, sin_o, phi, gamma_o);
    }
    return 0.5 * step * sum;
}

// All lobes at the shading point's quadrature.
fn chiang_radiance(f: Fibre, tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>) -> vec3<f32> {
    return chiang_lobes(f, tangent, to_light, to_eye, vec4<f32>(1.0), CHIANG_SAMPLES);
}

// The radiance the fibre sends towards the eye per unit radiance of a
// uniform environment, ∫ (S·cos θi) dωi over every light direction. M_p
// integrates to 1 over θi (d'Eon's normalization, whatever the tilt does to
// θo) and each N_p to 1 over φ, so what is left is the mean over h of the
// lobes' attenuations: ½∫ Σ_p A_p(h, θo) dh, the albedo of the fibre seen
// from the eye (A_p depend on the eye's θo alone, as pbrt-v3 and Mitsuba
// evaluate them). tests/chiang_uniform.rs holds it to the brute-force
// integral of chiang_radiance over the sphere.
fn chiang_albedo(f: Fibre, sin_o: f32, samples: i32) -> vec3<f32> {
    let cos_o = sqrt(max(0.0, 1.0 - sin_o * sin_o));
    let sin_t = sin_o / f.eta;
    let cos_t = sqrt(max(0.0, 1.0 - sin_t * sin_t));
    let eta_p = sqrt(f.eta * f.eta - sin_o * sin_o) / cos_o;
    let step = PI / f32(samples);
    var sum = vec3<f32>(0.0);
    for (var k = 0; k < samples; k++) {
        let gamma_o = -0.5 * PI + (f32(k) + 0.5) * step;
        let sin_gt = clamp(sin(gamma_o) / eta_p, -1.0, 1.0);
        let cos_gt = sqrt(max(0.0, 1.0 - sin_gt * sin_gt));
        let t = exp(-f.sigma_a * (2.0 * cos_gt / cos_t));
        let fr = fresnel_dielectric(cos_o * cos(gamma_o), f.eta);
        let a1 = (1.0 - fr) * (1.0 - fr) * t;
        let a2 = a1 * fr * t;
        let a3 = a2 * fr * t / (vec3<f32>(1.0) - t * fr);
        sum += cos(gamma_o) * (vec3<f32>(fr) + a1 + a2 + a3);
    }
    return 0.5 * step * sum;
}

// chiang_albedo along `tangent` (unit) towards `to_eye`, at the shading
// point's quadrature.
fn chiang_uniform(f: Fibre, tangent: vec3<f32>, to_eye: vec3<f32>) -> vec3<f32> {
    return chiang_albedo(f, dot(tangent, to_eye), CHIANG_SAMPLES);
}
