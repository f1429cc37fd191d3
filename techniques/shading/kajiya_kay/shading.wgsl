// plait::shading::kajiya_kay — the Kajiya-Kay strand model (Halén & Wester
// 2007 §3.2.1) under the key light, energy-normalized
// (`plait::kajiya_kay::kajiya_kay_radiance`): diffuse kd/π² tinted by the
// hair, an untinted specular cone normalized by its exponent, both times
// cos θi = sin(T, L). Its four numbers are the scene's `hair_shading`.
#define_import_path plait::shading::kajiya_kay

#import plait::frame::frame
#import plait::kajiya_kay::{kajiya_kay_radiance, kajiya_kay_uniform}

fn hair_direct(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let s = frame.hair_shading;
    return kajiya_kay_radiance(tangent, to_light, to_eye, base, s.x, s.y, s.z, s.w);
}

// Under a uniform environment (`lighting = "ambient"`): the closed form of
// plait::kajiya_kay::kajiya_kay_uniform with the same four numbers.
fn hair_uniform(tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let s = frame.hair_shading;
    return kajiya_kay_uniform(tangent, to_eye, base, s.x, s.y, s.w);
}
