// plait::shading::kajiya_kay — the Kajiya-Kay strand model (Halén & Wester
// 2007 §3.2.1) under the key light: diffuse kd·sin(T,L) tinted by the hair,
// an untinted specular lobe with the shifted highlight of
// `plait::kajiya_kay`. Its four numbers are the scene's `hair_shading`.
#define_import_path plait::shading::kajiya_kay

#import plait::frame::frame
#import plait::kajiya_kay::kajiya_kay

fn hair_direct(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let s = frame.hair_shading;
    let kk = kajiya_kay(tangent, to_light, to_eye, s.x, s.y, s.z, s.w);
    return base * kk.x + vec3<f32>(kk.y);
}
