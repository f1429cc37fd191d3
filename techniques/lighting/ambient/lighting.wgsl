// plait::lighting::ambient — everything but the key light as a uniform
// environment of radiance L_a (the scene's `ambient`; docs/formats.md,
// "Light and units"), reflected by the chosen fibre: the shading point's
// `hair_uniform` is its radiance towards the eye per unit radiance of a
// uniform environment (Kajiya-Kay's closed form, or Chiang's albedo seen
// from the eye), so the environment lights the same fibre as the key light.
#define_import_path plait::lighting::ambient

#import plait::frame::frame
#import plait::shading::shade_uniform

fn hair_environment(world: vec3<f32>, tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    return frame.ambient.rgb * shade_uniform(tangent, to_eye, base);
}
