// plait::lighting::ambient — everything but the key light as a uniform
// environment of radiance L_a (the scene's `ambient`; docs/formats.md,
// "Light and units"), reflected by the energy-normalized Kajiya-Kay fibre
// of plait::kajiya_kay: its diffuse part kd/π² integrates over the sphere
// (∫ cos θi dωi = π²) to kd · base · L_a exactly; its specular cone to
// ks · L_a · ∫cos^p(θi − θc) cos²θi dθi / ∫cos^p, taken in the narrow-cone
// limit ks · L_a · cos²θc, where the cone's longitudinal angle θc has
// cos θc = sin θ′ (θ′ the tangent-to-eye angle with the scene's shift).
#define_import_path plait::lighting::ambient

#import plait::frame::frame

fn hair_environment(world: vec3<f32>, tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    let s = frame.hair_shading;
    let theta_eye = acos(clamp(dot(normalize(tangent), to_eye), -1.0, 1.0)) + s.w;
    let cone = sin(theta_eye);
    return frame.ambient.rgb * (base * s.x + vec3<f32>(s.y * cone * cone));
}
