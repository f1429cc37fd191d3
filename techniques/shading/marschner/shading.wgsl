// plait::shading::marschner — Marschner R / TT / TRT from lookup tables
// (Halén & Wester 2007 §5.8, after Nguyen & Donnelly 2005). The tables are
// made once by the `marschner_tables` pass (shaders/passes/marschner_tables.wgsl)
// from plait::marschner, the model the per-fragment reference
// (plait::shading::marschner_reference) evaluates directly; this provider
// reads M_R, M_TT, M_TRT and cos θd at (sin θi, sin θr), then the clear
// N_TT, N_TRT and their path lengths at (cos φ, cos θd), both with bilinear
// filtering, evaluates N_R exactly (square roots only) and applies the hair
// colour's absorption per channel — no inverse trigonometry per fragment,
// as §5.8 asks.
#define_import_path plait::shading::marschner

#import plait::frame::{frame, linear_sampler}
#import plait::chiang::sigma_a_from_color
#import plait::marschner::{model, slice, reflection, hair_angles, table_coordinate, combine, absorption_of, uniform_response}

struct ShadingParams {
    // The lobes' gain (1: the model).
    marschner_specular_gain: f32,
    marschner_shift_r: f32,
    marschner_shift_tt: f32,
    marschner_shift_trt: f32,
    marschner_width_r: f32,
    marschner_width_tt: f32,
    marschner_width_trt: f32,
    marschner_ior: f32,
    marschner_absorption: f32,
    marschner_caustic_limit: f32,
    marschner_form: i32,
    chiang_beta_n: f32,
}
@group(1) @binding(20) var<uniform> shading_params: ShadingParams;
// rgba16float: M_R, M_TT, M_TRT, cos θd at (sin θi, sin θr).
@group(1) @binding(21) var marschner_m: texture_2d<f32>;
// rgba16float: clear N_TT, N_TRT and their path lengths at (cos φ, cos θd).
@group(1) @binding(22) var marschner_n: texture_2d<f32>;

fn hair_direct(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let p = shading_params;
    let a = hair_angles(tangent, to_light, to_eye);
    let m_size = f32(textureDimensions(marschner_m).x);
    let m_uv = vec2<f32>(table_coordinate(a.x, -1.0, 1.0, m_size), table_coordinate(a.y, -1.0, 1.0, m_size));
    let m = textureSampleLevel(marschner_m, linear_sampler, m_uv, 0.0);
    let cos_td = m.a;
    let n_size = f32(textureDimensions(marschner_n).x);
    let n_uv = vec2<f32>(table_coordinate(a.z, -1.0, 1.0, n_size), table_coordinate(cos_td, 0.0, 1.0, n_size));
    let n = textureSampleLevel(marschner_n, linear_sampler, n_uv, 0.0);
    let fibre = model(vec3<f32>(0.0), vec3<f32>(1.0), p.marschner_ior, p.marschner_absorption, p.marschner_caustic_limit);
    let sigma_a = absorption_of(fibre, p.marschner_form, sigma_a_from_color(base, p.chiang_beta_n));
    let n_r = reflection(a.z, slice(p.marschner_ior, cos_td));
    let n_tt = n.x * exp(-sigma_a * n.z);
    let n_trt = n.y * exp(-sigma_a * n.w);
    return combine(m.rgb, n_r, n_tt, n_trt, cos_td, a.x, base, frame.hair_shading.x, p.marschner_form, p.marschner_specular_gain);
}

// Under a uniform environment: the model's own response, ∫ S cos θi dωi
// (plait::marschner::uniform_response), as marschner_reference's.
fn hair_uniform(tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let p = shading_params;
    let m = model(
        vec3<f32>(p.marschner_shift_r, p.marschner_shift_tt, p.marschner_shift_trt),
        vec3<f32>(p.marschner_width_r, p.marschner_width_tt, p.marschner_width_trt),
        p.marschner_ior,
        p.marschner_absorption,
        p.marschner_caustic_limit,
    );
    let sigma_a = absorption_of(m, p.marschner_form, sigma_a_from_color(base, p.chiang_beta_n));
    let sin_o = dot(normalize(tangent), to_eye);
    return uniform_response(m, sin_o, sigma_a, base, frame.hair_shading.x, p.marschner_form, p.marschner_specular_gain);
}
