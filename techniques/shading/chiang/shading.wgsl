// plait::shading::chiang — Chiang et al. 2016's fibre model (plait::chiang,
// shaders/lib/chiang.wgsl) under the key light: the mean over the strand's
// width of M_p A_p N_p, p = 0, 1, 2 and the p ≥ 3 remainder, σ_a from the
// hair colour by Chiang 2016 §4.2. Its params are the technique's
// (techniques/shading/chiang/technique.toml), their ranges in
// crates/plait-passes/src/shading.rs.
#define_import_path plait::shading::chiang

#import plait::chiang::{fibre, chiang_radiance, chiang_uniform}

struct ShadingParams {
    chiang_beta_m: f32,
    chiang_beta_n: f32,
    chiang_tilt: f32,
    chiang_eta: f32,
}
@group(1) @binding(20) var<uniform> shading_params: ShadingParams;

fn hair_direct(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let p = shading_params;
    let f = fibre(p.chiang_beta_m, p.chiang_beta_n, p.chiang_tilt, p.chiang_eta, base);
    return chiang_radiance(f, tangent, to_light, to_eye);
}

// Under a uniform environment (`lighting = "ambient"`): the fibre's albedo
// seen from the eye (plait::chiang::chiang_albedo), so the ambient light is
// reflected by the same fibre as the key light's — Kajiya-Kay's closed form
// here once put the environment's light on a chiang fibre through the
// scene's kd and ks, which the path tracer's fibre does not have.
fn hair_uniform(tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let p = shading_params;
    let f = fibre(p.chiang_beta_m, p.chiang_beta_n, p.chiang_tilt, p.chiang_eta, base);
    return chiang_uniform(f, normalize(tangent), to_eye);
}
