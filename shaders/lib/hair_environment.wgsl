// plait::hair_environment — the lighting provider a hair pass's `lighting`
// param names (`#ifdef LIGHTING_<NAME>`): light from everything but the key
// light, unshadowed by it (the occlusion provider darkens it). A new provider
// is one module in shaders/lib/lighting/ plus one line here.
#define_import_path plait::hair_environment

#ifdef LIGHTING_AMBIENT
#import plait::lighting::ambient::hair_environment
#else ifdef LIGHTING_IRRADIANCE_MAPS
#import plait::lighting::irradiance_maps::hair_environment
#else ifdef LIGHTING_ENVIRONMENT_REFERENCE
#import plait::lighting::environment_reference::hair_environment
#else
#import plait::lighting::ambient::hair_environment
#endif

fn shade_environment(world: vec3<f32>, tangent: vec3<f32>, to_eye: vec3<f32>, base: vec3<f32>) -> vec3<f32> {
    return hair_environment(world, tangent, to_eye, base);
}
