// plait::shading::marschner_reference — the Marschner model of
// plait::shading::marschner evaluated per fragment, without tables: the
// ground truth the tables are measured against (Halén & Wester 2007 §3.2.2.1,
// the complete model). Same module (plait::marschner), same params, same
// angles and the same assembly (`combine`), so any difference between the two
// images is the tables' resolution and half-float storage.
#define_import_path plait::shading::marschner_reference

#import plait::frame::frame
#import plait::kajiya_kay::kajiya_kay_uniform
#import plait::marschner::{model, hair_angles, longitudinal, azimuthal, cos_theta_d, combine}

// The model's params by the technique's names (techniques/shading/
// marschner_model.toml), the same values the table pass gets.
struct ShadingParams {
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
}
@group(1) @binding(20) var<uniform> shading_params: ShadingParams;

fn hair_direct(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let p = shading_params;
    let m = model(
        vec3<f32>(p.marschner_shift_r, p.marschner_shift_tt, p.marschner_shift_trt),
        vec3<f32>(p.marschner_width_r, p.marschner_width_tt, p.marschner_width_trt),
        p.marschner_ior,
        p.marschner_absorption,
        p.marschner_caustic_limit,
    );
    let a = hair_angles(tangent, to_light, to_eye);
    let cos_td = cos_theta_d(a.x, a.y);
    let lobes = longitudinal(m, a.x, a.y) * azimuthal(m, a.z, cos_td);
    return combine(lobes, cos_td, a.x, base, frame.hair_shading.x, p.marschner_specular_gain);
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
