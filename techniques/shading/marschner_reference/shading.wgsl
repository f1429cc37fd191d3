// plait::shading::marschner_reference — the Marschner model of
// plait::shading::marschner evaluated per fragment, without tables: the
// ground truth the tables are measured against (Halén & Wester 2007 §3.2.2.1,
// the complete model). Same module (plait::marschner), same params, same
// angles and the same assembly (`combine`), so any difference between the two
// images is the tables' resolution, half-float storage and TRT's absorption
// taken at its roots' mean path length.
#define_import_path plait::shading::marschner_reference

#import plait::frame::frame
#import plait::chiang::sigma_a_from_color
#import plait::marschner::{Model, model, hair_angles, longitudinal, azimuthal, cos_theta_d, combine, absorption_of, uniform_response}

// The model's params by the technique's names (techniques/shading/
// marschner_model.toml), the same values the table pass gets; the form and
// the fibre description's β_n (σa from the colour) are the shading point's.
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
    marschner_form: i32,
    chiang_beta_n: f32,
}
@group(1) @binding(20) var<uniform> shading_params: ShadingParams;

fn params_model() -> Model {
    let p = shading_params;
    return model(
        vec3<f32>(p.marschner_shift_r, p.marschner_shift_tt, p.marschner_shift_trt),
        vec3<f32>(p.marschner_width_r, p.marschner_width_tt, p.marschner_width_trt),
        p.marschner_ior,
        p.marschner_absorption,
        p.marschner_caustic_limit,
    );
}

fn hair_direct(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let p = shading_params;
    let m = params_model();
    let sigma_a = absorption_of(m, p.marschner_form, sigma_a_from_color(base, p.chiang_beta_n));
    let a = hair_angles(tangent, to_light, to_eye);
    let cos_td = cos_theta_d(a.x, a.y);
    let lobes = longitudinal(m, a.x, a.y);
    let n = azimuthal(m, a.z, cos_td, sigma_a);
    return combine(lobes, n.r, n.tt, n.trt, cos_td, a.x, base, frame.hair_shading.x, p.marschner_form, p.marschner_specular_gain);
}

// Under a uniform environment: the model's own response,
// ∫ S cos θi dωi (plait::marschner::uniform_response) — the same fibre the
// key light sees, as the chiang technique's hair_uniform is.
fn hair_uniform(tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let p = shading_params;
    let m = params_model();
    let sigma_a = absorption_of(m, p.marschner_form, sigma_a_from_color(base, p.chiang_beta_n));
    let sin_o = dot(normalize(tangent), to_eye);
    return uniform_response(m, sin_o, sigma_a, base, frame.hair_shading.x, p.marschner_form, p.marschner_specular_gain);
}
