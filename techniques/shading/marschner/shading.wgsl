// plait::shading::marschner — Marschner R / TT / TRT from lookup tables
// (Halén & Wester 2007 §5.8, after Nguyen & Donnelly 2005). The tables are
// made once by the `marschner_tables` pass (shaders/passes/marschner_tables.wgsl)
// from plait::marschner, the model the per-fragment reference
// (plait::shading::marschner_reference) evaluates directly; this provider
// reads M_R, M_TT, M_TRT and cos θd at (sin θi, sin θr), then N_R, N_TT,
// N_TRT at (cos φ, cos θd), both with bilinear filtering — no inverse
// trigonometry per fragment, as §5.8 asks.
#define_import_path plait::shading::marschner

#import plait::frame::{frame, linear_sampler}
#import plait::kajiya_kay::kajiya_kay_uniform
#import plait::marschner::{hair_angles, table_coordinate, combine}

struct ShadingParams {
    // The lobes' gain against Kajiya-Kay's diffuse term (§5.8 adds it).
    marschner_specular_gain: f32,
}
@group(1) @binding(20) var<uniform> shading_params: ShadingParams;
// rgba16float: M_R, M_TT, M_TRT, cos θd at (sin θi, sin θr).
@group(1) @binding(21) var marschner_m: texture_2d<f32>;
// rgba16float: N_R, N_TT, N_TRT at (cos φ, cos θd).
@group(1) @binding(22) var marschner_n: texture_2d<f32>;

fn hair_direct(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let a = hair_angles(tangent, to_light, to_eye);
    let m_size = f32(textureDimensions(marschner_m).x);
    let m_uv = vec2<f32>(table_coordinate(a.x, -1.0, 1.0, m_size), table_coordinate(a.y, -1.0, 1.0, m_size));
    let m = textureSampleLevel(marschner_m, linear_sampler, m_uv, 0.0);
    let cos_td = m.a;
    let n_size = f32(textureDimensions(marschner_n).x);
    let n_uv = vec2<f32>(table_coordinate(a.z, -1.0, 1.0, n_size), table_coordinate(cos_td, 0.0, 1.0, n_size));
    let n = textureSampleLevel(marschner_n, linear_sampler, n_uv, 0.0);
    return combine(m.rgb * n.rgb, cos_td, a.x, base, frame.hair_shading.x, shading_params.marschner_specular_gain);
}

// Under a uniform environment: Kajiya-Kay's closed form
// (plait::kajiya_kay::kajiya_kay_uniform), as Halén & Wester 2007 §5.7 light
// Marschner-shaded hair by the environment through Kajiya-Kay irradiance
// maps. The lobes' own integral over the sphere has no closed form; it is
// not what this model's environment term is (stated in docs/formats.md).
fn hair_uniform(tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let s = frame.hair_shading;
    return kajiya_kay_uniform(tangent, to_eye, base, s.x, s.y, s.w);
}
