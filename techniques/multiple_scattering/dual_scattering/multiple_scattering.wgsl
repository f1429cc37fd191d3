// plait::multiple_scattering::dual_scattering — Zinke et al. 2008 §4–5
// (techniques/multiple_scattering/dual_scattering/technique.toml) on the
// Chiang fibre: per channel, the tables' averages at (sin θi, σ_a), σ_a from
// the hair colour by Chiang 2016 §4.2 (plait::chiang, as the shading does).
// Returned: what single scattering leaves out, per unit irradiance —
//   v · d_b · A_b(m) · g(θh − Δ_b, σ_b²)/(2 cos θo) · N_b
//   + (1 − v) · T_f · d_f · ( (ā_f + ā_b) · g(θh − α_f, β_f² + σ̄_f²)/(2 cos θo) / 2π
//                                      + d_b · A_b(m) · g(θh − Δ_b, σ_b² + σ̄_f²)/(2 cos θo) · N_b )
// v the self-shadow visibility (the direct fraction), T_f = ā_f^n,
// σ̄_f² = n β_f², n the strand count toward the light, N_b = 1/π over the
// backward half (|φ| < π/2), 0 elsewhere; A_b(m) = (1 − ā_f^2m) · A_b, the
// back-scattering of the m strands that lie behind the point along the
// light's ray (technique.toml: Zinke's A_b sums an unbounded slab of hair
// behind the point; a groom is a shell of a few strands on a head).
#define_import_path plait::multiple_scattering::dual_scattering

#import plait::frame::linear_sampler
#import plait::chiang::sigma_a_from_color
#import plait::marschner::hair_angles
#import plait::self_shadow::strands_along_light
#import plait::dual_scattering::{absorption_uv, back_scattering, behind_fraction, lobe}

struct MultipleScatteringParams {
    dual_scattering_front_density: f32,
    dual_scattering_back_density: f32,
    chiang_beta_n: f32,
    dual_scattering_count_behind: f32,
}
@group(1) @binding(70) var<uniform> multiple_scattering_params: MultipleScatteringParams;
// rgba16float: ā_f, ā_b, α_f, α_b at (sin θi, σ_a/(1+σ_a)).
@group(1) @binding(71) var dual_scattering_a: texture_2d<f32>;
// rgba16float: β_f², β_b² at the same.
@group(1) @binding(72) var dual_scattering_b: texture_2d<f32>;

const PI: f32 = 3.14159265358979;

// One channel's added radiance per unit irradiance: the tables' energies
// are the shading point's (S·cos θi integrated), so no further cos θi.
fn channel(sin_i: f32, sigma_a: f32, theta_h: f32, cos_o: f32, backward: f32, n: f32, m: f32, v: f32) -> f32 {
    let size = vec2<f32>(textureDimensions(dual_scattering_a));
    // Texel centres span [0.5, size − 0.5]: x = sin θi over [−1, 1]; y by
    // plait::dual_scattering's rows (row 0 the clear fibre).
    let uv = vec2<f32>(0.5 + 0.5 * sin_i, absorption_uv(sigma_a, size.y));
    let a = textureSampleLevel(dual_scattering_a, linear_sampler, uv, 0.0);
    let b = textureSampleLevel(dual_scattering_b, linear_sampler, uv, 0.0).xy;
    let p = multiple_scattering_params;
    let back = back_scattering(a, b, p.dual_scattering_back_density);
    let d_b = p.dual_scattering_back_density;
    let attenuation = back.attenuation * behind_fraction(a.x, m);
    let local = d_b * attenuation * lobe(theta_h, back.shift, back.variance, cos_o) * backward / PI;
    let spread = n * b.x;
    let transmitted = pow(a.x, n);
    let global_front = (a.x + a.y) * lobe(theta_h, a.z, b.x + spread, cos_o) / (2.0 * PI);
    let global_back = d_b * attenuation * lobe(theta_h, back.shift, back.variance + spread, cos_o) * backward / PI;
    let global = (1.0 - v) * transmitted * p.dual_scattering_front_density * (global_front + global_back);
    return v * local + global;
}

fn hair_multiple_scattering(world: vec3<f32>, tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>, hair_visibility: f32) -> vec3<f32> {
    let angles = hair_angles(tangent, to_light, to_eye);
    let theta_i = asin(angles.x);
    let theta_o = asin(angles.y);
    let theta_h = 0.5 * (theta_i + theta_o);
    let cos_o = cos(theta_o);
    // |φ| < π/2: the backward half, where back-scattered light leaves.
    let backward = select(0.0, 1.0, angles.z > 0.0);
    // n, the strands toward the light, and m, those behind `world` along
    // the light's ray before an opaque object (the light-view maps are
    // depth-tested against the head) — past the point's own strand — from
    // one read of the self-shadow technique's light texel (point.toml,
    // `hair_strands_along_light`).
    let counts = strands_along_light(world);
    let n = counts.x;
    // count_behind 0: Zinke's unbounded hair (10⁶ strands: ā_f^2m is 0).
    let m = select(1e6, counts.y, multiple_scattering_params.dual_scattering_count_behind > 0.5);
    let sigma = sigma_a_from_color(base, multiple_scattering_params.chiang_beta_n);
    let v = hair_visibility;
    return vec3<f32>(
        channel(angles.x, sigma.x, theta_h, cos_o, backward, n, m, v),
        channel(angles.x, sigma.y, theta_h, cos_o, backward, n, m, v),
        channel(angles.x, sigma.z, theta_h, cos_o, backward, n, m, v),
    );
}
