// plait::hair_direct — the shading provider a hair pass's `shading` param
// names (`#ifdef SHADING_<NAME>`): the radiance a strand reflects towards the
// eye per unit key-light colour, before any shadowing. A new provider is one
// module in shaders/lib/shading/ plus one line here.
#define_import_path plait::hair_direct

#ifdef SHADING_KAJIYA_KAY
#import plait::shading::kajiya_kay::hair_direct
#else ifdef SHADING_MARSCHNER
#import plait::shading::marschner::hair_direct
#else ifdef SHADING_MARSCHNER_REFERENCE
#import plait::shading::marschner_reference::hair_direct
#else
#import plait::shading::kajiya_kay::hair_direct
#endif

fn shade_direct(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    return hair_direct(tangent, to_light, to_eye, base);
}
